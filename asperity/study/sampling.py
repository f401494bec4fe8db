"""The cases of a study: parameter distributions and the sample matrices built from them.

Every sample matrix is a pure function of the study (kind, sample count, seed and the
parameters in the order of the file), built on the client before any work: the same study
gives the same cases bit for bit whatever the number of workers or the batch size, and a
resumed study rebuilds exactly the cases it had.

Distributions (the ``[parameters]`` table of a study file)::

    { distribution = "uniform", low = L, high = H }
    { distribution = "normal", mean = M, sd = S }
    { distribution = "truncated-normal", mean = M, sd = S, low = L, high = H }
    { distribution = "lognormal", median = M, sigma = S }     # ln X ~ normal(ln M, S)
    { values = [v1, v2, ...] }  or  { low = L, high = H, n = N }   # kind = "grid" only

A distribution that cannot be sampled in double precision -- a spread below the
resolution of its values (every sample the same number), a truncated normal whose
interval lies more than 6 sd from its mean or that is flat on it, tails beyond a double --
is refused when the study is read, in one line naming the key and its allowed range.

Sample matrices: ``grid`` the Cartesian product of the values (first parameter varying
slowest); ``monte-carlo`` independent draws (NumPy PCG64 stream of the seed, inverse
transform); ``latin-hypercube`` scipy.stats.qmc.LatinHypercube (seeded, one stratum per
sample in every parameter); ``sobol`` Saltelli's scheme through SALib (N (D + 2) cases for
first-order and total indices, scrambled Sobol' sequence of the seed).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_int, check_range

KINDS = ("grid", "monte-carlo", "latin-hypercube", "sobol", "files")
DISTRIBUTIONS = ("uniform", "normal", "truncated-normal", "lognormal")
#: most cases a study may have (the store and the sample matrix stay well under 1 GB)
MAX_CASES = 10_000_000
#: most values per grid axis
MAX_GRID_AXIS = 100_000


@dataclass(frozen=True)
class Parameter:
    """One varied input: ``name`` is TABLE.KEY of the texture or assembly file it replaces;
    ``distribution`` one of :data:`DISTRIBUTIONS` or "grid" with ``values``."""

    name: str
    distribution: str
    args: tuple = ()               # (low, high) | (mean, sd) | (mean, sd, low, high) | (median, sigma)
    values: tuple = ()             # grid values

    def ppf(self, u: np.ndarray) -> np.ndarray:
        """The parameter values at probabilities ``u`` in (0, 1) (inverse transform)."""
        from scipy import stats
        d, a = self.distribution, self.args
        if d == "uniform":
            return a[0] + (a[1] - a[0]) * u
        if d == "normal":
            return stats.norm.ppf(u, loc=a[0], scale=a[1])
        if d == "truncated-normal":
            lo, hi = (a[2] - a[0]) / a[1], (a[3] - a[0]) / a[1]
            return stats.truncnorm.ppf(u, lo, hi, loc=a[0], scale=a[1])
        if d == "lognormal":
            return a[0] * np.exp(a[1] * stats.norm.ppf(u))
        raise InputError(f"parameter {self.name}: grid values are not sampled")

    @property
    def centre(self) -> float:
        """A representative value (median or first grid value), used to check the study."""
        if self.distribution == "grid":
            return float(self.values[0])
        return float(self.ppf(np.array([0.5]))[0])

    def describe(self) -> str:
        a = self.args
        if self.distribution == "grid":
            v = self.values
            return f"grid of {len(v)} values {v[0]:g} .. {v[-1]:g}"
        if self.distribution == "uniform":
            return f"uniform [{a[0]:g}, {a[1]:g}]"
        if self.distribution == "normal":
            return f"normal, mean {a[0]:g}, sd {a[1]:g}"
        if self.distribution == "truncated-normal":
            return f"truncated normal, mean {a[0]:g}, sd {a[1]:g}, in [{a[2]:g}, {a[3]:g}]"
        return f"lognormal, median {a[0]:g}, sigma(ln) {a[1]:g}"


_KEYS = {"uniform": ("low", "high"), "normal": ("mean", "sd"),
         "truncated-normal": ("mean", "sd", "low", "high"), "lognormal": ("median", "sigma")}
#: largest magnitude of a parameter value or of a distribution's key
LIMIT = 1e300
#: relative resolution: a spread below RESOLUTION x the magnitude of the values rounds
#: every sample to (nearly) one value -- a constant, not a distribution
RESOLUTION = 1e-12
#: the probabilities sampled lie in [CLIP, 1 - CLIP] (inverse transforms stay finite)
CLIP = 1e-12
#: standard normal quantile of 1 - CLIP: the farthest tail a sample reaches (7.03 sd)
Z_CLIP = 7.034483825230511
#: a truncated normal's interval must reach within this many sd of its mean (beyond, it
#: holds less than 1e-9 of the normal, and scipy's inverse loses its accuracy)
MAX_TAIL_SD = 6.0
#: most sd of a truncated normal per unit of its interval's width (wider: flat on the
#: interval, a uniform; scipy's inverse loses its accuracy)
MAX_FLAT = 1e6


def parse_parameter(name: str, table, kind: str) -> Parameter:
    """A parameter of the ``[parameters]`` table; one-line InputError naming the field."""
    where = f"parameters.{name}"
    if not isinstance(table, dict):
        raise InputError(f"{where} must be a table such as {{ distribution = \"uniform\", "
                         f"low = 1.0, high = 2.0 }}, got {type(table).__name__}")
    if kind == "grid":
        return _grid_parameter(name, table, where)
    if "values" in table or "n" in table:
        raise InputError(f"{where}: values / n make a grid axis; kind = \"{kind}\" samples "
                         f"from a distribution ({', '.join(DISTRIBUTIONS)})")
    dist = table.get("distribution")
    if not isinstance(dist, str) or dist not in _KEYS:
        raise InputError(f"{where}.distribution must be one of {', '.join(DISTRIBUTIONS)}, "
                         f"got {dist!r}")
    keys = _KEYS[dist]
    unknown = sorted(set(table) - set(keys) - {"distribution"})
    if unknown:
        raise InputError(f"{where}: unknown key {unknown[0]} for a {dist} distribution; "
                         f"allowed: {', '.join(keys)}")
    missing = [k for k in keys if k not in table]
    if missing:
        raise InputError(f"{where}.{missing[0]} missing (a {dist} distribution needs "
                         f"{', '.join(keys)})")
    a = _CHECKS[dist](where, table)
    p = Parameter(name, dist, a)
    _check_sampled(p, where)
    return p


def _key(where: str, table: dict, key: str, low: float = -LIMIT, high: float = LIMIT,
         **kw) -> float:
    return check_range(f"{where}.{key}", table[key], low, high, **kw)


def _interval(where: str, table: dict) -> tuple[float, float]:
    """(low, high) of a uniform or truncated normal: low < high, apart by more than the
    resolution of their magnitude."""
    lo, hi = _key(where, table, "low"), _key(where, table, "high")
    if not hi > lo:
        raise InputError(f"{where}.high must be greater than low = {lo:g}, got {hi:g}")
    least = RESOLUTION * max(abs(lo), abs(hi))
    if hi - lo < least:
        raise InputError(f"{where}.high must exceed low by at least {RESOLUTION:g} x "
                         f"max(|low|, |high|) = {least:.3g} (a narrower interval rounds every "
                         f"sample to one value), got high - low = {hi - lo:.3g}")
    return lo, hi


def _sd(where: str, table: dict, scale: float) -> float:
    """sd > 0 and at least the resolution of ``scale`` (the magnitude of the values)."""
    sd = _key(where, table, "sd", 0.0, low_open=True)
    least = RESOLUTION * scale
    if sd < least:
        raise InputError(f"{where}.sd must be at least {RESOLUTION:g} x the magnitude of the "
                         f"values ({least:.3g}): a smaller sd rounds every sample to the mean "
                         f"(give the value in the texture or assembly file instead), got "
                         f"{sd:.3g}")
    return sd


def _uniform(where: str, table: dict) -> tuple:
    return _interval(where, table)


def _normal(where: str, table: dict) -> tuple:
    mean = _key(where, table, "mean")
    return mean, _sd(where, table, abs(mean))


def _truncated_normal(where: str, table: dict) -> tuple:
    mean = _key(where, table, "mean")
    lo, hi = _interval(where, table)
    sd = _sd(where, table, max(abs(mean), abs(lo), abs(hi)))
    if sd > MAX_FLAT * (hi - lo):
        raise InputError(f"{where}.sd must be at most {MAX_FLAT:g} x (high - low) = "
                         f"{MAX_FLAT * (hi - lo):.3g} (a wider normal is flat on [low, high]: "
                         f"use distribution = \"uniform\"), got {sd:.3g}")
    if lo > mean + MAX_TAIL_SD * sd:
        raise InputError(f"{where}.low must be at most mean + {MAX_TAIL_SD:g} sd = "
                         f"{mean + MAX_TAIL_SD * sd:.6g} (beyond, [low, high] holds less than "
                         f"1e-9 of the normal: check mean, sd and the bounds), got {lo:.6g}")
    if hi < mean - MAX_TAIL_SD * sd:
        raise InputError(f"{where}.high must be at least mean - {MAX_TAIL_SD:g} sd = "
                         f"{mean - MAX_TAIL_SD * sd:.6g} (beyond, [low, high] holds less than "
                         f"1e-9 of the normal: check mean, sd and the bounds), got {hi:.6g}")
    return mean, sd, lo, hi


def _lognormal(where: str, table: dict) -> tuple:
    median = _key(where, table, "median", 1.0 / LIMIT)
    sigma = _key(where, table, "sigma", RESOLUTION, 10.0)
    # the sampled tails median exp(+-Z_CLIP sigma) must stay finite, positive doubles
    info = np.finfo(float)
    room = min(math.log(float(info.max) / median), math.log(median / float(info.tiny)))
    if sigma * Z_CLIP > room:
        raise InputError(f"{where}.sigma must be at most {room / Z_CLIP:.3g} with median "
                         f"{median:g} (the samples reach median x exp(+-{Z_CLIP:.2f} sigma), "
                         f"which must stay a finite positive number), got {sigma:g}")
    return median, sigma


_CHECKS = {"uniform": _uniform, "normal": _normal, "truncated-normal": _truncated_normal,
           "lognormal": _lognormal}


def _check_sampled(p: Parameter, where: str) -> None:
    """The values at the sampled extremes and the median: finite, increasing, within the
    distribution's bounds (a last guard behind the checks of each key)."""
    x = p.ppf(np.array([CLIP, 0.5, 1.0 - CLIP]))
    ok = bool(np.all(np.isfinite(x)) and x[0] < x[1] < x[2])
    if ok and p.distribution in ("uniform", "truncated-normal"):
        ok = p.args[-2] <= x[0] and x[2] <= p.args[-1]
    if not ok:
        raise InputError(f"{where}: this {p.distribution} distribution cannot be sampled in "
                         f"double precision (values {x[0]:.6g}, {x[1]:.6g}, {x[2]:.6g} at "
                         f"probabilities {CLIP:g}, 0.5, 1 - {CLIP:g}): widen or move it")


