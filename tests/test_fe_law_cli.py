"""``asperity law GAUGE --fric/--vfric/--vfriction FILE.f --abaqus-user FILE.inp`` (issue
27, items 1 and 2): self-contained fixed-form files that gfortran compiles against the
include stand-ins (72 columns enforced), a header holding the deck lines that
--abaqus-user writes, the JSON record of what was written, and bad input in one line
with nothing written."""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from cli_run import run, run_json
from fe_builds import library, needs_gfortran
from law_families import four_members

from asperity import derive, fit_derivation, write_gauge
from asperity.fe.fortran_harness import call_fric
from asperity.texture.wedges import WedgeTexture

ROUTINES = ("fric", "vfric", "vfriction")


@pytest.fixture(scope="module")
def star_gauge(tmp_path_factory):
    path = tmp_path_factory.mktemp("gauge") / "star.json"
    d = derive(WedgeTexture(30.0, 10.0, 0.1, 0.2), n_directions=360)
    write_gauge(path, fit_derivation(d, "star"))
    return path


def routine_files(tmp_path):
    return {r: tmp_path / f"{r}.f" for r in ROUTINES}


def test_writes_three_routines_and_the_deck(star_gauge, tmp_path, capsys):
    files = routine_files(tmp_path)
    deck = tmp_path / "deck.inp"
    d = run_json(capsys, "law", star_gauge, *(x for r in ROUTINES for x in
                                              (f"--{r}", files[r])), "--abaqus-user", deck)
    rec = d["abaqus_user"]
    assert rec["table_nodes"] >= 360 and 0.0 <= rec["max_table_error"] <= 1e-4
    assert [x["routine"] for x in rec["routines"]] == ["FRIC", "VFRIC", "VFRICTION"]
    assert all(0.0 < x["seconds"] < 60.0 for x in rec["routines"])
    assert rec["deck"]["routines"] == ["FRIC", "VFRIC", "VFRICTION"]
    inp = deck.read_text()
    for line in ("*FRICTION, USER, DEPVAR=3, PROPERTIES=3",
                 "*FRICTION, USER, DEPVAR=2, PROPERTIES=4",
                 "*FRICTION, USER=FRICTION, DEPVAR=2, PROPERTIES=4",
                 "*CONTACT PAIR, INTERACTION=TEXTURED", "*CONTACT PROPERTY ASSIGNMENT",
                 "*CONTACT FORMULATION, TYPE=PURE MASTER-SLAVE", "** *STEP, UNSYMM=YES"):
        assert line in inp.splitlines()
    for r, path in files.items():
        text = path.read_text()
        code = [x for x in text.splitlines() if x and x[0] not in "Cc*!"]
        assert max(len(x) for x in code) <= 72
        assert re.search(r"^      SUBROUTINE " + r.upper() + r"\(", text, re.IGNORECASE | re.MULTILINE)
        inc = "INCLUDE 'ABA_PARAM.INC'" if r == "fric" else "include 'vaba_param.inc'"
        assert inc in text
        block = text.split("C Input deck:\n")[1].split("\nC\n")[0]
        header = [x[4:] for x in block.splitlines()]
        section = next(x for x in inp.split("\n**\n") if f"user subroutine {r.upper()}" in x)
        assert header == section.splitlines()
        assert "State variables" in text and "Assumptions:" in text


@needs_gfortran
@pytest.mark.parametrize("routine", ROUTINES)
def test_written_routine_compiles_in_double_and_single(star_gauge, tmp_path, capsys, routine):
    path = tmp_path / f"{routine}.f"
    code, _, err = run(capsys, "law", star_gauge, f"--{routine}", path)
    assert code == 0, err
    library(path.read_text())
    if routine != "fric":
        library(path.read_text(), "single")


