"""Studies, case by case (issue 12): every case's outputs equal the single-case API called
directly on files that hold the same inputs, the samples follow the seed and nothing
else, and the statistics are wired correctly (a closed-form probability of ratchet, the
Ishigami function's Sobol indices).  All in this process (workers = 0): the engine's
cluster paths are in test_study_engine.py."""
from __future__ import annotations

import math
import sqlite3
from pathlib import Path

import numpy as np
import pytest

from asperity import (
    assembly_friction,
    assess_assembly,
    derive,
    fit_derivation,
    load_assembly,
    load_surface,
    load_texture,
)
from asperity.study import sampling
from asperity.study.run import run_study_file
from asperity.study.summary import sobol_indices, wilson

ROOT = Path(__file__).resolve().parents[1]
SURF = ROOT / "surfaces"


def write_study(tmp_path: Path, body: str, name: str = "s.toml") -> Path:
    p = tmp_path / name
    p.write_text(body.replace("SURF", str(SURF)))
    return p


def rows(folder: Path, cols: str = "*") -> list[tuple]:
    con = sqlite3.connect(folder / "study.sqlite")
    try:
        return con.execute(f"SELECT {cols} FROM cases ORDER BY case_id").fetchall()
    finally:
        con.close()


def table(folder: Path) -> list[dict]:
    con = sqlite3.connect(folder / "study.sqlite")
    con.row_factory = sqlite3.Row
    try:
        return [dict(r) for r in con.execute("SELECT * FROM cases ORDER BY case_id")]
    finally:
        con.close()


MC = """
[study]
kind = "monte-carlo"
samples = 12
seed = 7
stages = ["derive", "fit", "risk"]
texture = "SURF/wedge-asymmetric.toml"
assembly = "SURF/bushing-strip.toml"
directions = 36
law = "ellipse"

[parameters]
"texture.alpha_deg" = { distribution = "normal", mean = 30.0, sd = 2.0 }
"texture.mu_beta" = { distribution = "lognormal", median = 0.2, sigma = 0.2 }
"assembly.p" = { distribution = "truncated-normal", mean = 5e6, sd = 1e6, low = 3e6, high = 7e6 }
"loading.dT_max" = { distribution = "uniform", low = 60.0, high = 140.0 }
"""


def _toml_value(v):
    return repr(float(v)) if isinstance(v, float) else (f'"{v}"' if isinstance(v, str) else
                                                         repr(v))


def _edited(path: Path, changes: dict, out: Path) -> Path:
    """A copy of a TOML file with TABLE.KEY values replaced (written as repr(float), which
    TOML reads back to the same double)."""
    import tomllib
    data = tomllib.loads(path.read_text())
    for k, v in changes.items():
        t, key = k.split(".", 1)
        data.setdefault(t, {})[key] = v
    lines = []
    for k, v in data.items():
        if not isinstance(v, dict):
            lines.append(f"{k} = {_toml_value(v)}")
    for k, v in data.items():
        if isinstance(v, dict):
            lines.append(f"[{k}]")
            lines += [f"{kk} = {_toml_value(vv)}" for kk, vv in v.items()]
    out.write_text("\n".join(lines) + "\n")
    return out


def test_each_case_equals_the_single_case_api_on_files_with_its_inputs(tmp_path):
    run_study_file(write_study(tmp_path, MC), tmp_path / "out", workers=0)
    got = table(tmp_path / "out")
    assert len(got) == 12 and all(r["status"] == "ok" for r in got), got[0]
    for r in got:
        i = r["case_id"]
        tex_file = _edited(SURF / "wedge-asymmetric.toml",
                           {k: r[k] for k in ("texture.alpha_deg", "texture.mu_beta")},
                           tmp_path / f"t{i}.toml")
        asm_file = _edited(SURF / "bushing-strip.toml",
                           {k: r[k] for k in ("assembly.p", "loading.dT_max")},
                           tmp_path / f"a{i}.toml")
        tex = load_texture(tex_file)
        d = derive(tex, contact="all-faces", n_directions=36)
        for k in ("mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"):
            assert r[k] == d.axes[k], (i, k)
        assert r["anisotropy"] == d.anisotropy and r["principal_direction_deg"] == \
            d.principal_direction_deg
        fit = fit_derivation(d, kind="truncated-ellipse").fit
        assert r["fit_max_radial_error"] == fit.max_radial_error
        assert r["fit_holdout_angle_deg"] == fit.holdout_max_angle_deg
        asm = load_assembly(asm_file)
        out = assess_assembly(asm, assembly_friction(asm, tex))
        for k in ("mu_plus", "mu_minus", "dT_c_K", "margin", "drift_per_cycle_m",
                  "drift_after_cycles_m", "cycles_to_tolerance", "stabilised_at_cycle"):
            assert r[k] == out[k], (i, k, r[k], out[k])
        assert r["verdict"] == out["verdict"]


