"""Mutation testing of the generated Fortran (issue 27): cosmic-ray mutates Python, not the
Fortran text the package writes, so this script makes the mutants itself and measures how
many the FE tests kill.

    python benchmarks/fortran_mutants.py --plan            # the population per routine text
    python benchmarks/fortran_mutants.py -n 60 --seed 27   # run a seeded sample, print a table
    python benchmarks/fortran_mutants.py --json            # ... and print the results as JSON

Population: every executable line (no comment, no declaration) of the Fortran templates --
the FRIC wrapper (asperity/fe/abaqus_fric.py FRIC), the law-frame core
(asperity/fe/fortran/asp_core.f, fortran_core.CORE) and the explicit wrappers
(asperity/fe/abaqus_explicit.py VFRIC/VFRICTION body) -- times the operators: a relational
operator replaced (.LT. .LE. .GT. .GE. .EQ. .NE.), a binary + or - flipped, * and /
exchanged, a real constant changed (0.0D0 -> 1.0D0, any other x -> 2x), an array index 1
and 2 exchanged, an assignment deleted.  A mutant is applied by a pytest plugin (this file,
loaded with ``-p fortran_mutants``) that replaces the template's text in the imported module
before any test builds a routine; each mutant runs the FE test files in a fresh process
with ``-x`` (the first failure kills it).  A mutant that no longer compiles counts as
killed by the compiler (reported apart); survivors triaged in EQUIVALENT (with the reason) leave
the denominator, LEFT lists real ones without a test.  Score = killed / (mutants - compile
errors - equivalent).
"""
from __future__ import annotations

import argparse
import hashlib
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
ENV = "ASPERITY_FORTRAN_MUTANT"
TEMPLATES = (("asperity.fe.abaqus_fric", "FRIC"), ("asperity.fe.fortran_core", "CORE"),
             ("asperity.fe.abaqus_explicit", "BODY"))
TESTS = ("tests/test_fe_fric.py", "tests/test_fe_fric_family.py", "tests/test_fe_explicit.py",
         "tests/test_fe_fric_driver.py", "tests/test_fe_routines.py")
#: survivors judged equivalent (out of the score's denominator) and real ones left without a
#: test, by mutant id, with the reason (template:line of the run that found them)
EQUIVALENT = {
    '3f5ce12a74bb':
        'FRIC:31: PROPS(3) .LE. 0 for .LT. 0: differs only for PROPS(3) = 0, not a documented value (+1 or -1)',
    '05104643c6a5':
        "CORE:119: XX's start value: it is set by ASPXP before any use (only when a second root appears)",
    'dccfdad94f60':
        'CORE:128: EPS = 1e-15/(QN+1) for 1e-15*(QN+1): both are rounding-level tolerances of G and lam; no tested return moves by more than rounding',
    '720fb37e342e':
        'CORE:140: SPAN only guards blocks turning half a turn or more (then every block is searched): a wrong SPAN searches more blocks, the same roots (speed only)',
    'e2d0a88c55d0':
        'CORE:141: SPAN .LT./.GE. 0: the guard sends a block to the full search (speed only), the same roots',
    'c832017b0823':
        'CORE:141: SPAN .LT./.GE. 0: the guard sends a block to the full search (speed only), the same roots',
    'fa1fa30a3d55':
        'CORE:147: .GE. for .GT. EPS at the block bound: differs only when the bound equals EPS exactly',
    'dbd986f98c17':
        'CORE:148: .LE. for .LT. -EPS at the block bound: differs only at equality',
    'c8259314cdfc':
        'CORE:166: GHI was set and never read (the variable is gone since)',
    '4cf165f2e2d8':
        "CORE:178: .LT. for .LE. EPS in Newton's stop: equality only",
    '91d09128eb63':
        'CORE:179: .GE. for .GT. 0 in the bracket update: differs only when G = 0 exactly (then the root is found either way)',
    '60785d03d0a5':
        'CORE:206: the tie-break between two returns at the same distance: the same root found twice (at a shared node)',
    'f193694fd70c':
        'CORE:229: OUT(9) = 2 of the no-root fallback: a valid table always has a return (the winding argument: q outside C)',
    'cc7c540b531f':
        'CORE:321: MOD(ANG + TPSI(1)) for MOD(ANG - TPSI(1)): tables start at psi = 0 (the start grid), or within 4e-9 rad of it when a flat edge of D sits at 0',
    'd0243743da21':
        'CORE:393: VM = 1e-9 deleted: VM is a PARAMETER since (no assignment left to delete)',
    '1c0e9e4ae567':
        "CORE:394: R's fallback value when no segment of three holds the ray's point: never reached (the located segment or a neighbour always holds it, tested to 1e-12)",
    '895d6aeea24d':
        'BODY:5: dzero is passed as Y to ASPLAW for IOP 1 and 2, which do not read Y',
    '360f16938149':
        "BODY:59: the upper clip 0 -> 1 of the first component: a dissipative law's sliding force on the secondary node opposes t1 (first component <= 0), so the clip never acts",
}
LEFT = {
    'f61d529006a1':
        'CORE:151: a block straddling phq + 90 deg skipped when its start is ahead of q: a return there needs |q| = |P| (q on the boundary) with the force nearly perpendicular to its slip; no test law has one',
    '79e4f8ac6d97':
        "CORE:188: the Newton safeguard .GE. TH: G is nearly linear on an interval (|psi'| < 0.02 rad) and Newton from the secant guess never leaves it in the tests",
    '4ae284ac6e01':
        "BODY:30: dth = 0 when the law's axis is along the normal (its projection on the tangent plane is zero): a degenerate props(1:3) no test gives",
}
RELATIONS = (".LT.", ".LE.", ".GT.", ".GE.", ".EQ.", ".NE.")
SKIP = re.compile(r"^\s*(SUBROUTINE|subroutine|INTEGER|integer|DOUBLE|double|DIMENSION|"
                  r"dimension|PARAMETER|parameter|IMPLICIT|implicit|CHARACTER|character|"
                  r"include|INCLUDE|SAVE|RETURN|return|END|end|DATA)\b")


