"""What a case is built from: the texture or surface and the assembly of a study's case, its
parameter values put in their tables (:func:`build_inputs`; the per-case path of
:mod:`.cases` and the block path of :mod:`.blocks` both build from here)."""
from __future__ import annotations

from ..errors import InputError


def build_inputs(spec: dict, values: dict, file: str | None, cache: dict | None = None,
                 weigh: bool = True):
    """(texture or surface or None, Assembly or None) of one case.

    values: {"texture.alpha_deg": 31.2, "loading.dT_max": 120.0, ...}; file: the scan of a
    files study (read here, on the worker).  cache: texture and assembly objects of earlier
    cases of the same batch, by the values that built them (immutable objects: a case that
    varies only the texture parses the assembly once per batch).  With a ``[contact]``
    table (``spec["elastic"]``) the texture's faces are weighted by the contact force at
    the case's values (``weigh`` False: the values only checked)."""
    cache = {} if cache is None else cache
    texture = None
    elastic = None
    if spec.get("elastic") is not None:
        from .contact import elastic_for
        elastic = elastic_for(spec["elastic"], values)
        elastic = elastic if weigh else None
    if file is not None:
        texture = _load_file(file, spec.get("surface", {}), elastic)
    elif isinstance(spec.get("texture"), str) and elastic is not None:
        texture = _load_file(spec["texture"], {}, elastic)
    elif spec.get("texture") is not None:
        key = ("texture", *((k, v) for k, v in values.items() if k.startswith("texture.")))
        if key not in cache:
            cache[key] = _texture(spec, values)
        texture = cache[key]
        if elastic is not None:
            from .contact import weighted
            texture = weighted(texture, None, elastic, {})
    asm = spec.get("assembly_object")       # risk maps: a parsed assembly, not varied
    if spec.get("assembly") is not None:
        varied = {k: v for k, v in values.items() if not k.startswith("texture.")}
        key = ("assembly", *varied.items())
        if key not in cache:
            if varied and all(k.startswith("loading.") for k in varied):
                # only the loading varies: the rest of the file is parsed once per batch
                from ..microslip.assembly import with_loading
                if ("assembly",) not in cache:
                    cache[("assembly",)] = _assembly(spec, {})
                lo = dict(spec["assembly"].get("loading") or {})
                for k, v in varied.items():
                    lo[k.split(".", 1)[1]] = float(v)
                cache[key] = with_loading(cache[("assembly",)], lo, spec["assembly_path"])
            else:
                cache[key] = _assembly(spec, values)
        asm = cache[key]
    if len(cache) > 64:
        base = cache.get(("assembly",))
        cache.clear()
        if base is not None:
            cache[("assembly",)] = base
    return texture, asm


def _texture(spec: dict, values: dict):
    if isinstance(spec["texture"], str):
        from ..friction.sources import load_texture_or_surface
        return load_texture_or_surface(spec["texture"])
    from ..texture.wedges import texture_from_dict
    table = dict(spec["texture"])
    for k, v in values.items():
        if k.startswith("texture."):
            table[k.split(".", 1)[1]] = float(v)
    return texture_from_dict(table)


def _assembly(spec: dict, values: dict):
    from ..microslip.assembly import assembly_from_dict
    data = dict(spec["assembly"])                  # copy the tables that change only
    for k, v in values.items():
        table, key = k.split(".", 1)
        if table in ("assembly", "friction", "loading"):
            t = data.get(table, {})
            if not isinstance(t, dict):
                raise InputError(f"{table} of the assembly file is not a table")
            data[table] = t = dict(t) if t is spec["assembly"].get(table) else t
            t[key] = float(v)
    return assembly_from_dict(data, spec["assembly_path"])


def _load_file(path: str, opts: dict, elastic=None):
    from ..friction.sources import is_texture_file
    from .contact import weighted
    if is_texture_file(path):
        from ..texture.wedges import load_texture
        t = load_texture(path)
        return t if elastic is None else weighted(t, None, elastic, opts)
    if elastic is not None:
        return weighted(None, path, elastic, opts)
    from ..surface.facets import load_surface
    px = opts.get("pixel_size")
    return load_surface(path, unit=opts.get("unit"),
                        pixel_size=tuple(px) if isinstance(px, list) else px,
                        height_scale=opts.get("height_scale", 1.0),
                        detrend=opts.get("detrend", "slope"), mu=opts.get("mu"),
                        max_slope=opts.get("max_slope"), despike=opts.get("despike"),
                        despike_window=opts.get("despike_window"))