@needs_gfortran
def test_written_fric_slides_at_the_laws_force(star_gauge, tmp_path, capsys):
    """The command's FRIC, driven far along local direction 1 (law turned by PROPS(2)
    = 30 deg), gives PRESS p(-30 deg) as `asperity law --psi -30` prints it."""
    path = tmp_path / "fric.f"
    assert run(capsys, "law", star_gauge, "--fric", path)[0] == 0
    lib = library(path.read_text())
    ref = run_json(capsys, "law", star_gauge, "--psi", "-30")["p"]
    out = call_fric(lib, lm=0, tau=[0.0, 0.0], statev=np.zeros(3), dgam=[1.0, 0.0],
                    press=2.0, props=[1e6, 30.0, 1.0], nfdir=2)
    c, s = np.cos(np.radians(30.0)), np.sin(np.radians(30.0))
    expect = 2.0 * np.array([c * ref[0] - s * ref[1], s * ref[0] + c * ref[1]])
    assert out.tau == pytest.approx(expect, abs=2e-4)
    assert out.statev[2] == 1.0


def test_family_routine_reports_its_levels(tmp_path, capsys):
    gauge = tmp_path / "family.json"
    write_gauge(gauge, four_members())
    d = run_json(capsys, "law", gauge, "--vfric", tmp_path / "v.f")
    levels = d["abaqus_user"]["table_pressure_levels_Pa"]
    assert levels[0] == 1e6 and levels[-1] == 5e7 and levels == sorted(levels)
    assert "pressure levels" in (tmp_path / "v.f").read_text()


def bad(capsys, tmp_path, *argv):
    before = set(tmp_path.rglob("*"))
    code, out, err = run(capsys, "law", *argv)
    assert code == 1 and out == ""
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert set(tmp_path.rglob("*")) == before, "nothing may be written"
    return err


def test_bad_input_is_one_line_and_writes_nothing(star_gauge, tmp_path, capsys):
    f = tmp_path / "out.f"
    err = bad(capsys, tmp_path, tmp_path / "missing.json", "--fric", f)
    assert "missing.json" in err
    broken = tmp_path / "broken.json"
    broken.write_text("{not json")
    err = bad(capsys, tmp_path, broken, "--vfric", f, "--abaqus-user", tmp_path / "d.inp")
    assert "broken.json" in err
    err = bad(capsys, tmp_path, star_gauge, "--fric", tmp_path / "no" / "such" / "x.f")
    assert "--fric" in err
    copy = tmp_path / "g.json"
    copy.write_text(Path(star_gauge).read_text())
    err = bad(capsys, tmp_path, copy, "--vfriction", copy)
    assert "--vfriction" in err
    assert json.loads(copy.read_text())


def test_a_table_that_cannot_meet_the_bound_names_directions(star_gauge, tmp_path, capsys,
                                                               monkeypatch):
    """The table refuses a bound it cannot meet; the command says so in one line and
    writes none of its files (a bound of 1e-9 with at most 400 nodes stands in for a
    law whose 1e-4 table cannot be built)."""
    import asperity.fe.abaqus_fric as A
    import asperity.fe.table as T
    monkeypatch.setattr(T, "MAX_NODES", 400)
    monkeypatch.setattr(A, "law_table_of", lambda g, tol=1e-4: T.law_table(g, 1e-9))
    err = bad(capsys, tmp_path, star_gauge, "--fric", tmp_path / "a.f", "--abaqus-user",
              tmp_path / "a.inp")
    assert "cannot hold the force within 1e-09" in err and " deg " in err


def test_conventions_figure_draws(tmp_path):
    from asperity.fe.conventions_figure import draw
    path = draw(str(tmp_path / "conventions.png"))
    assert (tmp_path / "conventions.png").stat().st_size > 20_000 and path.endswith(".png")


def test_deck_lines_carry_the_models_properties(star_gauge, tmp_path, capsys):
    deck, f = tmp_path / "deck.inp", tmp_path / "fric.f"
    run_json(capsys, "law", star_gauge, "--fric", f, "--vfriction", tmp_path / "v.f",
             "--abaqus-user", deck, "--slip-stiffness", "2.5e11", "--law-angle", "-30",
             "--texture-side", "secondary", "--law-axis", "0", "1", "0.5")
    lines = deck.read_text().splitlines()
    fric = lines[lines.index("*FRICTION, USER, DEPVAR=3, PROPERTIES=3") + 1]
    assert [float(x) for x in fric.split(",")] == [2.5e11, -30.0, -1.0]
    vf = lines[lines.index("*FRICTION, USER=FRICTION, DEPVAR=2, PROPERTIES=4") + 1]
    assert [float(x) for x in vf.split(",")] == [0.0, 1.0, 0.5, -1.0]
    assert "placeholder" not in deck.read_text()
    head = [ln[2:] for ln in f.read_text().splitlines() if ln.startswith("C ")]
    assert "  2.5E+11, -30.0, -1.0" in head
    for flags, name in ((("--slip-stiffness", "0"), "--slip-stiffness"),
                        (("--law-angle", "400"), "--law-angle"),
                        (("--law-axis", "0", "0", "0"), "--law-axis")):
        err = bad(capsys, tmp_path, star_gauge, "--fric", tmp_path / "x.f", *flags)
        assert name in err


