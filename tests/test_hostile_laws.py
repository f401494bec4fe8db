"""Hostile input to the laws room (issue 11, classes 2, 3, 6): gauge files tampered field
by field (types, ranges, non-finite numbers, nesting, huge integers, a C or D that does not
belong to the data and fit report), bad flags of `asperity law` and `asperity fit`, and bad
calls of the public API.  Every one ends in one InputError line (exit 1 on the command
line); a valid file still reloads bit for bit."""
from __future__ import annotations

import copy
import json
import math

import numpy as np
import pytest
from cli_run import run
from hostile import SURF, assert_finite_output, assert_refused, cli

from asperity.errors import InputError
from asperity.friction.derive import derive
from asperity.laws import export, fitting, sets, summary, walker_leine
from asperity.laws.convex_set import ConvexSet
from asperity.laws.gauge_file import GaugeFileError, read_gauge, to_dict, write_gauge
from asperity.texture.wedges import WedgeTexture, load_texture


@pytest.fixture(scope="module")
def fitted():
    t = load_texture(SURF / "wedge-asymmetric.toml")
    d = derive(t, "all-faces", "closed-form", 72)
    return {"star": fitting.fit_derivation(d, "star"),
            "truncated-ellipse": fitting.fit_derivation(d, "truncated-ellipse"), "d": d}


def tamper(obj: dict, path: str, value):
    """A copy of ``obj`` with the field at ``path`` (``a.b[2][0]``) set to ``value``."""
    out = copy.deepcopy(obj)
    node, parts = out, path.replace("]", "").replace("[", ".").split(".")
    for part in parts[:-1]:
        node = node[int(part)] if isinstance(node, list) else node[part]
    last = parts[-1]
    if isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value
    return out


NUMBER_FIELDS = {
    "star": ["parameters.C.points[3][1]", "parameters.D.psi_rad[4]", "parameters.D.h[5]",
             "parameters.D.dh_dpsi[6]", "data.psi_rad[2]", "data.p[7][0]",
             "frame.principal_direction_deg", "fit.max_radial_error", "fit.min_dissipation"],
    "truncated-ellipse": ["parameters.mu_a_plus", "parameters.mu_a_minus", "parameters.mu_b_plus",
                          "parameters.mu_b_minus", "parameters.theta_rad", "data.p[1][1]",
                          "fit.rms_radial_error", "fit.C_min_turn_deg"],
}
#: what a hand edit may put in a number field
BAD_VALUES = ["0.2", True, None, [0.2], {"v": 0.2}, -1.0, 0.0, 5e-324, 1e300, -1e300, 10**400]


def cases():
    for kind, fields in NUMBER_FIELDS.items():
        for field in fields:
            for v in BAD_VALUES:
                yield kind, field, v


@pytest.mark.parametrize("kind,field,value", list(cases()))
def test_every_number_field_refuses_bad_values(fitted, tmp_path, kind, field, value):
    """Class 3 and 2: text, booleans, null, lists, tables, signs, zeros, subnormals and
    overflowing values in every kind of number field: refused, or (where the value is
    allowed, e.g. a negative angle) the law and the fit must still agree."""
    obj = tamper(to_dict(fitted[kind]), field, value)
    p = tmp_path / "g.json"
    p.write_text(json.dumps(obj))
    try:
        gl = read_gauge(p)
    except GaugeFileError as exc:
        assert "\n" not in str(exc) and str(p) in str(exc)
        return
    # accepted: then it is a usable law whose numbers are all finite
    f = gl.force(np.linspace(0, 2 * np.pi, 37))
    assert np.all(np.isfinite(f.p)) and np.all(np.isfinite(f.alpha))


NON_FINITE_TOKENS = ["NaN", "Infinity", "-Infinity", "1e999"]


@pytest.mark.parametrize("token", NON_FINITE_TOKENS)
@pytest.mark.parametrize("kind", ["star", "truncated-ellipse"])
def test_non_finite_tokens_are_refused_naming_the_field(fitted, tmp_path, kind, token):
    field = NUMBER_FIELDS[kind][0]
    text = json.dumps(tamper(to_dict(fitted[kind]), field, 123456.789))
    p = tmp_path / "g.json"
    p.write_text(text.replace("123456.789", token))
    with pytest.raises(GaugeFileError, match="must be a finite number"):
        read_gauge(p)


def scaled(obj, what: str, factor: float):
    out = copy.deepcopy(obj)
    prm = out["parameters"]
    if what == "C":
        prm["C"]["points"] = [[factor * x, factor * y] for x, y in prm["C"]["points"]]
    elif what == "D":
        prm["D"]["h"] = [factor * x for x in prm["D"]["h"]]
        prm["D"]["dh_dpsi"] = [factor * x for x in prm["D"]["dh_dpsi"]]
    elif what == "C and D":
        return scaled(scaled(obj, "C", factor), "D", factor)
    elif what == "data":
        out["data"]["p"] = [[factor * x, factor * y] for x, y in out["data"]["p"]]
    elif what == "ellipse":
        prm["mu_a_plus"] *= factor
    elif what == "theta":
        prm["theta_rad"] += factor
    return out


