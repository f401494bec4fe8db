"""Risk maps: the ratchet verdict over a grid of two wedge parameters, as a grid study.

:func:`risk_map` (``asperity risk --map``) runs its cells through the study engine -- the
one code path for sweeps -- in this process by default, or on a Dask cluster.
"""
from __future__ import annotations

import os

from ..errors import InputError, check_array, check_choice, check_instance, check_int
from ..microslip.assembly import Assembly
from ..microslip.risk import (
    CONTACTS,
    MAP_PARAMS,
    check_axis_and_face,
    check_risk_texture,
    life_settings,
    loading_dict,
)

#: values per axis of a risk map
MAP_VALUES = (2, 200)


def risk_map(asm: Assembly, x: tuple[str, object], y: tuple[str, object], texture=None, *,
             contact: str | None = None, slip_axis_deg: float | None = None,
             textured: str | None = None, cycles: float | None = None,
             max_marched: int = 200, workers: int | None = 0,
             scheduler: str | None = None, folder=None) -> dict:
    """Verdict and drift per cycle over a grid of two wedge parameters.

    x, y    : (parameter, values), parameter one of :data:`MAP_PARAMS`
    texture : the wedge texture whose other parameters stay fixed (default: the texture
              of the assembly file's ``[friction]`` table, with its contact regime)
    The other arguments as :func:`assembly_friction` and :func:`assess_assembly`.
    The grid is a study (:mod:`asperity.study`) run by the study engine: ``workers`` 0
    (default) in this process, N on a local Dask cluster, or ``scheduler`` an existing
    one; ``folder`` keeps its store (resumable), else a temporary one is used.
    """
    import numpy as np

    from .. import __version__
    check_instance("asm", asm, Assembly, "parsed assembly (load_assembly)")
    if folder is not None:
        check_instance("folder", folder, (str, os.PathLike), "folder name (text or a Path)")
    (px, xs), (py, ys) = (_map_axis(name, a) for name, a in (("x", x), ("y", y)))
    if px == py:
        raise InputError(f"a risk map needs two different parameters, got {px} twice")
    cycles, _ = life_settings(asm, cycles, None)
    max_marched = check_int("max_marched", max_marched, 2, 1_000_000)
    check_risk_texture(texture)
    if contact is not None:
        check_choice("contact", contact, CONTACTS)
    slip_axis_deg, textured = check_axis_and_face(slip_axis_deg, textured)
    fr = asm.friction_table
    if texture is None:
        if "texture" not in fr:
            raise InputError("a risk map needs a wedge texture: a texture file, the wedge flags, or "
                             "a texture in the assembly's [friction] table")
        from ..friction.sources import load_texture_or_surface
        from ..paths import named_path
        texture = load_texture_or_surface(named_path(fr["texture"], asm.folder))
        contact = contact or fr.get("contact", "all-faces")
    contact = contact or "all-faces"
    if getattr(texture, "kind", "") not in ("wedge", "gaussian-wedge"):
        raise InputError("a risk map varies wedge parameters: give a wedge texture, not a surface")
    axis = slip_axis_deg if slip_axis_deg is not None else fr.get("slip_axis_deg")
    face = textured or fr.get("textured", "support")
    rows = _map_cases(asm, texture, (px, xs), (py, ys), contact, axis, face, cycles,
                      max_marched, workers, scheduler, folder)
    shape = (ys.size, xs.size)
    verdict = np.array([r["verdict"] for r in rows], dtype=object).reshape(shape)
    drift, mup, mum = (np.array([np.nan if r[k] is None else r[k] for r in rows],
                                dtype=float).reshape(shape)
                       for k in ("drift_per_cycle_m", "mu_plus", "mu_minus"))

    def grid(a):
        return [[(float(v) if np.isfinite(v) else None) for v in row] for row in a]
    from ..microslip.verdict import SIGN_CONVENTION
    return {"asperity_version": __version__, "assembly": asm.to_dict(),
            "loading": loading_dict(asm), "contact": contact, "textured": face,
            "slip_axis_deg": 0.0 if axis is None else float(axis),
            "base_texture": texture.to_dict(),
            "map": {"x": {"parameter": px, "values": xs.tolist()},
                    "y": {"parameter": py, "values": ys.tolist()},
                    "verdict": verdict.tolist(), "drift_per_cycle_m": grid(drift),
                    "mu_plus": grid(mup), "mu_minus": grid(mum)},
            "cycles": cycles,
            "drift_after_cycles_m": grid(drift * cycles),
            "sign_convention": SIGN_CONVENTION}


def _map_cases(asm, texture, xa, ya, contact, axis, face, cycles, max_marched, workers,
               scheduler, folder) -> list[dict]:
    """The cells of a risk map (y slowest), each the outputs of one study case."""
    import shutil
    import tempfile

    from ..study.sampling import Parameter
    from ..study.spec import Study
    (px, xs), (py, ys) = xa, ya
    params = tuple(Parameter(f"texture.{MAP_PARAMS[p]}", "grid", (), tuple(map(float, v)))
                   for p, v in ((py, ys), (px, xs)))
    spec = {"stages": ["risk"], "texture": texture.to_dict(), "texture_name": "",
            "assembly": None, "assembly_object": asm, "assembly_path": str(asm.folder),
            "contact": contact, "slip_axis_deg": axis, "textured": face, "cycles": cycles,
            "tolerance": None, "max_marched": max_marched, "directions": 72, "law": "star",
            "output": "drift_per_cycle_m", "surface": {}}
    study = Study(f"risk-map-{asm.name}", "", "grid", None, 0, params, (), spec, None,
                  "risk --map")
    from ..study.engine import run_study
    from ..study.store import open_store
    tmp = None if folder is not None else tempfile.mkdtemp(prefix="asperity-map-")
    store = open_store(folder if folder is not None else tmp, study)
    try:
        run_study(study, store, workers=workers, scheduler=scheduler)
        cols = [c for c, _ in store.outputs]
        rows = []
        for r in store.rows():
            row = dict(zip(store.columns(), r))
            if row["status"] != "ok":
                v = ", ".join(f"{p} = {row[f'texture.{MAP_PARAMS[p]}']:g}" for p in (px, py))
                msg = str(row["message"]).removeprefix("texture.")
                raise InputError(f"risk map: {msg} (at {v})")
            rows.append({c: row[c] for c in cols})
        return rows
    finally:
        store.close()
        if tmp is not None:
            shutil.rmtree(tmp, ignore_errors=True)


def _map_axis(which: str, axis) -> tuple:
    """(parameter, values) of one risk-map axis, checked."""
    if not isinstance(axis, (tuple, list)) or len(axis) != 2:
        raise InputError(f"risk map axis {which} must be (parameter, values), got "
                         f"{type(axis).__name__}")
    name, values = axis
    check_choice("map parameter", name, tuple(MAP_PARAMS))
    v = check_array(f"risk map {name} values", values, shape=(None,), min_size=MAP_VALUES[0])
    if v.size > MAP_VALUES[1]:
        raise InputError(f"risk map {name} values: at most {MAP_VALUES[1]}, got {v.size}")
    return name, v
