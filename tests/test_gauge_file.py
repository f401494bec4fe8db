"""Gauge files: bit-for-bit reload, the JSON Schema, one-line errors naming the field."""
import json
from pathlib import Path

import numpy as np
import pytest

from asperity.friction.derive import derive
from asperity.laws.fitting import fit_derivation
from asperity.texture.wedges import load_texture

SURF = Path(__file__).resolve().parents[1] / "surfaces"


# ----------------------------------------------------------------------------- gauge files

@pytest.fixture(scope="module")
def fitted():
    t = load_texture(SURF / "wedge-asymmetric.toml")
    return {(c, k): fit_derivation(derive(t, c, "closed-form", 360), k)
            for c in ("all-faces", "windward") for k in ("star", "truncated-ellipse")}


def test_gauge_file_reloads_bit_for_bit_and_matches_the_schema(fitted, tmp_path):
    from asperity.laws.gauge_file import read_gauge, write_gauge
    from asperity.laws.gauge_schema import schema
    jsonschema = pytest.importorskip("jsonschema")
    psi = np.linspace(-1, 8, 997)
    for (c, k), gl in fitted.items():
        path = tmp_path / f"{c}-{k}.json"
        write_gauge(path, gl)
        jsonschema.Draft202012Validator(schema()).validate(json.loads(path.read_text()))
        back = read_gauge(path)
        assert back.kind == k and back.fit == gl.fit and back.source == gl.source
        assert (back.data.psi == gl.data.psi).all() and (back.data.p == gl.data.p).all()
        f0, f1 = gl.force(psi), back.force(psi)
        assert (f0.p == f1.p).all() and (f0.alpha == f1.alpha).all()
        if k == "star":
            assert (back.law.C.points == gl.law.C.points).all()
            assert (back.law.D.h == gl.law.D.h).all() and (back.law.D.dh == gl.law.D.dh).all()
        else:
            assert back.law.C == gl.law.C
    assert not list(tmp_path.glob(".*part"))


def _mutate(obj, path, value):
    node = obj
    for k in path[:-1]:
        node = node[k]
    if value is KeyError:
        del node[path[-1]]
    else:
        node[path[-1]] = value


@pytest.mark.parametrize("path,value,msg", [
    (["version"], 3, "field version: unknown gauge-file version 3"),
    (["format"], "other", "field format must be 'asperity-gauge'"),
    (["law"], KeyError, "missing field law"),
    (["parameters", "D", "h"], KeyError, "missing field parameters.D.h"),
    (["parameters", "C", "points", 3, 1], "NaN",
     "field parameters.C.points[3][1] must be a finite number, got NaN"),
    (["fit", "max_radial_error"], "Infinity", "field fit.max_radial_error must be a finite number"),
    (["parameters", "D", "h", 2], -1.0, "field parameters.D.h[2] must be > 0"),
    (["parameters", "D", "h", 5], "abc", "field parameters.D.h[5] must be of type number"),
    (["law"], "spline", "field law must be one of"),
    (["parameters", "D", "dh_dpsi", 7], 3.0, "field parameters.D: h and dh are not a consistent"),
    (["parameters", "extra"], 1, "unknown field parameters.extra"),
])
def test_gauge_file_errors_name_the_field(fitted, tmp_path, path, value, msg):
    from asperity.laws.gauge_file import GaugeFileError, read_gauge, to_dict
    obj = to_dict(fitted[("windward", "star")])
    special = value in ("NaN", "Infinity")
    _mutate(obj, path, "@@" if special else value)
    text = json.dumps(obj)
    if special:
        text = text.replace('"@@"', value)
    f = tmp_path / "bad.json"
    f.write_text(text)
    with pytest.raises(GaugeFileError) as exc:
        read_gauge(f)
    line = str(exc.value)
    assert "\n" not in line and msg in line, line
    if not special:
        jsonschema = pytest.importorskip("jsonschema")
        from asperity.laws.gauge_schema import schema
        if "consistent" not in msg and "format" not in msg:
            assert not jsonschema.Draft202012Validator(schema()).is_valid(obj), \
                "the shipped schema refuses it too"


def test_ellipse_gauge_file_errors(fitted, tmp_path):
    from asperity.laws.gauge_file import GaugeFileError, read_gauge, to_dict
    obj = to_dict(fitted[("all-faces", "truncated-ellipse")])
    obj["parameters"]["mu_b_minus"] = 0
    f = tmp_path / "bad.json"
    f.write_text(json.dumps(obj))
    with pytest.raises(GaugeFileError, match="field parameters.mu_b_minus must be > 0"):
        read_gauge(f)
    f.write_text("{not json")
    with pytest.raises(GaugeFileError, match="not valid JSON"):
        read_gauge(f)
    with pytest.raises(GaugeFileError, match="does not exist"):
        read_gauge(tmp_path / "missing.json")