@pytest.mark.parametrize("outputs", [("fric",), ("vfric", "vfriction"), ("deck",),
                                     ("vfriction", "deck"), ("fric", "vfric", "vfriction",
                                                             "deck")])
def test_the_terminal_names_exactly_the_files_written(star_gauge, tmp_path, capsys, outputs):
    """Every "... written to PATH" line names a file now on disk holding what the line
    says, and every file written has its line: routines alone, the deck alone (FRIC's
    lines), and both."""
    argv = []
    for o in outputs:
        argv += (["--abaqus-user", tmp_path / "deck.inp"] if o == "deck"
                 else [f"--{o}", tmp_path / f"{o}.f"])
    code, out, err = run(capsys, "law", star_gauge, *argv)
    assert code == 0, err
    named = re.findall(r"^(.*) written to (.*)$", out, re.MULTILINE)
    assert sorted(p for _, p in named) == sorted(str(p) for p in tmp_path.iterdir())
    for what, path in named:
        text = Path(path).read_text()
        if what == "Abaqus input-deck lines":
            assert "*FRICTION, USER" in text
            routines = [o.upper() for o in outputs if o != "deck"] or ["FRIC"]
            assert re.findall(r"user subroutine (\w+)", text) == routines
        else:
            name = re.fullmatch(r"Abaqus (\w+) routine", what).group(1)
            assert re.search(rf"^      SUBROUTINE {name}\(", text,
                             re.IGNORECASE | re.MULTILINE), what


def _arguments(source: str) -> set:
    """The dummy arguments of the SUBROUTINE statement of a fixed-form source (lower case)."""
    lines = source.splitlines()
    i = next(k for k, x in enumerate(lines) 
             if re.match(r"^      subroutine ", x, re.IGNORECASE))
    text = lines[i][6:]
    for x in lines[i + 1:]:
        if x[:1] in "Cc*!":
            continue
        if len(x) < 6 or x[5] == " ":
            break
        text += x[6:]
    inner = text[text.index("(") + 1:text.rindex(")")]
    return {a.strip().lower() for a in inner.split(",")}


def test_each_header_speaks_of_its_own_routines_arguments(star_gauge, tmp_path, capsys):
    """The Assumptions of each routine's header name arguments of that routine only:
    FRIC's (TAU, DGAM, LM, DDTDDG ...) in FRIC, the explicit ones (fStickForce, dirCosSl
    ...) in VFRIC and VFRICTION."""
    files = routine_files(tmp_path)
    run_json(capsys, "law", star_gauge, *(x for r in ROUTINES for x in (f"--{r}", files[r])))
    texts = {r: files[r].read_text() for r in ROUTINES}
    args = {r: _arguments(texts[r]) for r in ROUTINES}
    every = set().union(*args.values())
    for r, text in texts.items():
        block = text.split("C Assumptions:\n")[1].split("\n      ")[0]
        words = set(re.findall(r"\b(?:[A-Z][A-Z0-9]+|[a-z]+[A-Z]\w*)\b", block))
        named = {w for w in words if w.lower() in every}
        assert len(named) >= 4, (r, named)
        assert {w for w in named if w.lower() not in args[r]} == set(), r


@pytest.fixture(scope="module")
def conventions():
    from asperity.fe.conventions_figure import figure
    from asperity.io import pyplot
    fig = figure()
    yield fig
    pyplot().close(fig)


def _arrows(ax):
    """{colour (hex): (tail, head)} of the annotation arrows of ``ax``."""
    from matplotlib.colors import to_hex
    from matplotlib.text import Annotation
    return {to_hex(a.arrow_patch.get_edgecolor()): (np.array(a.xyann), np.array(a.xy))
            for a in ax.texts if isinstance(a, Annotation) and a.arrow_patch is not None}


