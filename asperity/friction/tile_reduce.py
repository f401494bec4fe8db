"""The passes of a tiled derivation reduced in tile order (:mod:`.tiled` runs them): the
global quantities of the preparatory pass, the exact rest level of a bearing fraction,
and the Derivation assembled from the sweeps as :func:`asperity.friction.derive.derive`
assembles it from the facets in memory."""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError, TextureFileError


def prepare(run, plan, path, detrend, friction_map, height_scale):
    """(plan with spikes, form and slope, the facets' info, prep figures) from pass 1."""
    from ..surface.detrend import FormFit
    from ..surface.facets import DETREND
    from ..surface.quality import locking_limit_deg
    from ..surface.topography import check_coordinates
    src = plan.heights
    name = getattr(src, "name", None) or src.path or src.source
    degree = DETREND[detrend] if DETREND[detrend] not in (None, "slope") else None
    res = run.map("prep", plan, (degree, detrend == "slope"), "reading, spikes, form")
    lo = min((r["lo"] for r in res if r["lo"] == r["lo"]), default=math.nan)
    hi = max((r["hi"] for r in res if r["hi"] == r["hi"]), default=math.nan)
    if lo != lo:
        raise TextureFileError(f"{name}: every pixel is undefined")
    check_coordinates(np.array([lo, hi]), f"{name}: heights")
    spikes = np.concatenate([r["spikes"] for r in res]) if plan.despike else None
    n_ok = sum(r["n_ok"] for r in res)
    undefined = sum(r["undefined"] for r in res)
    form = None
    if degree is not None:
        form = FormFit(degree, *src.shape)
        for r in res:
            form.gram += r["gram"]
            form.rhs += r["rhs"]
            form.count += r["count"]
        form.solve(src.source)
    if n_ok == 0:
        raise InputError(f"{src.source}: no facet left (every triangle was undefined, "
                         "degenerate or vertical)")
    slope = None
    if detrend == "slope":
        slope = (sum(r["sum_g"][0] for r in res) / n_ok, sum(r["sum_g"][1] for r in res) / n_ok)
    mu_max = plan.mu
    if plan.mu_map is not None:
        bad = [r["bad_mu"] for r in res if r["bad_mu"][0]]
        if bad:
            from ..surface.friction_map import bad_mu_error
            where = f"{friction_map}: " if isinstance(friction_map, str) else ""
            raise bad_mu_error(sum(b[0] for b in bad), bad[0][1], where)
        mu_max = max(r["mu_max"] for r in res)
    plan = plan.with_(spikes=spikes, form=form, slope=slope,
                      limit_deg=locking_limit_deg(mu_max))
    nx, ny = src.shape
    info = {"file": str(path), "detrend": detrend, "height_scale": float(height_scale)}
    if isinstance(friction_map, str) or hasattr(friction_map, "__fspath__"):
        info["friction_map"] = str(friction_map)
    info.update(kind="heightmap", source=src.source, grid=[nx, ny],
                pixel_size_m=[src.dx, src.dy], physical_size_m=[src.dx * nx, src.dy * ny],
                n_undefined=undefined, n_skipped_undefined=2 * (nx - 1) * (ny - 1) - n_ok,
                mu=plan.mu if plan.mu_map is None else None)
    if slope is not None:
        info["removed_slope"] = [slope[0], slope[1]]
    prep = {"undefined": undefined, "spikes": 0 if spikes is None else int(spikes.size),
            "mu_max": mu_max, "n_ok": n_ok, "passes": 1}
    return plan, info, prep


def bearing_rank(n: int, area: float, fraction: float) -> int:
    """The index k of :func:`asperity.surface.grid_facets.rest_level_for_bearing` for n
    facets of equal area: the cumulative sums of the whole map's facets (sequential, so
    pieces with a carried total round exactly as one call)."""
    piece = 1 << 20
    total = 0.0
    for a in range(0, n, piece):
        m = min(n, a + piece) - a
        total = float(np.cumsum(np.concatenate([[total], np.full(m, area)]))[-1])
    target = fraction * total * (1 - 1e-12)
    carry = 0.0
    for a in range(0, n, piece):
        m = min(n, a + piece) - a
        cum = np.cumsum(np.concatenate([[carry], np.full(m, area)]))[1:]
        k = int(np.searchsorted(cum, target))
        if k < m:
            return min(a + k, n - 1)
        carry = float(cum[-1])
    return n - 1


