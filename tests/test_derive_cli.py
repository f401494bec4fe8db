"""The command line run in-process through its real parser."""
import json
from pathlib import Path

import pytest
from cli_run import run

SURF = Path(__file__).resolve().parents[1] / "surfaces"




def test_derive_json_keys_and_values(capsys):
    code, out, _ = run(capsys, "derive", "--alpha", "30", "--beta", "10", "--mu-alpha", "0.1",
                       "--mu-beta", "0.2", "--json", "--directions", "36")
    assert code == 0
    d = json.loads(out)
    for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus", "admissible", "self_locking",
              "directions"):
        assert k in d
    assert d["mu_a_plus"] == pytest.approx(0.185697, abs=1e-6)
    assert len(d["directions"]) == 36
    assert set(d["directions"][0]) >= {"psi_deg", "p", "tangential", "lateral"}


def test_derive_file_self_locking_reported_not_nan(capsys):
    code, out, _ = run(capsys, "derive", str(SURF / "self-locking.toml"), "--json")
    assert code == 0
    assert "NaN" not in out and "Infinity" not in out
    d = json.loads(out)
    assert d["mu_a_plus"] is None
    assert d["self_locking"] and d["self_locking"][0]["face"] == "alpha"


def test_derive_springs_agree_with_closed_form(capsys):
    code, out, _ = run(capsys, "derive", str(SURF / "wedge-asymmetric.toml"), "--method", "springs",
                       "--directions", "8", "--k-f", "inf", "--n-springs", "4096", "--json")
    assert code == 0
    d = json.loads(out)
    assert d["springs"]["max_relative_deviation_from_closed_form"] < 6e-4     # 3.7e-4 reached
    assert d["mu_a_plus"] == pytest.approx(0.185697, rel=2e-4)                 # 5.9e-5 reached


def test_derive_plot_written(tmp_path, capsys):
    png = tmp_path / "r.png"
    code, _, _ = run(capsys, "derive", str(SURF / "wedge-symmetric-30.toml"), "--contact", "windward",
                     "--plot", str(png))
    assert code == 0 and png.stat().st_size > 10_000
    assert not list(tmp_path.glob(".*part"))


@pytest.mark.parametrize("argv,msg", [
    (["--alpha", "95", "--beta", "10", "--mu-alpha", "0.1", "--mu-beta", "0.1"], "--alpha must be in (0, 90)"),
    (["--alpha", "30", "--beta", "10", "--mu-alpha", "-1", "--mu-beta", "0.1"], "--mu-alpha must be in [0"),
    (["--alpha", "30", "--beta", "10", "--mu-alpha", "0.1"], "missing --mu-beta"),
    ([], "no texture"),
])
def test_derive_errors_one_line(capsys, argv, msg):
    code, out, err = run(capsys, "derive", *argv)
    assert code == 1
    assert msg in err and err.count("\n") == 1 and "Traceback" not in err


def test_texture_file_errors(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text('[texture]\nkind="wedge"\nalpha_deg=30\nbeta_deg=10\nmu_alpha=0.1\nmu_beta=0.1\ncolour=1\n')
    code, _, err = run(capsys, "derive", str(bad))
    assert code == 1 and "unknown key texture.colour" in err
    bad.write_text('[texture]\nkind="wedge"\nalpha_deg=30\nmu_alpha=0.1\nmu_beta=0.1\n')
    code, _, err = run(capsys, "derive", str(bad))
    assert code == 1 and "missing key texture.beta_deg" in err


def _wedge_stl(tmp_path, angle=0.0):
    import trimesh

    from asperity.surface.wedge_surfaces import wedge_mesh
    from asperity.texture.wedges import WedgeTexture
    mesh, _ = wedge_mesh(WedgeTexture(30, 30, 0.2, 0.2, height=1e-3), periods=3, angle_deg=angle)
    path = tmp_path / "wedges.stl"
    trimesh.Trimesh(mesh.vertices * 1e3, mesh.faces, process=False).export(path)
    return path


def test_derive_surface_file_json_keys(capsys, tmp_path):
    path = _wedge_stl(tmp_path, angle=25.0)
    code, out, _ = run(capsys, "derive", str(path), "--unit", "mm", "--mu", "0.2", "--detrend",
                       "none", "--json", "--directions", "36")
    assert code == 0
    d = json.loads(out)
    assert d["n_facets"] == 12 and d["n_undefined"] == 0
    assert d["principal_direction_deg"] == pytest.approx(25.0, abs=1e-4)   # float32 STL
    # symmetric 30/30 wedge, mu 0.2, across the ridges: H(0.2, 30 deg) and H(0.2, -30 deg) averaged
    import math
    t = math.tan(math.radians(30))
    h = 0.5 * ((0.2 + t) / (1 - 0.2 * t) + (0.2 - t) / (1 + 0.2 * t))
    assert d["mu_a_plus"] == pytest.approx(h, rel=1e-5)
    assert d["texture"]["kind"] == "mesh" and d["texture"]["n_skipped_vertical"] == 0


def test_derive_surface_errors_are_one_line(capsys, tmp_path):
    path = _wedge_stl(tmp_path)
    code, out, err = run(capsys, "derive", str(path))
    assert code == 1 and "unit" in err and "Traceback" not in err and len(err.strip().splitlines()) == 1
    code, _, err = run(capsys, "derive", str(path), "--unit", "mm", "--mu", "-1")
    assert code == 1 and "mu" in err and len(err.strip().splitlines()) == 1
    code, _, err = run(capsys, "derive", str(path), "--unit", "mm", "--rest-level", "1.0")
    assert code == 1 and "--rest-level" in err
    code, _, err = run(capsys, "derive", "--alpha", "30", "--beta", "10", "--mu-alpha", "0.1",
                       "--mu-beta", "0.1", "--mu", "0.2")
    assert code == 1 and "--mu" in err


def test_derive_surface_friction_map_and_plot(capsys, tmp_path):
    import numpy as np
    z = np.zeros((6, 5))
    np.save(tmp_path / "flat.npy", z)
    np.save(tmp_path / "mu.npy", np.full((6, 5), 0.25))
    code, out, _ = run(capsys, "derive", str(tmp_path / "flat.npy"), "--unit", "um",
                       "--pixel-size", "1", "--friction-map", str(tmp_path / "mu.npy"), "--json",
                       "--plot", str(tmp_path / "flat.png"), "--directions", "8")
    assert code == 0
    d = json.loads(out)
    assert all(x["tangential"] == pytest.approx(0.25, rel=1e-12) for x in d["directions"])
    assert (tmp_path / "flat.png").stat().st_size > 10_000


def test_progress_bar_draws_on_a_terminal_only():
    import io

    from asperity.progress import QUIET_SECONDS, chunks, progress_bar, report

    class Tty(io.StringIO):
        def isatty(self):
            return True
    bar = progress_bar("facets", stream=Tty())
    with bar:
        bar(0.1)                                # within the first half second: silent
        assert not bar.shown
        bar.start -= QUIET_SECONDS
        bar(0.5)
        report(1.0, "locking share")            # library code reports to the active bar
        assert [(a, b) for a, b in chunks(10, 4)] == [(0, 4), (4, 8), (8, 10)]
    text = bar.stream.getvalue()
    assert "50.0 %" in text and "100.0 %" in text and "locking share" in text
    assert "s left" in text and text.endswith("\r")
    quiet = progress_bar("facets")          # pytest's stderr is not a terminal
    quiet.start -= QUIET_SECONDS
    quiet(0.5)
    assert not quiet.shown
    report(0.5)                             # no active bar: nothing happens