def _filled(ax, colour):
    """The paths (data coordinates) of the patches and fills of ``colour`` in ``ax``."""
    from matplotlib.colors import to_hex
    out = [p.get_patch_transform().transform_path(p.get_path()) for p in ax.patches
           if to_hex(p.get_facecolor()) == colour]
    return out + [q for c in ax.collections if len(c.get_facecolor())
                  and to_hex(c.get_facecolor()[0]) == colour for q in c.get_paths()]


def _radius(poly, phi):
    """Distance from the origin to the closed polygon ``poly`` (dense, star-shaped) along phi."""
    ang = np.unwrap(np.arctan2(poly[:, 1], poly[:, 0]))
    r = np.hypot(poly[:, 0], poly[:, 1])
    return np.interp(np.mod(phi - ang[0], 2 * np.pi) + ang[0], ang, r)


def test_conventions_plan_view_draws_the_laws_force_on_c(conventions):
    """The plan view: C of the law turned to its +x axis (the green arrow: C reaches
    mu_a+ along it, mu_a- against it, mu_b+- across), and the force for sliding along t1
    (blue) on the boundary of C, where the dissipation p.t1 is largest (associated law),
    equal to R(theta) p(-theta) of the law as `law --psi` gives it."""
    from matplotlib.colors import to_hex

    from asperity.fe.conventions_figure import AXES
    from asperity.laws.sets import TruncatedEllipse
    from asperity.laws.walker_leine import associated
    ax = conventions.axes[2]
    arrows = _arrows(ax)
    (t0, t1), (g0, g1), (p0, p) = (arrows[to_hex(c)] for c in
                                    ("tab:blue", "tab:green", "tab:purple"))
    assert t0.tolist() == [0, 0] and g0.tolist() == [0, 0] and p0.tolist() == [0, 0]
    assert t1[1] == 0 and t1[0] > 0
    (path,) = _filled(ax, "#fdd0a2")
    poly = path.vertices
    th = math.atan2(g1[1], g1[0])
    for k, mu in enumerate(AXES):
        assert _radius(poly, th + (0, math.pi, math.pi / 2, -math.pi / 2)[k]) == \
            pytest.approx(mu, rel=1e-3)
    assert np.hypot(*p) == pytest.approx(_radius(poly, math.atan2(p[1], p[0])), rel=1e-3)
    assert p[0] >= (poly @ [1.0, 0.0]).max() * (1 - 1e-4)
    ref = associated(TruncatedEllipse(*AXES)).force(np.array([-th])).p[0]
    c, s = math.cos(th), math.sin(th)
    assert p == pytest.approx([c * ref[0] - s * ref[1], s * ref[0] + c * ref[1]], abs=1e-12)


def test_conventions_side_views_label_the_bodies_and_oppose_the_slip(conventions):
    """Each side view names the body it labels (the label lies on it), the slip of the
    secondary points along +t1 and the force on it against; the two views draw the bodies
    alike (the same outer faces: only the texture changes side); the three panels all
    show."""
    extents = []
    for ax in conventions.axes[:2]:
        top = max(q.get_extents().y1 for q in _filled(ax, "#9ecae1"))
        bottom = min(q.get_extents().y0 for q in _filled(ax, "#c9c9c9"))
        extents.append((top, bottom))         # the outer faces, away from the texture
        labels = {t.get_text(): t.get_position() for t in ax.texts}
        for label, colour in (("secondary (slave)", "#9ecae1"), ("main (master)", "#c9c9c9")):
            assert any(q.contains_point(labels[label]) for q in _filled(ax, colour)), label
        arrows = _arrows(ax)
        slip, force = (arrows[c][1] - arrows[c][0] for c in ("#1f77b4", "#d62728"))
        assert slip[0] > 0 and force[0] < 0 and slip[1] == force[1] == 0
    assert extents[0] == extents[1]
    boxes = [ax.get_position() for ax in conventions.axes]
    assert all(b.width > 0.2 and b.height > 0.5 for b in boxes)
    assert boxes[0].x1 <= boxes[1].x0 and boxes[1].x1 <= boxes[2].x0