def _text(module: str, name: str) -> str:
    import importlib
    return getattr(importlib.import_module(module), name)


def _code_lines(text: str):
    for k, line in enumerate(text.split("\n")):
        if not line or line[0] in "Cc*!" or SKIP.match(line[6:] if len(line) > 6 else ""):
            continue
        if len(line) > 5 and line[5] not in " 0" and SKIP.match(line[6:].lstrip() or "x"):
            continue
        yield k, line


def mutants() -> list[dict]:
    """Every mutant of the population: {id, module, name, line, old, new, op}."""
    out = []
    for module, name in TEMPLATES:
        try:
            text = _text(module, name)
        except (ImportError, AttributeError):
            continue
        for k, line in _code_lines(text):
            head, body = line[:6], line[6:]
            found = []
            for rel in RELATIONS:
                for m in re.finditer(re.escape(rel), body, re.IGNORECASE):
                    for other in RELATIONS:
                        if other != rel.upper():
                            found.append(("relation", m.start(), m.end(), other))
            for m in re.finditer(r"(?<=[\w)\s])([+-])(?=[\s\w(.])", body):
                if body[:m.start()].rstrip().endswith(("=", "(", ",")):
                    continue
                found.append(("sign", m.start(), m.end(), "-" if m.group(1) == "+" else "+"))
            for m in re.finditer(r"(?<![*])([*/])(?![*])", body):
                found.append(("muldiv", m.start(), m.end(), "/" if m.group(1) == "*" else "*"))
            for m in re.finditer(r"\b(\d+\.\d*)D(-?\d+)\b", body, re.IGNORECASE):
                v = float(f"{m.group(1)}e{m.group(2)}")
                new = "1.0D0" if v == 0.0 else f"{2 * v!r}D0".replace("e", "D")
                found.append(("constant", m.start(), m.end(), new))
            for m in re.finditer(r"(?<=\()([12])(?=[),])", body):
                found.append(("index", m.start(), m.end(), "2" if m.group(1) == "1" else "1"))
            if re.match(r"\s*\w+(\([^)]*\))?\s*=", body) and line[5] in " 0":
                found.append(("delete", 0, len(body), "CONTINUE"))
            for op, a, b, new in found:
                mutated = head + body[:a] + new + body[b:]
                if len(mutated) > 72:
                    continue
                mid = hashlib.sha1(f"{module}:{name}:{line}:{op}:{a}:{new}".encode()).hexdigest()
                out.append({"id": mid[:12], "module": module, "name": name, "line": k,
                            "old": line, "new": mutated, "op": op})
    return out