def bearing_level(run, plan, fraction: float) -> float:
    """The rest level of a bearing fraction, as the whole map's facets place it."""
    p = plan.with_(rest_level=None, need_z=True)
    zr = run.map("zrange", p, (), "bearing fraction: range")
    n = sum(r[0] for r in zr)
    if n == 0:
        raise InputError(f"max_slope {plan.max_slope:g} deg drops every facet of "
                         f"{plan.heights.source} (the gentlest is steeper)")
    zmin, zmax = min(r[1] for r in zr), max(r[2] for r in zr)
    src = plan.heights
    k = bearing_rank(n, 0.5 * src.dx * src.dy, fraction)
    if k + 1 >= n:
        return float(zmin - 1e-9 * max(zmax - zmin, abs(zmin), 1e-300))
    ranks = (n - 1 - k, n - 2 - k)             # ascending ranks of z[k] and z[k + 1]
    levels, below = [(zmin, zmax, BINS, 0, BINS - 1)], 0
    for depth in range(4):
        h = np.sum([np.asarray(x) for x in run.map("zhist", p, (levels,),
                                                   "bearing fraction: histogram")], axis=0)
        cum = np.cumsum(h)
        b = [int(np.searchsorted(cum, r - below, side="right")) for r in ranks]
        b0, b1 = min(b), max(b)
        lo, hi, nb = levels[-1][:3]
        levels[-1] = (lo, hi, nb, b0, b1)
        below += int(cum[b0 - 1]) if b0 else 0
        count = int(cum[b1] - (cum[b0 - 1] if b0 else 0))
        if count <= COLLECT or depth == 3:
            break
        span = (hi - lo) / nb
        levels.append((lo + b0 * span, lo + (b1 + 1) * span, BINS, 0, BINS - 1))
    v = np.sort(np.concatenate(run.map("zcollect", p, (levels,), "bearing fraction: level")))
    z_k, z_k1 = v[ranks[0] - below], v[ranks[1] - below]
    return float(0.5 * (z_k + z_k1))


BINS = 1 << 16
COLLECT = 1 << 22


def global_first(results, k, axis_rows: int) -> np.ndarray:
    """First self-locking facet of job ``k`` in the whole map's facet order (-1: none)."""
    tot = np.zeros((2, axis_rows), dtype=np.int64)
    for r in results:
        c = r["counts"]
        tot[:, r["row0"]:r["row0"] + c.shape[1]] += c
    n_lower = int(tot[0].sum())
    before = np.zeros((2, axis_rows + 1), dtype=np.int64)
    np.cumsum(tot, axis=1, out=before[:, 1:])
    left = np.zeros((2, axis_rows), dtype=np.int64)      # earlier tiles on the same row
    best = None
    for r in results:
        cand = r["jobs"][k][1]
        if best is None:
            best = np.full(cand.size, -1, dtype=np.int64)
        c, row0 = r["counts"], r["row0"]
        sel = np.flatnonzero(cand >= 0)
        if sel.size:
            cums = (np.cumsum(c[0]), np.cumsum(c[1]))          # per tile, not per direction
            low_total = int(cums[0][-1]) if cums[0].size else 0
            for j in sel:
                loc = int(cand[j])
                h = int(loc >= low_total)
                loc -= h * low_total
                cum = cums[h]
                row = int(np.searchsorted(cum, loc, side="right"))
                pos = loc - (int(cum[row - 1]) if row else 0)
                i = row0 + row
                g = h * n_lower + int(before[h, i]) + int(left[h, i]) + pos
                if best[j] < 0 or g < best[j]:
                    best[j] = g
        left[:, row0:row0 + c.shape[1]] += c
    return best


