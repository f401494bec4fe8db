"""slide_body at its limits: the step limit itself is allowed (one step more is refused in
one line), and a body file is known by being a file, whatever its suffix (a missing
``.toml`` is named as missing, not taken for a body kind)."""
from __future__ import annotations

import pytest

from asperity import coulomb_law
from asperity.bodies import footprint as fpm
from asperity.dynamics import body as solver_module
from asperity.dynamics import moreau
from asperity.dynamics.body_api import make_body, slide_body
from asperity.errors import InputError


def test_step_limit_is_inclusive(monkeypatch):
    """slide_body's own limit (the solver module, imported above, keeps its own)."""
    monkeypatch.setattr(moreau, "MAX_STEPS", 400)
    assert solver_module.MAX_STEPS > 400
    fp = fpm.disc(0.05, contact_points=16)
    res = slide_body(coulomb_law(0.3), fp, 5.0, 0.0, dt=1e-3, t_end=0.4).result
    assert res.steps == 400 and res.ok
    with pytest.raises(InputError, match="gives 401 steps, at most 4e[+]02") as e:
        slide_body(coulomb_law(0.3), fp, 5.0, 0.0, dt=1e-3, t_end=0.401)
    assert "\n" not in str(e.value)


def test_body_file_is_known_by_being_a_file(tmp_path):
    path = tmp_path / "plate.body"
    path.write_text('[body]\nshape = "disc"\nradius = 0.05\nmass = 2.0\n')
    body = make_body(str(path))
    assert body.mass == 2.0 and body.footprint.radius == 0.05
    assert slide_body(coulomb_law(0.3), body, 0.5, 30.0).result.rest
    with pytest.raises(InputError, match="missing.toml") as e:
        make_body(str(tmp_path / "missing.toml"))
    assert "body file" in str(e.value) and "kind must be" not in str(e.value)
