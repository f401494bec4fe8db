"""Gauge files: a fitted friction law as versioned JSON (format "asperity-gauge", version 1;
a law family over the nominal pressure is version 2, :mod:`asperity.laws.family`).

The layout is the JSON Schema shipped with the package, ``asperity/schemas/gauge-1.schema.json``
(:func:`schema`).  :func:`write_gauge` writes atomically; :func:`read_gauge` refuses an
unknown format or version, then checks the file against the schema (by hand, for the
schema keywords the file uses: one error line naming the field) and rebuilds the law, whose
own checks (polygon order, support-function consistency, convexity of D) follow.

Floats are written with ``repr`` (shortest round-trip form), so a law reloads bit for bit.
Non-finite numbers (``NaN``, ``Infinity``, ``1e999``) are refused.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .. import __version__
from ..errors import InputError
from .convex_set import ConvexSet
from .fitting import FitReport, GaugeLaw, ReservoirData
from .gauge_checks import check_consistency, check_ranges
from .gauge_schema import FAMILY_VERSION, FORMAT, VERSION, parse_constant, validate
from .sets import StarSet, TruncatedEllipse
from .walker_leine import WalkerLeineLaw, associated

UNITS = {"force": "per unit normal load (dimensionless): p = -lambda_T / lambda_N",
         "angles": "rad in *_rad fields (sliding direction psi from the x axis of the force "
                   "frame towards y), deg in *_deg fields"}


class GaugeFileError(InputError):
    """A gauge file cannot be read or does not follow the format."""


def to_dict(gl: GaugeLaw) -> dict:
    """The JSON object of a gauge file."""
    from ..errors import check_instance
    check_instance("gauge law", gl, GaugeLaw)
    law = gl.law
    if gl.kind == "truncated-ellipse":
        e = law.C
        params = {**e.axes, "theta_rad": float(e.theta)}
    elif gl.kind == "componentwise":
        from .componentwise import parameters
        params = parameters(law)
    else:
        params = {"C": {"points": law.C.points.tolist()},
                  "D": {"psi_rad": law.D.psi.tolist(), "h": law.D.h.tolist(),
                        "dh_dpsi": law.D.dh.tolist()}}
    return {
        "format": FORMAT,
        "version": VERSION,
        "asperity_version": __version__,
        "law": gl.kind,
        "units": dict(UNITS),
        "frame": {"principal_direction_deg": float(gl.principal_direction_deg),
                  "description": "forces and directions in the frame of the source: wedge "
                                 "textures t_a (across the ridges), t_b (along them); "
                                 "surfaces x, y of the file, t_a at principal_direction_deg"},
        "parameters": params,
        "data": {"psi_rad": gl.data.psi.tolist(), "p": gl.data.p.tolist(),
                 "limit": [int(v) for v in gl.data.limit]},
        "fit": gl.fit.to_dict(),
        "source": gl.source,
    }


def dumps(obj) -> str:
    """JSON text: objects indented, arrays of numbers (and of number pairs) on one line."""
    def enc(x, ind):
        pad = "  " * ind
        if isinstance(x, dict):
            if not x:
                return "{}"
            items = [f'{pad}  {json.dumps(k)}: {enc(v, ind + 1)}' for k, v in x.items()]
            return "{\n" + ",\n".join(items) + "\n" + pad + "}"
        if isinstance(x, list):
            if all(not isinstance(v, (dict, list)) for v in x) or all(
                    isinstance(v, list) and all(not isinstance(w, (dict, list)) for w in v)
                    for v in x):
                return json.dumps(x, allow_nan=False, separators=(", ", ": "))
            return "[\n" + ",\n".join(f"{pad}  {enc(v, ind + 1)}" for v in x) + "\n" + pad + "]"
        return json.dumps(x, allow_nan=False)
    return enc(obj, 0) + "\n"


def write_gauge(path, gl) -> dict:
    """Write the gauge file of a fitted law (versioned JSON, format ``"asperity-gauge"``).

    Written atomically, floats in their shortest round-trip form (the law reloads bit for
    bit); the object is checked against the shipped JSON Schema
    (``asperity/schemas/gauge-1.schema.json``) first.

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write (its folder must exist).
    gl : GaugeLaw or GaugeFamily
        A fitted law (:func:`~asperity.fit_derivation`): version 1; a
        :class:`~asperity.GaugeFamily` of two or more members: version 2 (of one member:
        its law, version 1).

    Returns
    -------
    dict
        The JSON object written (``format``, ``version``, ``law``, ``units``, ``frame``,
        ``parameters``, ``data``, ``fit``, ``source``).

    Raises
    ------
    InputError
        If ``path`` cannot be written (a folder, a missing or read-only folder) or ``gl``
        is not a fitted law or holds a non-finite number (``GaugeFileError``).
    OutputError
        If writing fails (full disk, permissions).

    See Also
    --------
    asperity.read_gauge : read it back.

    Examples
    --------
    >>> d = asperity.derive(asperity.load_texture("surfaces/wedge-asymmetric.toml"))
    >>> gl = asperity.fit_derivation(d, "truncated-ellipse")
    >>> obj = asperity.write_gauge("wedge.json", gl)
    >>> obj["format"], obj["version"], obj["law"]
    ('asperity-gauge', 1, 'truncated-ellipse')
    >>> print(f"{obj['parameters']['mu_a_minus']:.6f}")
    0.193768
    """
    from ..errors import check_instance
    check_instance("path", path, (str, Path), "file name")
    from ..io import check_output, write_text_atomic
    from .family import GaugeFamily
    check_output(path, "path")
    if isinstance(gl, GaugeFamily) and len(gl.members) == 1:
        gl = gl.members[0]
    obj = family_to_dict(gl) if isinstance(gl, GaugeFamily) else to_dict(gl)
    try:
        text = dumps(obj)
    except ValueError as exc:                                   # a non-finite number
        raise GaugeFileError(f"cannot write {path}: {exc}") from None
    validate(obj)
    write_text_atomic(path, text)
    return obj


def read_gauge(path):
    """Read and check a gauge file written by ``asperity fit`` or :func:`~asperity.write_gauge`.

    An unknown format or version is refused, then the file is checked against the
    schema and the law rebuilt with its own checks (polygon order, support-function
    consistency, convexity of D).

    Parameters
    ----------
    path : str or pathlib.Path
        The gauge file (JSON).

    Returns
    -------
    GaugeLaw or GaugeFamily
        The law (version 1), or the law family over the nominal pressure (version 2; a
        family of one member: its GaugeLaw).

    Raises
    ------
    InputError
        ``GaugeFileError``, with one line naming the file and the field, if the file is
        missing, not JSON, of another format or version, or breaks the schema or a check.

    See Also
    --------
    asperity.write_gauge : write one.
    asperity.law_from_gauge : the law for the solver.

    Examples
    --------
    >>> d = asperity.derive(asperity.load_texture("surfaces/wedge-asymmetric.toml"))
    >>> _ = asperity.write_gauge("wedge.json", asperity.fit_derivation(d))
    >>> gl = asperity.read_gauge("wedge.json")
    >>> gl.kind, gl.fit.admissible
    ('star', True)
    >>> print(gl.force(np.radians([0.0])).p.round(6))
    [[0.185697 0.      ]]
    >>> asperity.read_gauge("missing.json")
    Traceback (most recent call last):
    ...
    asperity.laws.gauge_file.GaugeFileError: gauge file 'missing.json' does not exist
    """
    from ..errors import check_instance
    from ..io import read_json
    check_instance("gauge file", path, (str, Path), "file name")
    p = Path(path)
    obj = read_json(p, "gauge file", GaugeFileError, parse_constant=parse_constant)
    try:
        return from_dict(obj)
    except InputError as exc:
        raise GaugeFileError(f"{p}: {exc}") from None
    except RecursionError:
        raise GaugeFileError(f"{p}: not a usable gauge file (nested too deeply)") from None


def from_dict(obj):
    """Rebuild the law (or law family, version 2) of a gauge-file object (checked first)."""
    validate(obj)
    if obj["version"] != VERSION:
        return family_from_dict(obj)
    check_ranges(obj)
    kind = obj["law"]
    prm = obj["parameters"]
    if kind == "truncated-ellipse":
        e = TruncatedEllipse(prm["mu_a_plus"], prm["mu_a_minus"], prm["mu_b_plus"],
                             prm["mu_b_minus"], theta=prm["theta_rad"])
        law = associated(e)
    elif kind == "componentwise":
        from .componentwise import from_parameters
        law = from_parameters(prm)
    else:
        try:
            C = StarSet(np.array(prm["C"]["points"], dtype=float))
        except InputError as exc:
            raise InputError(f"field parameters.C.{exc}") from None
        D = prm["D"]
        n = {len(D["psi_rad"]), len(D["h"]), len(D["dh_dpsi"])}
        if len(n) != 1:
            raise InputError("field parameters.D: psi_rad, h and dh_dpsi must have the same "
                             f"length, got {len(D['psi_rad'])}, {len(D['h'])}, {len(D['dh_dpsi'])}")
        try:
            Dset = ConvexSet(np.array(D["psi_rad"], dtype=float), np.array(D["h"], dtype=float),
                             np.array(D["dh_dpsi"], dtype=float))
        except InputError as exc:
            raise InputError(f"field parameters.D: {exc}") from None
        law = WalkerLeineLaw(C, Dset)
    d = obj["data"]
    if not len(d["psi_rad"]) == len(d["p"]) == len(d["limit"]):
        raise InputError(f"field data: psi_rad, p and limit must have the same length, got "
                         f"{len(d['psi_rad'])}, {len(d['p'])}, {len(d['limit'])}")
    data = ReservoirData(np.array(d["psi_rad"], dtype=float), np.array(d["p"], dtype=float),
                         np.array(d["limit"], dtype=np.int64))
    fit = obj["fit"]
    known = set(FitReport.__dataclass_fields__)
    rep = FitReport(**{k: v for k, v in fit.items() if k in known})
    gl = GaugeLaw(kind, law, data, rep, obj["source"],
                  float(obj["frame"]["principal_direction_deg"]))
    check_consistency(gl)
    return gl


def family_to_dict(fam) -> dict:
    """The version-2 gauge-file object of a GaugeFamily of two or more members: the shared
    fields once (law, units, source without what depends on the pressure), each member's
    pressure, frame, parameters, data, fit, contact figures (and texture keys that depend
    on the load)."""
    from .family import INTERPOLATION, own_keys
    members = []
    for p, gl in zip(fam.pressures, fam.members):
        d = to_dict(gl)
        members.append({"pressure_Pa": p, "frame": d["frame"], "parameters": d["parameters"],
                        "data": d["data"], "fit": d["fit"],
                        "contact": dict(gl.source["elastic_contact"])})
        if own_keys(gl.source):
            members[-1]["texture"] = own_keys(gl.source)
    first = to_dict(fam.members[0])
    return {"format": FORMAT, "version": FAMILY_VERSION, "asperity_version": __version__,
            "law": fam.kind, "units": first["units"],
            "family": {"axis": "pressure_Pa", "interpolation": INTERPOLATION, **fam.elastic},
            "members": members, "source": fam.source}


def family_from_dict(obj: dict):
    """The family of a version-2 object (checked by the caller's ``validate``), or its
    single member's GaugeLaw when it has one."""
    from .family import GaugeFamily, contact_mismatch
    laws, ps = [], []
    fam = obj["family"]
    for k, m in enumerate(obj["members"]):
        one = {"format": FORMAT, "version": VERSION, "asperity_version": obj["asperity_version"],
               "law": obj["law"], "units": obj["units"], "frame": m["frame"],
               "parameters": m["parameters"], "data": m["data"], "fit": m["fit"],
               "source": {**obj["source"], "elastic_contact": m["contact"]}}
        if "texture" in m:
            one["source"]["texture"] = {**obj["source"]["texture"], **m["texture"]}
        try:
            laws.append(from_dict(one))
        except InputError as exc:             # the member's field named in the file's terms
            msg = str(exc)
            msg = (msg.replace("field ", f"field members[{k}].", 1) if "field " in msg else
                   f"members[{k}]: {msg}")
            raise InputError(msg) from None
        p, c = m["pressure_Pa"], m["contact"]
        if k and not p > ps[-1]:
            raise InputError(f"field members[{k}].pressure_Pa must exceed members[{k - 1}]'s "
                             f"(strictly increasing), got {p:g} after {ps[-1]:g}")
        why = contact_mismatch(c, p, fam)
        if why:
            raise InputError(f"field members[{k}].{why}")
        ps.append(p)
    if len(laws) == 1:
        return laws[0]
    return GaugeFamily(tuple(ps), tuple(laws))
