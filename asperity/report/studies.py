"""Report section: studies -- the statistics of the study engine against closed forms (the
probability of ratchet of the two-node model, the Sobol indices of the Ishigami function)
and the tolerance study of the shipped bushing with its figures."""
from __future__ import annotations

import math
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
SURF = ROOT / "surfaces"


def _two_node(tmp: Path) -> list[str]:
    from ..study.run import run_study_file
    f = tmp / "two-node-p.toml"
    f.write_text(f"""
[study]
kind = "monte-carlo"
samples = 4000
seed = 4
assembly = "{SURF / 'two-node-spec.toml'}"
[parameters]
"loading.dT_max" = {{ distribution = "uniform", low = 50.0, high = 150.0 }}
""")
    s = run_study_file(f, tmp / "two-node", workers=0)
    dT_c = 0.1 * 100.0 * (1 / 1e6 + 2 / 5e5) / (1.2e-5 * 0.1)
    exact = (150.0 - 2 * dT_c) / 100.0
    p = s["p_ratchet"]
    by = ", ".join(f"{k} {n}" for k, n in (s.get("solved_by") or {}).items())
    return ["### Probability of ratchet against its closed form", "",
            "The SPEC.md two-node assembly (dT_c = 41.67 K) under cycles 0 -> dT_max with "
            "dT_max uniform in [50, 150] K ratchets iff dT_max > 2 dT_c: P = (150 - 2 dT_c) / "
            "100.  Monte Carlo through the study engine (4000 cases, seed 4, in process):", "",
            "| closed form | estimate | 95 % interval (Wilson) | covered |", "|---|---|---|---|",
            f"| {exact:.5f} | {p['estimate']:.5f} | {p['low']:.5f} - {p['high']:.5f} | "
            f"{'yes' if p['low'] <= exact <= p['high'] else 'NO'} |", "",
            f"Solved by (the store's `solved_by`): {by}.", ""]


def _ishigami() -> list[str]:
    from ..study import sampling
    from ..study.summary import sobol_indices
    a, b = 7.0, 0.1
    V = a * a / 8 + b * math.pi ** 4 / 5 + b * b * math.pi ** 8 / 18 + 0.5
    V1 = 0.5 * (1 + b * math.pi ** 4 / 5) ** 2
    V13 = b * b * math.pi ** 8 * (1 / 18 - 1 / 50)
    exact = {"x1": (V1 / V, (V1 + V13) / V), "x2": (a * a / 8 / V, a * a / 8 / V),
             "x3": (0.0, V13 / V)}
    ps = [sampling.parse_parameter(f"texture.{n}", {"distribution": "uniform",
                                                    "low": -math.pi, "high": math.pi}, "sobol")
          for n in exact]
    lines = ["### Sobol indices of the Ishigami function", "",
             "f = sin x1 + 7 sin^2 x2 + 0.1 x3^4 sin x1, x_i uniform on [-pi, pi], through the "
             "study's Sobol path (its Saltelli sample, seeded; SALib's indices with 95 % "
             "bootstrap intervals):", "",
             "| N | input | S1 exact | S1 estimate | ST exact | ST estimate | within |",
             "|---|---|---|---|---|---|---|"]
    for N in (1024, 8192):
        X = sampling.sample_matrix("sobol", ps, N, seed=3)
        Y = np.sin(X[:, 0]) + a * np.sin(X[:, 1]) ** 2 + b * X[:, 2] ** 4 * np.sin(X[:, 0])
        si = sobol_indices(Y, [p.name for p in ps], seed=1)
        for (name, (s1, st)), p in zip(exact.items(), ps):
            v = si[p.name]
            ok = abs(v["S1"] - s1) <= v["S1_conf"] and abs(v["ST"] - st) <= v["ST_conf"]
            lines.append(f"| {N} | {name} | {s1:.4f} | {v['S1']:.4f} +- {v['S1_conf']:.4f} | "
                         f"{st:.4f} | {v['ST']:.4f} +- {v['ST_conf']:.4f} | "
                         f"{'yes' if ok else 'no'} |")
    return lines + [""]


def _bushing(folder: Path, tmp: Path) -> list[str]:
    from ..study.run import run_study_file
    from ..study.text import lines as summary_lines
    from ..study.plot import figures
    from ..study.store import read_store
    s = run_study_file(SURF / "bushing-tolerance.toml", tmp / "bushing", workers=0)
    store = read_store(tmp / "bushing")
    try:
        figures(store, s, folder, prefix="study_")
    finally:
        store.close()
    text = [x for x in summary_lines(s) if not x.startswith("store:")]
    return ["### The shipped bushing under production scatter", "",
            "`asperity study surfaces/bushing-tolerance.toml --plot`: wedge angles normal "
            "(sd 1.5 deg), face friction +-20 % (uniform), temperature swing uniform in "
            "90-140 K; 10 000 cases (run in process here):", "", "```", *text, "```", "",
            "![drift per cycle](study_drift.png)", "",
            "![verdict over the two most influential parameters](study_verdicts.png)", ""]


def section(folder: Path) -> list[str]:
    """Markdown lines of the section; writes study_drift.png and study_verdicts.png."""
    folder = Path(folder)
    lines = ["## Studies: statistics against closed forms, a tolerance study", "",
             "The study engine (`asperity study`) runs every case through the public API, "
             "or, for risk studies, through the block path: blocks of cases as arrays, the "
             "two-node model in closed form and the strip by the exact event solver over "
             "the whole block, each case equal to the single-case call (tests compare them "
             "case by case); the store's `solved_by` column says which path answered each "
             "case.  What is checked here is the statistics on top.", ""]
    with tempfile.TemporaryDirectory(prefix="asperity-report-") as tmp:
        tmp = Path(tmp)
        lines += _two_node(tmp)
        lines += _ishigami()
        lines += _bushing(folder, tmp)
    return lines