def _grid_parameter(name: str, table: dict, where: str) -> Parameter:
    if "distribution" in table:
        raise InputError(f"{where}: kind = \"grid\" takes values = [...] or low, high, n, "
                         f"not a distribution")
    if "values" in table:
        unknown = sorted(set(table) - {"values"})
        if unknown:
            raise InputError(f"{where}: unknown key {unknown[0]} beside values")
        v = table["values"]
        if not isinstance(v, list) or not v:
            raise InputError(f"{where}.values must be a non-empty list of numbers")
        if len(v) > MAX_GRID_AXIS:
            raise InputError(f"{where}.values: at most {MAX_GRID_AXIS} values, got {len(v)}")
        values = tuple(check_range(f"{where}.values[{i}]", x, -LIMIT, LIMIT)
                       for i, x in enumerate(v))
        first = {}
        for i, x in enumerate(values):
            if x in first:
                raise InputError(f"{where}.values[{i}] = {x:g} repeats values[{first[x]}]: "
                                 f"each value of a grid axis must be different")
            first[x] = i
    else:
        unknown = sorted(set(table) - {"low", "high", "n"})
        if unknown:
            raise InputError(f"{where}: unknown key {unknown[0]}; a grid axis takes values "
                             f"= [...] or low, high, n")
        missing = [k for k in ("low", "high", "n") if k not in table]
        if missing:
            raise InputError(f"{where}.{missing[0]} missing (a grid axis takes values = "
                             f"[...] or low, high, n)")
        n = check_int(f"{where}.n", table["n"], 1, MAX_GRID_AXIS)
        if n == 1:
            lo, hi = (_key(where, table, k) for k in ("low", "high"))
            if hi != lo:
                raise InputError(f"{where}.n must be at least 2 for low = {lo:g} < high = "
                                 f"{hi:g} (n = 1 keeps low only: give values = [{lo:g}] for "
                                 f"one value)")
            values = (lo,)
        else:
            lo, hi = _interval(where, table)
            most = int(min(MAX_GRID_AXIS, 1 + (hi - lo) / (RESOLUTION * max(abs(lo), abs(hi)))))
            if n > most:
                raise InputError(f"{where}.n must be at most {most} for [{lo:g}, {hi:g}] (a "
                                 f"finer grid repeats values in double precision), got {n}")
            values = tuple(float(x) for x in np.linspace(lo, hi, n))
    return Parameter(name, "grid", (), values)