def _pick(pop: list[dict], n: int, seed: int) -> list[dict]:
    key = lambda m: hashlib.sha1(f"{seed}:{m['id']}".encode()).hexdigest()
    return sorted(pop, key=key)[:n]


def run_one(m: dict, timeout: float) -> tuple[str, float, str]:
    env = {**os.environ, ENV: json.dumps(m),
           "PYTHONPATH": os.pathsep.join([str(HERE), os.environ.get("PYTHONPATH", "")])}
    tests = [t for t in TESTS if (REPO / t).is_file()]
    t0 = time.perf_counter()
    try:
        r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-x", "-p", "fortran_mutants",
                            "-p", "no:cacheprovider", *tests], check=False, cwd=REPO, env=env,
                           capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "timeout", time.perf_counter() - t0, ""
    dt = time.perf_counter() - t0
    text = r.stdout + r.stderr
    if r.returncode == 0:
        return "survived", dt, ""
    if "the template changed since the plan" in text:
        return "stale", dt, ""
    if "FortranError" in text or "Error: " in text and "gfortran" in text:
        return "compile-error", dt, ""
    last = [ln for ln in text.splitlines() if ln.startswith("FAILED")]
    return "killed", dt, last[0] if last else text.strip().splitlines()[-1]


def pytest_configure(config):                      # the plugin side
    raw = os.environ.get(ENV)
    if not raw:
        return
    import importlib
    m = json.loads(raw)
    mod = importlib.import_module(m["module"])
    lines = getattr(mod, m["name"]).split("\n")
    # the line is found by its text (the nearest copy to where the plan saw it), so a plan
    # survives edits elsewhere in the template
    at = [i for i, line in enumerate(lines) if line == m["old"]]
    assert at, "the template changed since the plan"
    k = min(at, key=lambda i: abs(i - m["line"]))
    lines[k] = m["new"]
    setattr(mod, m["name"], "\n".join(lines))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-n", type=int, default=60, help="mutants in the sample")
    ap.add_argument("--seed", type=int, default=27)
    ap.add_argument("--plan", action="store_true", help="the population only")
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds per mutant")
    ap.add_argument("--json", action="store_true", help="print the results as JSON")
    ap.add_argument("--ids", nargs="+", default=(), metavar="ID",
                    help="run only these mutants (ids from a run's JSON), in the sample or not")
    args = ap.parse_args(argv)
    pop = mutants()
    per = {}
    for m in pop:
        per.setdefault(f"{m['module']}.{m['name']}", []).append(m)
    if args.plan:
        for k, v in per.items():
            print(f"{k}: {len(v)} mutants")
        return 0
    sample = ([m for m in pop if m["id"] in set(args.ids)] if args.ids
              else _pick(pop, args.n, args.seed))
    results = []
    for i, m in enumerate(sample):
        status, dt, why = run_one(m, args.timeout)
        results.append({**m, "status": status, "seconds": round(dt, 1), "why": why})
        print(f"[{i + 1}/{len(sample)}] {status:13s} {dt:6.1f}s {m['name']}:{m['line']} "
              f"{m['op']}: {m['new'].strip()}", flush=True)
    for r in results:
        if r["status"] == "survived" and r["id"] in EQUIVALENT:
            r["status"] = "equivalent"
    counted = [r for r in results if r["status"] not in ("compile-error", "equivalent")]
    killed = sum(r["status"] in ("killed", "timeout") for r in counted)
    summary = {"population": len(pop), "sample": len(sample), "seed": args.seed,
               "compile_errors": sum(r["status"] == "compile-error" for r in results),
               "equivalent": sum(r["status"] == "equivalent" for r in results), "killed": killed,
               "survived": len(counted) - killed,
               "score": killed / len(counted) if counted else None}
    print(json.dumps(summary))
    for r in results:
        if r["status"] == "survived":
            print(f"SURVIVED {r['name']}:{r['line']} {r['op']}\n  - {r['old'].strip()}\n"
                  f"  + {r['new'].strip()}")
    if args.json:
        print(json.dumps({"summary": summary, "results": results}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