def test_files_study_reads_each_file_as_derive_does(tmp_path):
    rng = np.random.default_rng(3)
    for i in range(3):
        z = np.cumsum(rng.normal(size=(40, 50)), axis=1) * 0.05 * (1 + i)
        np.save(tmp_path / f"scan{i}.npy", z)
    study = write_study(tmp_path, """
[study]
kind = "files"
files = ["scan*.npy", "SURF/wedge-asymmetric.toml"]
unit = "um"
pixel_size = [1.0, 2.0]
mu = 0.15
max_slope = 4.0
stages = ["derive"]
directions = 48
""")
    s = run_study_file(study, tmp_path / "out", workers=0)
    got = table(tmp_path / "out")
    assert [Path(r["file"]).name for r in got] == ["scan0.npy", "scan1.npy", "scan2.npy",
                                                   "wedge-asymmetric.toml"]
    for r in got[:3]:
        d = derive(load_surface(r["file"], unit="um", pixel_size=(1.0, 2.0), mu=0.15,
                                max_slope=4.0), n_directions=48)
        assert r["principal_direction_deg"] == d.principal_direction_deg
        assert r["mu_a_plus"] == d.axes["mu_a_plus"] and r["anisotropy"] == d.anisotropy
    assert got[3]["mu_a_plus"] == pytest.approx(0.185697, abs=5e-7)   # SPEC.md check value
    ranked = [Path(r["file"]).name for r in s["ranking"]]
    aniso = {Path(r["file"]).name: r["anisotropy"] for r in got}
    assert ranked == sorted(aniso, key=lambda k: -aniso[k])          # no verdict: by anisotropy


def test_a_failing_case_is_stored_with_its_reason_and_the_study_goes_on(tmp_path):
    np.save(tmp_path / "good.npy", np.random.default_rng(1).normal(size=(20, 20)))
    (tmp_path / "bad.npy").write_bytes(b"not a surface at all")
    study = write_study(tmp_path, """
[study]
kind = "files"
files = ["*.npy"]
unit = "um"
pixel_size = 1.0
mu = 0.1
""")
    s = run_study_file(study, tmp_path / "out", workers=0)
    got = {Path(r["file"]).name: r for r in table(tmp_path / "out")}
    assert got["good.npy"]["status"] == "ok" and got["bad.npy"]["status"] == "failed"
    assert "bad.npy" in got["bad.npy"]["message"] and "\n" not in got["bad.npy"]["message"]
    assert s["completed"] == 1 and s["failed"] == 1 and s["failures"][0]["cases"] == 1


# ----------------------------------------------------------------------------- sampling

@pytest.mark.parametrize("kind", ["monte-carlo", "latin-hypercube", "sobol"])
def test_samples_follow_the_seed_only(kind):
    ps = [sampling.parse_parameter("texture.alpha_deg", {"distribution": "normal", "mean": 30,
                                                         "sd": 1.5}, kind),
          sampling.parse_parameter("loading.dT_max", {"distribution": "uniform", "low": 90,
                                                      "high": 140}, kind)]
    a = sampling.sample_matrix(kind, ps, 64, seed=5)
    b = sampling.sample_matrix(kind, ps, 64, seed=5)
    c = sampling.sample_matrix(kind, ps, 64, seed=6)
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)
    assert a.shape == ((64 * 4, 2) if kind == "sobol" else (64, 2))
    assert np.all((a[:, 1] >= 90) & (a[:, 1] <= 140))


def test_latin_hypercube_puts_one_sample_in_every_stratum():
    p = sampling.parse_parameter("loading.dT_max", {"distribution": "uniform", "low": 0.0,
                                                    "high": 1.0}, "latin-hypercube")
    x = sampling.sample_matrix("latin-hypercube", [p, p], 50, seed=2)
    for j in range(2):
        assert sorted(np.floor(x[:, j] * 50).astype(int)) == list(range(50))


