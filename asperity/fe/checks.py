"""Checks of the GetFEM runs against the law and the chain (tests, report, benchmark).

* :func:`drag_check`: an elastic plate in plan view (the contact plane is the model plane,
  friction an area term: the GWFL plan-view law of ``asperity law --gwfl``) dragged by one
  edge along each of ``directions`` directions; once it slides steadily the pull per unit
  normal load must be the law's force p(psi) (SPEC.md 3).
"""
from __future__ import annotations

import math

import numpy as np

#: the plate: side (m), elements per side, modulus (Pa), Poisson's ratio, pressure (Pa);
#: drag per increment (m) and increments; regularisation slip length (m)
PLATE = {"size": 0.01, "n": 6, "E": 2e11, "nu": 0.3, "p": 1e6, "drag": 1e-4, "steps": 2,
         "eps": 1e-9}


def drag_check(gl, directions: int = 24, *, gwfl_text: str | None = None, **plate) -> dict:
    """Pull force per unit normal load of the dragged plate against ``gl.force`` along
    ``directions`` equally spaced directions: rows and the largest relative error
    |F_FE - p| / |p|.  ``gwfl_text``: the macros as ``law --gwfl`` wrote them (else made
    from ``gl``)."""
    from .getfem_runner import run_job
    from .gwfl import gwfl_text as make_text
    from .gwfl import parse_gwfl
    text = gwfl_text if gwfl_text is not None else make_text(gl, "drag check")
    law = parse_gwfl(text)
    macros = [m for m in law["macros"] if m[0] not in ("asp_ttr", "asp_tx")]
    deg = [360.0 * k / directions for k in range(directions)]
    q = {**PLATE, **plate}
    job = {"task": "drag", **q, "functions": law["functions"], "macros": macros,
           "directions_deg": deg, "max_res": 1e-10 * q["E"] * q["drag"] * q["size"],
           "max_iter": 30}
    r = run_job(job)
    ref = np.asarray(gl.force(np.radians(deg)).p, float)
    rows, worst = [], 0.0
    for f, pl in zip(r["forces"], ref):
        fe = np.asarray(f["pull"], float)
        err = float(np.linalg.norm(fe - pl) / np.linalg.norm(pl))
        worst = max(worst, err)
        rows.append({"direction_deg": f["direction_deg"], "law": pl.tolist(),
                     "fe": fe.tolist(), "friction_integral": f["friction"],
                     "relative_error": err, "slip_spread": f["slip_spread"]})
    return {"rows": rows, "max_relative_error": worst, "elements": r["elements"],
            "newton_iterations": r["newton_iterations"], "seconds": r["seconds"],
            "directions": directions}


def angle_deg(v) -> float:
    return math.degrees(math.atan2(v[1], v[0]))