def case_count(kind: str, params: list[Parameter], samples: int | None) -> int:
    """Number of cases of a study (files: given by the caller as ``samples``)."""
    if kind == "grid":
        return math.prod(len(p.values) for p in params)
    if kind == "sobol":
        return samples * (len(params) + 2)
    return samples


def sample_matrix(kind: str, params: list[Parameter], samples: int | None,
                  seed: int) -> np.ndarray:
    """(cases, parameters) float64 matrix of parameter values, row i = case i."""
    d = len(params)
    n = case_count(kind, params, samples)
    if n > MAX_CASES:
        raise InputError(f"the study has {n:.3g} cases, at most {MAX_CASES:.0e}: lower "
                         f"study.samples or the grid sizes")
    if kind == "grid":
        axes = [np.asarray(p.values, dtype=float) for p in params]
        mesh = np.meshgrid(*axes, indexing="ij")
        return np.stack([m.ravel() for m in mesh], axis=1) if d else np.zeros((1, 0))
    if kind == "monte-carlo":
        u = np.random.default_rng(seed).random((n, d))
    elif kind == "latin-hypercube":
        from scipy.stats import qmc
        u = qmc.LatinHypercube(d=d, rng=np.random.default_rng(seed)).random(n)
    elif kind == "sobol":
        u = saltelli_unit(d, samples, seed)
    else:
        raise InputError(f"study.kind {kind!r} has no sample matrix")
    u = np.clip(u, 1e-12, 1.0 - 1e-12)       # inverse transforms are finite inside (0, 1)
    return np.stack([p.ppf(u[:, j]) for j, p in enumerate(params)], axis=1)


