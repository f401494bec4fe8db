"""Hostile input files through every command that reads one (issue 11, class 3): texture
and assembly TOML, gauge JSON.  Broken files of every kind end in one line and exit 1;
random values in every field of a valid file give either a result or an InputError,
never another exception (property-based)."""
from __future__ import annotations

import json
import math
import os
from pathlib import Path

import pytest
from hostile import SURF, assert_refused, cli
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from asperity.errors import InputError

TEXTURE = (SURF / "wedge-asymmetric.toml").read_text()
ASSEMBLY = (SURF / "two-node-spec.toml").read_text()


def broken_files(tmp_path: Path, kind: str) -> dict[str, tuple[Path, str]]:
    """name -> (file, words of the expected message) for a TOML or JSON input."""
    suffix = ".toml" if kind == "toml" else ".json"
    out = {}

    def put(name, data: bytes, msg):
        p = tmp_path / f"{name}{suffix}"
        p.write_bytes(data)
        out[name] = (p, msg)
    put("latin1", "name = \"r\xe9sum\xe9\"\n".encode("latin-1"), "not UTF-8")
    put("binary", os.urandom(2048), "not UTF-8")
    put("empty", b"", "")
    if kind == "toml":
        put("deep", ("a = " + "[" * 3000 + "]" * 3000 + "\n").encode(), "")
        put("syntax", b"[texture\nalpha_deg = 30\n", "not valid TOML")
    else:
        put("deep", ("[" * 100_000 + "]" * 100_000).encode(), "nested too deeply")
        put("bigint", ('{"format": "asperity-gauge", "version": 1' + ', "x": ' + "9" * 5000
                       + "}").encode(), "")
        put("syntax", b'{"format": "asperity-gauge",', "not valid JSON")
        put("nan", b'{"format": "asperity-gauge", "version": NaN}', "")
    big = tmp_path / f"huge{suffix}"
    with big.open("wb") as fh:
        fh.truncate(70 << 20)
    out["huge"] = (big, "too large")
    (tmp_path / f"folder{suffix}").mkdir()
    out["folder"] = (tmp_path / f"folder{suffix}", "is a folder")
    out["missing"] = (tmp_path / f"missing{suffix}", "does not exist")
    fifo = tmp_path / f"fifo{suffix}"
    os.mkfifo(fifo)
    out["fifo"] = (fifo, "not a regular file")
    return out


TOML_CASES = ["latin1", "binary", "empty", "deep", "syntax", "huge", "folder", "missing", "fifo"]
JSON_CASES = ["latin1", "binary", "empty", "deep", "bigint", "syntax", "nan", "huge", "folder",
              "missing", "fifo"]


@pytest.mark.parametrize("case", TOML_CASES)
def test_broken_texture_and_assembly_files(case, tmp_path):
    path, msg = broken_files(tmp_path, "toml")[case]
    assert_refused(cli("derive", path), contains=msg)
    assert_refused(cli("risk", path), contains=msg)
    assert_refused(cli("risk", path, SURF / "two-node-spec.toml"), contains=msg)


@pytest.mark.parametrize("case", JSON_CASES)
def test_broken_gauge_files(case, tmp_path):
    path, msg = broken_files(tmp_path, "json")[case]
    assert_refused(cli("law", path), contains=msg)
    assert_refused(cli("slide", path, "--u0", "1", "--angle", "0"), contains=msg)


# ----------------------------------------------------------------------------- fuzzed fields

#: values a hand-edited file may hold in any field
ANY_VALUE = st.one_of(
    st.none(), st.booleans(), st.integers(min_value=-10**30, max_value=10**30),
    st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=8),
    st.lists(st.one_of(st.integers(-5, 5), st.floats(-1e3, 1e3), st.booleans()), max_size=4),
    st.dictionaries(st.text(max_size=3), st.integers(), max_size=2),
    st.sampled_from(["30", "0.2", "inf", "nan", "1e308", "5e-324", "-1", "all-faces"]),
    st.sampled_from([5e-324, 1e-300, 1e308, -0.0, 0.0, 1e-12, 90.0, 89.999999]))


def toml_value(v) -> str:
    """``v`` as a TOML value (None becomes an empty table, which TOML can hold)."""
    if v is None:
        return "{}"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) \
            else repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    return "{" + ", ".join(f"{json.dumps(k)} = {toml_value(x)}" for k, x in v.items()) + "}"


def replace_key(text: str, key: str, value) -> str:
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.split("=")[0].strip() == key:
            lines[i] = f"{key} = {toml_value(value)}"
            return "\n".join(lines) + "\n"
    raise AssertionError(f"{key} not in the file")


TEXTURE_KEYS = ["alpha_deg", "beta_deg", "mu_alpha", "mu_beta", "height"]
ASSEMBLY_KEYS = ["k", "l0", "alpha_T", "k_t", "N", "mu_plus", "mu_minus", "dT_min", "dT_max"]
FUZZ = settings(max_examples=60, deadline=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture])


@FUZZ
@given(key=st.sampled_from(TEXTURE_KEYS), value=ANY_VALUE)
def test_any_value_in_a_texture_file_gives_a_result_or_one_error(tmp_path, key, value):
    from asperity.friction.derive import derive, to_json
    from asperity.texture.wedges import load_texture
    p = tmp_path / "t.toml"
    p.write_text(replace_key(TEXTURE, key, value))
    try:
        d = derive(load_texture(p), n_directions=16)
    except InputError as exc:
        assert "\n" not in str(exc) and str(exc)
        return
    json.dumps(to_json(d), allow_nan=False)            # finite, or null where self-locking


def _assembly_text() -> str:
    for key in ASSEMBLY_KEYS:
        assert any(line.split("=")[0].strip() == key for line in ASSEMBLY.splitlines()), key
    return ASSEMBLY


@FUZZ
@given(key=st.sampled_from(ASSEMBLY_KEYS), value=ANY_VALUE)
def test_any_value_in_an_assembly_file_gives_a_verdict_or_one_error(tmp_path, key, value):
    from asperity.microslip.assembly import load_assembly
    from asperity.microslip.risk import assembly_friction, assess_assembly
    p = tmp_path / "a.toml"
    p.write_text(replace_key(_assembly_text(), key, value))
    try:
        asm = load_assembly(p)
        out = assess_assembly(asm, assembly_friction(asm), cycles=100)
    except InputError as exc:
        assert "\n" not in str(exc) and str(exc)
        return
    except Exception as exc:                            # physical outcomes are AsperityErrors
        from asperity.errors import AsperityError
        assert isinstance(exc, AsperityError), repr(exc)
        return
    public = {k: v for k, v in out.items() if not k.startswith("_")}
    json.dumps(public, allow_nan=False)