@pytest.mark.parametrize("table,check", [
    ({"distribution": "normal", "mean": 3.0, "sd": 0.5}, lambda x: (x.mean(), x.std())),
    ({"distribution": "lognormal", "median": 2.0, "sigma": 0.3},
     lambda x: (np.median(x), np.log(x).std())),
    ({"distribution": "truncated-normal", "mean": 0.0, "sd": 1.0, "low": -0.5, "high": 2.0},
     lambda x: (x.min(), x.max())),
])
def test_distributions_have_their_moments(table, check):
    from scipy import stats
    p = sampling.parse_parameter("assembly.h", table, "monte-carlo")
    x = sampling.sample_matrix("monte-carlo", [p], 200_000, seed=11)[:, 0]
    a, b = check(x)
    if table["distribution"] == "normal":
        assert a == pytest.approx(3.0, abs=4 * 0.5 / math.sqrt(2e5)) and b == pytest.approx(
            0.5, rel=0.01)
    elif table["distribution"] == "lognormal":
        assert a == pytest.approx(2.0, rel=0.005) and b == pytest.approx(0.3, rel=0.01)
    else:
        assert -0.5 <= a < -0.499 and 1.999 < b <= 2.0
        m = stats.truncnorm.mean(-0.5, 2.0)
        assert x.mean() == pytest.approx(m, abs=4 * x.std() / math.sqrt(x.size))


def test_grid_is_the_cartesian_product_first_parameter_slowest():
    ps = [sampling.parse_parameter("texture.alpha_deg", {"values": [10.0, 20.0]}, "grid"),
          sampling.parse_parameter("texture.beta_deg", {"low": 5.0, "high": 15.0, "n": 3},
                                   "grid")]
    x = sampling.sample_matrix("grid", ps, None, 0)
    assert x.tolist() == [[10, 5], [10, 10], [10, 15], [20, 5], [20, 10], [20, 15]]


# ----------------------------------------------------------------------------- statistics

def test_probability_of_ratchet_covers_the_two_node_closed_form(tmp_path):
    """Two-node SPEC assembly (dT_c = 41.67 K) with dT_max uniform in [50, 150] K and
    dT_min = 0: it ratchets iff dT_max > 2 dT_c, so P = (150 - 2 dT_c) / 100."""
    study = write_study(tmp_path, """
[study]
kind = "monte-carlo"
samples = 3000
seed = 4
assembly = "SURF/two-node-spec.toml"
[parameters]
"loading.dT_max" = { distribution = "uniform", low = 50.0, high = 150.0 }
""")
    s = run_study_file(study, tmp_path / "out", workers=0)
    dT_c = 1.0e-1 * 100.0 * (1 / 1e6 + 2 / 5e5) / (1.2e-5 * 0.1)     # mu- N (1/k + 2/k_t)/(alpha l0)
    exact = (150.0 - 2 * dT_c) / 100.0
    p = s["p_ratchet"]
    assert p["low"] <= exact <= p["high"], (p, exact)
    assert p["high"] - p["low"] < 0.04
    assert set(s["verdicts"]) == {"ratchet", "shakedown"} and s["completed"] == 3000
    # the drift of every ratchet case is the SPEC closed form -alpha l0 (dT - 2 dT_c)
    got = rows(tmp_path / "out", '"loading.dT_max", drift_per_cycle_m, verdict')
    for dT, drift, verdict in got[:200]:
        want = -1.2e-5 * 0.1 * (dT - 2 * dT_c) if dT > 2 * dT_c else 0.0
        assert drift == pytest.approx(want, rel=1e-9, abs=1e-18)
        assert verdict == ("ratchet" if dT > 2 * dT_c else "shakedown")


@pytest.mark.parametrize("k,n", [(0, 10), (3, 10), (10, 10), (731, 1000)])
def test_wilson_interval_matches_scipy(k, n):
    from scipy.stats import binomtest
    ci = binomtest(k, n).proportion_ci(confidence_level=0.95, method="wilson")
    w = wilson(k, n)
    assert w["low"] == pytest.approx(ci.low, abs=1e-12)
    assert w["high"] == pytest.approx(ci.high, abs=1e-12)
    assert w["estimate"] == k / n


