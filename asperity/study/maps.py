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
    """The ratchet verdict and drift per cycle of an assembly over a grid of two wedge
    parameters (``asperity risk --map``).

    Parameters
    ----------
    asm : Assembly
        An assembly read by :func:`asperity.load_assembly`.
    x, y : tuple
        (parameter, values) of each axis: parameter one of "alpha", "beta" (deg),
        "mu_alpha", "mu_beta"; 2 to 200 values; two different parameters.
    texture : WedgeTexture, GaussianWedgeTexture or None, optional
        The wedge texture whose other parameters stay fixed; None (default): the texture
        of the assembly file's ``[friction]`` table, with its contact regime.
    contact : str or None, optional
        "all-faces" or "windward"; None: the table's, else "all-faces".
    slip_axis_deg : float or None, optional
        As :func:`asperity.assembly_friction`.
    textured : str or None, optional
        As :func:`asperity.assembly_friction`.
    cycles : float or None, optional
        As :func:`asperity.assess_assembly`.
    max_marched : int, optional
        As :func:`asperity.assess_assembly` (default 200).
    workers : int or None, optional
        0 (default): the cells run in this process; N in [1, 4096]: on a local Dask
        cluster of N workers; None: the scheduler of ``$ASPERITY_SCHEDULER``, else a local
        cluster.
    scheduler : str or None, optional
        An existing Dask scheduler (its address or scheduler file) to run the cells on.
    folder : str, os.PathLike or None, optional
        Keeps the study's store there (a rerun resumes); None (default): a temporary one,
        removed.

    Returns
    -------
    dict
        The JSON object of ``asperity risk --map --json``: ``map`` holds the axes (``x``,
        ``y``: parameter and values) and the grids (rows along y, columns along x)
        ``verdict``, ``drift_per_cycle_m`` (m, positive towards +x), ``mu_plus`` and
        ``mu_minus`` (None where undefined); besides ``drift_after_cycles_m``, ``cycles``,
        ``base_texture``, ``assembly``, ``loading`` and the ``sign_convention``.

    Raises
    ------
    InputError
        A bad axis, no wedge texture (a surface cannot be varied), a value outside its
        range, a cell that fails (named by its parameters).

    See Also
    --------
    asperity.assess_assembly, asperity.assembly_friction, asperity.WedgeTexture

    Notes
    -----
    The grid is a study (``asperity.study``) run by the study engine, the one code path
    for sweeps.

    Examples
    --------
    The bushing's housing texture over its steep face's angle and its gentle face's
    coefficient: at alpha = 30 deg, mu_beta = 0.2 it is the SPEC.md wedge
    (mu_a+ = 0.185697):

    >>> asm = asperity.load_assembly("surfaces/bushing-strip.toml")
    >>> out = asperity.risk_map(asm, ("alpha", [20.0, 30.0, 40.0]), ("mu_beta", [0.1, 0.2]))
    >>> for row in out["map"]["verdict"]:
    ...     print(row)
    ['alternating-slip', 'alternating-slip', 'ratchet']
    ['ratchet', 'ratchet', 'ratchet']
    >>> print(f"{out['map']['mu_plus'][1][1]:.6f}")
    0.185697
    >>> print(f"{out['map']['drift_per_cycle_m'][1][1]:.3e}")        # m per cycle
    2.748e-07
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