CONSISTENCY = [("star", "C", 100.0, "parameters.D is not scaled to C"),
               ("star", "C", 1.001, "parameters.D is not scaled to C"),
               ("star", "D", 2.0, "parameters.D is not scaled to C"),
               ("star", "C and D", 1.5, "fit.max_radial_error"),
               ("star", "data", 1.01, "fit.max_radial_error"),
               ("truncated-ellipse", "ellipse", 1.01, "fit.max_radial_error"),
               ("truncated-ellipse", "data", 0.5, "fit.max_radial_error"),
               ("truncated-ellipse", "theta", 0.3, "parameters.theta_rad")]


@pytest.mark.parametrize("kind,what,factor,msg", CONSISTENCY)
def test_parameters_data_and_fit_must_agree(fitted, tmp_path, kind, what, factor, msg):
    p = tmp_path / "g.json"
    p.write_text(json.dumps(scaled(to_dict(fitted[kind]), what, factor)))
    with pytest.raises(GaugeFileError, match=msg.replace(".", r"\.")):
        read_gauge(p)


def test_an_edited_fit_report_is_refused_and_a_valid_file_still_reloads(fitted, tmp_path):
    p = tmp_path / "g.json"
    for kind in ("star", "truncated-ellipse"):
        write_gauge(p, fitted[kind])
        again = read_gauge(p)
        assert to_dict(again) == to_dict(fitted[kind])          # bit for bit
        obj = json.loads(p.read_text())
        obj["fit"]["max_angle_error_deg"] = obj["fit"]["max_angle_error_deg"] * 0.5 + 1e-3
        p.write_text(json.dumps(obj))
        with pytest.raises(GaugeFileError, match="fit.max_angle_error_deg"):
            read_gauge(p)


@pytest.mark.parametrize("text,msg", [
    ("[" * 100_000 + "]" * 100_000, "nested too deeply"),
    ('{"format": "asperity-gauge", "version": 1, "x": ' + "7" * 5000 + "}", "usable gauge file"),
    ('{"format": "asperity-gauge", "version": ' + "[" * 900 + "]" * 900 + "}", "version"),
    ("", "not valid JSON"),
    ("\ufeff{}", "not valid JSON"),
])
def test_structure_of_the_json_text(tmp_path, text, msg):
    p = tmp_path / "g.json"
    p.write_text(text)
    with pytest.raises(GaugeFileError, match=msg):
        read_gauge(p)


# ----------------------------------------------------------------------------- flags

@pytest.fixture(scope="module")
def gauge_file(fitted, tmp_path_factory):
    p = tmp_path_factory.mktemp("g") / "star.json"
    write_gauge(p, fitted["star"])
    return p


FLAGS = [
    (["--psi", "nan"], "--psi must be in [-3600, 3600] deg, got NaN"),
    (["--psi", "inf"], "--psi must be a finite number"),
    (["--psi", "1e308"], "--psi must be in [-3600, 3600] deg"),
    (["--psi", "abc"], "--psi must be a number, got 'abc'"),
    (["--psi", "-1e4"], "--psi must be in [-3600, 3600] deg, got -10000"),
    (["--csv-directions", "0", "--csv", "t.csv"], "--csv-directions must be a whole number"),
    (["--csv-directions", "1000000000", "--csv", "t.csv"], "--csv-directions must be"),
    (["--csv-directions", "-5", "--csv", "t.csv"], "--csv-directions must be"),
]


@pytest.mark.parametrize("flags,msg", FLAGS)
def test_law_flags(gauge_file, capsys, tmp_path, monkeypatch, flags, msg):
    monkeypatch.chdir(tmp_path)
    code, out, err = run(capsys, "law", gauge_file, *flags)
    assert code == 1 and out == "" and msg in err and err.count("\n") == 1, err
    assert not (tmp_path / "t.csv").exists()


@pytest.mark.parametrize("flags,msg", [(["--directions", "0"], "directions must be"),
                                        (["--directions", "10000000"], "directions must be"),
                                        (["--law", "spline"],
                                         "--law must be one of ellipse, star, got 'spline'")])
def test_fit_flags_through_the_real_command(flags, msg):
    status, out, err = cli("fit", SURF / "wedge-asymmetric.toml", *flags)
    assert_refused((status, out, err), code=1, contains=msg)


def test_refused_file_leaves_no_output_and_law_json_is_finite(gauge_file, tmp_path):
    obj = json.loads(gauge_file.read_text())
    obj["parameters"]["C"]["points"][0] = [1e300, 0.0]
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(obj))
    assert_refused(cli("law", bad, "--csv", tmp_path / "t.csv"), contains="parameters.C.points")
    assert not (tmp_path / "t.csv").exists()
    status, out, _ = cli("law", gauge_file, "--psi", "-3599.5", "--json")
    assert status == 0
    assert_finite_output(out)


# ----------------------------------------------------------------------------- Python API