def test_ishigami_through_the_study_sobol_path_gives_its_known_indices():
    """Ishigami f = sin x1 + 7 sin^2 x2 + 0.1 x3^4 sin x1, x_i uniform on [-pi, pi]:
    S1 = (0.3139, 0.4424, 0), ST = (0.5576, 0.4424, 0.2437) (a = 7, b = 0.1)."""
    ps = [sampling.parse_parameter(f"texture.x{i}", {"distribution": "uniform",
                                                     "low": -math.pi, "high": math.pi}, "sobol")
          for i in range(3)]
    X = sampling.sample_matrix("sobol", ps, 4096, seed=3)
    Y = np.sin(X[:, 0]) + 7 * np.sin(X[:, 1]) ** 2 + 0.1 * X[:, 2] ** 4 * np.sin(X[:, 0])
    a, b = 7.0, 0.1
    V = a * a / 8 + b * math.pi ** 4 / 5 + b * b * math.pi ** 8 / 18 + 0.5
    V1 = 0.5 * (1 + b * math.pi ** 4 / 5) ** 2
    V2 = a * a / 8
    V13 = b * b * math.pi ** 8 * (1 / 18 - 1 / 50)
    exact_S1 = [V1 / V, V2 / V, 0.0]
    exact_ST = [(V1 + V13) / V, V2 / V, V13 / V]
    si = sobol_indices(Y, [p.name for p in ps], seed=1)
    for j, p in enumerate(ps):
        v = si[p.name]
        assert abs(v["S1"] - exact_S1[j]) <= v["S1_conf"], (p.name, v, exact_S1[j])
        assert abs(v["ST"] - exact_ST[j]) <= v["ST_conf"], (p.name, v, exact_ST[j])
        assert v["S1_conf"] < 0.05 and v["ST_conf"] < 0.05


def test_sobol_study_of_the_two_node_drift(tmp_path):
    """The two-node drift is -alpha l0 (dT - 2 dT_c) above the threshold: with dT_max and
    N both varied, dT_max carries most of the variance; the indices come with intervals."""
    study = write_study(tmp_path, """
[study]
kind = "sobol"
samples = 256
seed = 2
assembly = "SURF/two-node-spec.toml"
[parameters]
"loading.dT_max" = { distribution = "uniform", low = 100.0, high = 200.0 }
"assembly.N" = { distribution = "uniform", low = 90.0, high = 110.0 }
""")
    s = run_study_file(study, tmp_path / "out", workers=0, plot=True)
    assert s["cases"] == 256 * 4 and s["completed"] == 1024
    so = s["sobol"]
    assert so["loading.dT_max"]["ST"] > 0.8 > so["assembly.N"]["ST"]
    assert all(v["S1_conf"] > 0 and v["ST_conf"] > 0 for v in so.values())
    assert {Path(f).name for f in s["figures"]} == {"drift.png", "verdicts.png", "sobol.png"}
    md = (tmp_path / "out" / "summary.md").read_text()
    assert "Sobol indices" in md and "![sobol.png](sobol.png)" in md


def test_progress_is_reported_per_batch_up_to_the_whole_run(tmp_path, monkeypatch):
    """The study's bar sees one fraction per batch (of this run) and nothing from inside
    the cases (their own progress reports would draw over it)."""
    from asperity import progress
    seen = []
    monkeypatch.setattr(progress.progress_bar, "__call__",
                        lambda self, f, label=None: seen.append((f, label)))
    study = write_study(tmp_path, MC.replace('stages = ["derive", "fit", "risk"]',
                                             'stages = ["risk"]'))
    with progress.progress_bar("study"):
        run_study_file(study, tmp_path / "out", workers=0, batch_size=5)
    assert [round(f, 6) for f, _ in seen] == [0.0, round(5 / 12, 6), round(10 / 12, 6), 1.0]
    assert {label for _, label in seen} == {"study"}
    s = run_study_file(study, tmp_path / "out", workers=0)
    assert s["run"]["ran"] == 0 and s["sobol"] is None and s["p_ratchet"] is not None


def test_a_study_varying_the_loading_only_equals_the_api_too(tmp_path):
    """Such studies parse the assembly once per batch and replace its loading: the same
    Assembly as parsing the file with that loading."""
    study = write_study(tmp_path, """
[study]
kind = "latin-hypercube"
samples = 6
seed = 1
texture = "SURF/wedge-asymmetric.toml"
assembly = "SURF/bushing-strip.toml"
[parameters]
"loading.dT_max" = { distribution = "uniform", low = 10.0, high = 140.0 }
"loading.dT_min" = { distribution = "uniform", low = -20.0, high = 5.0 }
""")
    run_study_file(study, tmp_path / "out", workers=0)
    tex = load_texture(SURF / "wedge-asymmetric.toml")
    for r in table(tmp_path / "out"):
        asm = load_assembly(_edited(SURF / "bushing-strip.toml",
                                    {k: r[k] for k in ("loading.dT_max", "loading.dT_min")},
                                    tmp_path / f"a{r['case_id']}.toml"))
        out = assess_assembly(asm, assembly_friction(asm, tex))
        assert r["status"] == "ok", r["message"]
        for k in ("verdict", "dT_c_K", "margin", "drift_per_cycle_m", "cycles_to_tolerance"):
            assert r[k] == out[k], (k, r[k], out[k])
