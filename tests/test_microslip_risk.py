"""The risk analysis as a library API: the same numbers as ``asperity risk``, and its
own one-line errors."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from cli_run import run_json

from asperity import assembly_friction, assess_assembly, load_assembly, load_texture, risk_map
from asperity.errors import InputError
from asperity.microslip.risk_text import format_map, format_text

SURF = Path(__file__).resolve().parents[1] / "surfaces"


def public(out: dict) -> dict:
    return {k: v for k, v in out.items() if not k.startswith("_")}


def test_assess_assembly_is_what_the_command_prints(capsys):
    asm = load_assembly(SURF / "bushing-strip.toml")
    tex = load_texture(SURF / "wedge-asymmetric.toml")
    out = assess_assembly(asm, assembly_friction(asm, tex, texture_name="wedge"))
    cli = run_json(capsys, "risk", SURF / "wedge-asymmetric.toml", SURF / "bushing-strip.toml")
    lib = public(out)
    lib["friction"]["texture"] = cli["friction"]["texture"]       # the name given differs
    assert lib == cli
    assert out["verdict"] == "ratchet" and out["_chain"].n == 201
    assert "RATCHET" in format_text(out)


def test_friction_overrides_follow_the_sign_convention():
    asm = load_assembly(SURF / "bushing-strip.toml")
    tex = load_texture(SURF / "wedge-asymmetric.toml")
    base = assembly_friction(asm, tex)
    turned = assembly_friction(asm, tex, slip_axis_deg=180.0)
    part = assembly_friction(asm, tex, textured="part")
    assert base.mu_plus == pytest.approx(0.185697, abs=1e-6)
    for f in (turned, part):
        assert (f.mu_plus, f.mu_minus) == pytest.approx((base.mu_minus, base.mu_plus), rel=1e-12)
    with pytest.raises(InputError, match="textured must be one of support, part"):
        assembly_friction(asm, tex, textured="both")
    spec = load_assembly(SURF / "two-node-spec.toml")               # explicit mu+/mu-
    with pytest.raises(InputError, match="applies to a texture or gauge"):
        assembly_friction(spec, slip_axis_deg=90.0)


def test_risk_map_is_what_the_command_prints(capsys):
    asm = load_assembly(SURF / "bushing-strip-mild.toml")
    tex = load_texture(SURF / "wedge-asymmetric.toml")
    grid = np.linspace(5.0, 40.0, 3)
    out = risk_map(asm, ("alpha", grid), ("mu_beta", [0.1, 0.3]), tex)
    cli = run_json(capsys, "risk", SURF / "wedge-asymmetric.toml",
                   SURF / "bushing-strip-mild.toml", "--map", "alpha=5:40:3", "mu_beta=0.1:0.3:2")
    assert out == cli
    assert np.array(out["map"]["verdict"]).shape == (2, 3)
    assert "risk map" in format_map(out)


def test_risk_map_refuses_what_it_cannot_vary():
    asm = load_assembly(SURF / "bushing-strip-mild.toml")
    tex = load_texture(SURF / "wedge-asymmetric.toml")
    with pytest.raises(InputError, match="two different parameters"):
        risk_map(asm, ("alpha", [5, 10]), ("alpha", [5, 10]), tex)
    with pytest.raises(InputError, match="map parameter must be one of"):
        risk_map(asm, ("gamma", [5, 10]), ("alpha", [5, 10]), tex)
    with pytest.raises(InputError, match="risk map: alpha_deg must be in"):
        risk_map(asm, ("alpha", [5, 95]), ("beta", [5, 10]), tex)