def api_calls(fitted):
    gl, ge, d = fitted["star"], fitted["truncated-ellipse"], fitted["d"]
    nan = float("nan")
    return {
        "Disc(None)": lambda: sets.Disc(None), "Disc('0.2')": lambda: sets.Disc("0.2"),
        "Disc(5e-324)": lambda: sets.Disc(5e-324), "Disc(1e300)": lambda: sets.Disc(1e300),
        "ellipse text": lambda: sets.TruncatedEllipse("0.1", 0.1, 0.1, 0.1),
        "ellipse 1e300": lambda: sets.TruncatedEllipse(1e300, 0.1, 0.1, 0.1),
        "ellipse theta nan": lambda: sets.TruncatedEllipse(0.1, 0.1, 0.1, 0.1, theta=nan),
        "ellipse theta 1e9": lambda: sets.TruncatedEllipse(0.1, 0.1, 0.1, 0.1, theta=1e9),
        "StarSet(None)": lambda: sets.StarSet(None), "StarSet('abc')": lambda: sets.StarSet("abc"),
        "StarSet ragged": lambda: sets.StarSet([[1, 0], [0, 1, 2], [-1, 0]]),
        "StarSet 1e300": lambda: sets.StarSet([[1e300, 0], [0, 1e300], [-1e300, -1e300]]),
        "StarSet nan": lambda: sets.StarSet([[1, 0], [0, nan], [-1, 0]]),
        "ConvexSet(None)": lambda: ConvexSet(None, None, None),
        "ConvexSet text": lambda: ConvexSet("a", "b", "c"),
        "ConvexSet h 1e300": lambda: ConvexSet([0, 2, 4], [1e300] * 3, [0, 0, 0]),
        "WalkerLeineLaw(None)": lambda: walker_leine.WalkerLeineLaw(None, None),
        "WalkerLeineLaw(text)": lambda: walker_leine.WalkerLeineLaw("C", "D"),
        "coulomb(None)": lambda: walker_leine.coulomb(None),
        "associated(None)": lambda: walker_leine.associated(None),
        "force('a')": lambda: gl.law.force("a"), "force(None)": lambda: gl.law.force(None),
        "force(nan)": lambda: gl.law.force(nan), "force(1e308)": lambda: gl.law.force(1e308),
        "radial(nan)": lambda: ge.law.C.radial(nan), "gauge(None)": lambda: ge.law.C.gauge(None),
        "gauge shape": lambda: ge.law.C.gauge([[1, 2, 3]]),
        "criterion sigma nan": lambda: ge.law.C.criterion([[0.1, 0.1]], nan),
        "criterion sigma < 0": lambda: ge.law.C.criterion([[0.1, 0.1]], -1.0),
        "prepare_reservoir(None)": lambda: fitting.prepare_reservoir(None),
        "fit_star(None)": lambda: fitting.fit_star(None),
        "fit_truncated_ellipse(None)": lambda: fitting.fit_truncated_ellipse(None),
        "fit_derivation(None)": lambda: fitting.fit_derivation(None),
        "fit_derivation('a')": lambda: fitting.fit_derivation("a"),
        "fit_derivation(kind)": lambda: fitting.fit_derivation(d, "spline"),
        "compare(None)": lambda: fitting.compare_with_reservoir(None, None),
        "write_gauge(None path)": lambda: write_gauge(None, gl),
        "write_gauge(gl None)": lambda: write_gauge("x.json", None),
        "to_dict(None)": lambda: to_dict(None), "read_gauge(None)": lambda: read_gauge(None),
        "read_gauge(3)": lambda: read_gauge(3),
        "polar_table(None)": lambda: export.polar_table(None),
        "polar_table(n text)": lambda: export.polar_table(gl, "x"),
        "polar_table(n 1e9)": lambda: export.polar_table(gl, 10**9),
        "abaqus_block(None)": lambda: export.abaqus_block(None),
        "summary(None)": lambda: summary.summary(None),
        "format_fit(None)": lambda: summary.format_fit(None),
        "force_at(None)": lambda: summary.force_at(None, 0.0),
        "force_at(nan)": lambda: summary.force_at(gl, nan),
        "force_at('1')": lambda: summary.force_at(gl, "1"),
        "force_at(1e308)": lambda: summary.force_at(gl, 1e308),
    }


API_NAMES = list(api_calls({"star": None, "truncated-ellipse": None, "d": None}))


@pytest.mark.parametrize("name", API_NAMES)
def test_public_api_raises_one_line_input_errors(fitted, tmp_path, monkeypatch, name):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(InputError) as exc:
        api_calls(fitted)[name]()
    assert "\n" not in str(exc.value) and str(exc.value)
    assert not list(tmp_path.iterdir())


def test_fits_of_tiny_and_huge_textures_stay_finite():
    """A texture at the ends of the allowed friction range still gives a finite law."""
    for mu in (1e-6, 5.0):
        d = derive(WedgeTexture(5, 5, mu, mu), n_directions=72)
        try:
            gl = fitting.fit_derivation(d, "truncated-ellipse")
        except InputError as exc:
            assert "\n" not in str(exc)
            continue
        assert all(math.isfinite(v) for v in gl.law.C.axes.values())