def assemble(run, plan, info, prep, contact, n, other_contact):
    """Sweeps -> the Derivation (same steps as :func:`asperity.friction.derive.derive`)."""
    from ..surface.quality import SlopeStats, quality_stats
    from ..surface.tiles import ScanSurface, preview_step
    from ._facet_kernels import MODE_ALL, MODE_WINDWARD
    from .derive import Derivation, anisotropy, principal_direction
    from .diagnostics import (
        SURFACE_DERIVATIVE_STEP,
        check_admissibility,
        check_associativity,
        dT_dpsi_from,
        find_self_locking,
        share_directions,
        share_of,
    )
    from .reservoir import directions
    src = plan.heights
    mode = {"all-faces": MODE_ALL, "windward": MODE_WINDWARD}
    psi = directions(n)
    h = SURFACE_DERIVATIVE_STEP
    psi3 = np.concatenate([psi, psi + h, psi - h])
    res = run.map("sweep", plan, ([("sweep", mode[contact], psi3)], True), "facets x directions")
    n_facets = sum(r["n"] for r in res)
    stats = SlopeStats(plan.limit_deg)
    for r in res:
        stats.merge(r["stats"])
    if n_facets == 0:
        if stats.dropped == prep["n_ok"]:
            raise InputError(f"max_slope {plan.max_slope:g} deg drops every facet of "
                             f"{src.source} (the gentlest is steeper)")
        zc_max = max((r["zc_max"] for r in res if r["zc_max"] is not None), default=math.nan)
        raise InputError(f"rest_level {plan.rest_level:g} m lies above the highest facet "
                         f"({zc_max:g} m): nothing is in contact")
    rows = src.shape[0] - 1
    wsum = sum(r["wsum"] for r in res)
    main = _reduce(res, 0, rows)
    info["rest_level_m"] = plan.rest_level
    info["n_unloaded"] = sum(r["n_unloaded"] for r in res)
    step = preview_step(src)
    prev = np.vstack([r["preview"][1] for r in res if r["preview"][1].size]) \
        if any(r["preview"][1].size for r in res) else np.zeros((0, 0))
    preview = prev if src.axis == 0 else prev.T
    del res
    fake = _Sums(wsum)
    both = _finish_job(run, plan, fake, psi3, contact, main, mode, rows)
    cf = both.take(slice(0, n))
    theta = principal_direction(cf)
    axis_psi = theta + np.array([0.0, np.pi, 0.5 * np.pi, 1.5 * np.pi])
    share, k_share = share_directions(cf)
    jobs = [("sweep", mode[contact], axis_psi)]
    if k_share.size:
        jobs.append(("lockw", contact == "windward", cf.psi[k_share]))
    if other_contact is not None:
        jobs.append(("sweep", mode[other_contact], psi))
    post = run.map("sweep", plan, (jobs, False), "axes, load shares")
    out = [_reduce(post, k, rows) for k in range(len(jobs))]
    del post
    axis_res = _finish_job(run, plan, fake, axis_psi, contact, out[0], mode, rows)
    if k_share.size:
        share[k_share] = share_of(out[1])
    other = None
    if other_contact is not None:
        other = _finish_job(run, plan, fake, psi, other_contact, out[-1], mode, rows)
    t = axis_res.tangential
    assoc = check_associativity(cf, *dT_dpsi_from(both.take(slice(n, 2 * n)),
                                                  both.take(slice(2 * n, 3 * n)), h))
    axes = {"mu_a_plus": float(t[0]), "mu_a_minus": float(t[1]),
            "mu_b_plus": float(t[2]), "mu_b_minus": float(t[3])}
    quality = quality_stats(pixels=src.shape[0] * src.shape[1], undefined=prep["undefined"],
                            despike=plan.despike, spikes=prep["spikes"],
                            max_slope=plan.max_slope, mu_max=prep["mu_max"], stats=stats)
    tiling = {"tile_rows": plan.tile_lines, "tiles": plan.n_tiles,
              "axis": src.axis, "streamed": bool(src.streams), "passes": run.passes,
              "preview_step": step}
    surf = ScanSurface(info, n_facets, preview, (src.dx * src.shape[0], src.dy * src.shape[1]),
                       quality, tiling)
    if other is not None:
        surf.other[other_contact] = other
    return Derivation(surf, contact, "closed-form", cf, axes, find_self_locking(cf, None),
                      check_admissibility(cf), assoc, None, cf,
                      principal_direction_deg=math.degrees(theta), anisotropy=anisotropy(cf),
                      locking_share=float(np.nanmax(share, initial=0.0)))


class _Sums:
    """What :func:`.facet_reservoir._assemble` reads of the facets: the total weight."""

    def __init__(self, wsum):
        self.wsum = wsum
        self.idx = np.empty(0, dtype=np.int64)

    def original(self, i):
        return np.asarray(i, dtype=np.int64)


def _reduce(results, k, rows):
    """Job k's totals over the tiles in tile order: (sums, first) or the locked weights."""
    acc = None
    for r in results:
        part = r["jobs"][k]
        part = part[0] if isinstance(part, tuple) else part
        acc = part.copy() if acc is None else acc + part
    if not isinstance(results[0]["jobs"][k], tuple):
        return acc
    return acc, global_first(results, k, rows)


def _finish_job(run, plan, fake, psi, contact, job, mode, rows):
    """Reservoir of a sweep job; in the windward regime the directions in which no facet
    is climbed take the level facets, from one more pass (rare: exactly along ridges)."""
    from ._facet_kernels import MODE_LEVEL
    from .facet_reservoir import _assemble
    level = None
    none = job[0][:, 4] == 0
    if contact == "windward" and none.any():
        res = run.map("sweep", plan, ([("sweep", MODE_LEVEL, psi[none])], False),
                      "level facets")
        level = _reduce(res, 0, rows)
    return _assemble(fake, psi, contact, job[0], job[1], lambda sel: level)