def sobol_problem(d: int) -> dict:
    """SALib problem on the unit cube (the study maps it through the distributions)."""
    return {"num_vars": d, "names": [f"x{j}" for j in range(d)], "bounds": [[0.0, 1.0]] * d}


def saltelli_unit(d: int, base: int, seed: int) -> np.ndarray:
    """Saltelli's sample on the unit cube: (base (d + 2), d), first-order and total
    indices (no second order), from a scrambled Sobol' sequence seeded by ``seed``."""
    import warnings

    from SALib.sample import sobol as saltelli
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return saltelli.sample(sobol_problem(d), base, calc_second_order=False, scramble=True,
                               seed=seed)


#: smallest base sample N of a Sobol study: from N = 64 on, the 95 % bootstrap intervals
#: covered the exact indices of three test functions in at least 95 % of 200 seeded designs
#: (benchmarks/sobol_coverage.py); at N = 32 the Ishigami function's S1 in 88 %, at N = 1
#: the bootstrap collapses to intervals of zero width
MIN_SOBOL_BASE = 64


def check_sobol_base(samples: int) -> int:
    """The base sample N of a Sobol study: a power of two (Sobol' sequences balance only
    there; SALib's estimators assume it) of at least :data:`MIN_SOBOL_BASE`."""
    if samples < MIN_SOBOL_BASE:
        raise InputError(f"study.samples must be at least {MIN_SOBOL_BASE} for kind = "
                         f"\"sobol\" (the base sample N: with fewer, the indices' 95 % "
                         f"bootstrap intervals miss the true indices too often, and N = 1 "
                         f"gives intervals of zero width), got {samples}")
    if samples & (samples - 1):
        lo = 1 << (samples.bit_length() - 1)
        raise InputError(f"study.samples must be a power of 2 for kind = \"sobol\" (the base "
                         f"sample N of Saltelli's scheme), got {samples}; use {lo} or {2 * lo}")
    return samples
