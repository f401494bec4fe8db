"""mu+ and mu- of a block of wedge textures (issue 28): cases per second of one
:func:`asperity.microslip.friction_batch.texture_friction_batch` call against the per-case
path it stands in for, on the bushing tolerance study's texture
(``surfaces/bushing-tolerance.toml``: alpha, beta, mu_alpha, mu_beta varied; slip axis and
textured face from the assembly), and checks that the two agree on every case timed.

Per-case loops timed: ``friction_from_texture(texture_from_dict(table_i))`` (the
friction alone) and the study's route (``cases._texture`` then ``assembly_friction``, as
``cases.evaluate`` does).  One core, numba limited to one thread, as in a study worker.

Run:  python benchmarks/bench_friction_batch.py [--cases N] [--loop-cases N] [--repeats R] [--json]
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def bench(n_cases: int = 10_000, loop_cases: int = 2_000, repeats: int = 5) -> dict:
    import numba

    from asperity.microslip.friction import friction_from_texture
    from asperity.microslip.friction_batch import resolve_slip_rules, texture_friction_batch
    from asperity.microslip.risk import assembly_friction
    from asperity.study.cases import _texture, build_inputs
    from asperity.study.spec import load_study
    from asperity.texture.wedges import texture_from_dict
    numba.set_num_threads(1)
    study = load_study(ROOT / "surfaces" / "bushing-tolerance.toml")
    spec, names = study.spec, study.parameter_names
    M = study.matrix()                               # the study's 10 000 sampled cases
    X = M[np.arange(n_cases) % len(M)]
    tex_names = [n for n in names if n.startswith("texture.")]
    varied = {n.split(".", 1)[1]: X[:, names.index(n)] for n in tex_names}
    _, asm = build_inputs(spec, {}, None)
    axis, face = resolve_slip_rules(asm.friction_table, spec.get("slip_axis_deg"),
                                    spec.get("textured"))
    kw = {"contact": spec["contact"], "slip_axis_deg": axis, "textured": face}

    t0 = time.perf_counter()
    texture_friction_batch(spec["texture"], {k: v[:2] for k, v in varied.items()}, **kw)
    first = time.perf_counter() - t0                 # compile, or load numba's cache
    block = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        mp, mm, ok = texture_friction_batch(spec["texture"], varied, **kw)
        block.append(time.perf_counter() - t0)

    n = min(loop_cases, n_cases)
    t0 = time.perf_counter()
    for i in range(n):
        t = dict(spec["texture"], **{k: float(v[i]) for k, v in varied.items()})
        f = friction_from_texture(texture_from_dict(t), kw["contact"], axis, face)
    friction_loop = time.perf_counter() - t0
    worst = 0.0
    t0 = time.perf_counter()
    for i in range(n):
        tex = _texture(spec, {k: float(X[i, names.index(k)]) for k in tex_names})
        f = assembly_friction(asm, tex, contact=spec["contact"],
                              slip_axis_deg=spec.get("slip_axis_deg"),
                              textured=spec.get("textured"))
        if not ok[i]:
            raise RuntimeError(f"case {i}: the block refused a case the per-case path takes")
        worst = max(worst, abs(mp[i] - f.mu_plus) / f.mu_plus,
                    abs(mm[i] - f.mu_minus) / f.mu_minus)
    study_loop = time.perf_counter() - t0
    best = min(block)
    return {"cases": n_cases, "fields": sorted(varied), "first_call_s": first,
            "block_s": best, "block_cases_per_s": n_cases / best,
            "block_us_per_case": 1e6 * best / n_cases, "loop_cases": n,
            "friction_loop_cases_per_s": n / friction_loop,
            "study_loop_cases_per_s": n / study_loop,
            "study_loop_ms_per_case": 1e3 * study_loop / n,
            "speed_up_vs_study_loop": (n_cases / best) / (n / study_loop),
            "max_relative_difference": worst, "ok": int(ok.sum())}


def format_bench(r: dict) -> str:
    lines = [
        (f"block of {r['cases']} cases ({', '.join(r['fields'])} varied): "
         f"{r['block_cases_per_s']:.3g} cases/s ({r['block_us_per_case']:.3g} us a case; "
         f"first call {r['first_call_s']:.3g} s)"),
        (f"per-case friction_from_texture(texture_from_dict(...)): "
         f"{r['friction_loop_cases_per_s']:.3g} cases/s"),
        (f"per-case study route (_texture + assembly_friction): "
         f"{r['study_loop_cases_per_s']:.3g} cases/s ({r['study_loop_ms_per_case']:.3g} ms a "
         f"case); the block {r['speed_up_vs_study_loop']:.0f}x"),
        (f"max relative difference over {r['loop_cases']} cases: "
         f"{r['max_relative_difference']:.3g}")]
    return "\n".join(lines)


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cases", type=int, default=10_000, help="cases in the block")
    p.add_argument("--loop-cases", type=int, default=2_000, help="cases of the per-case loops")
    p.add_argument("--repeats", type=int, default=5, help="block calls timed (best kept)")
    p.add_argument("--json", action="store_true", help="print the figures as JSON")
    a = p.parse_args()
    out = bench(a.cases, a.loop_cases, a.repeats)
    print(json.dumps(out, indent=2) if a.json else format_bench(out))
