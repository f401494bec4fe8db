"""Mutation-testing campaign (issue 25, item 5): a seeded random sample of the mutants that
cosmic-ray generates in the newest rooms, each run against the test files of its module.

    python benchmarks/mutation_campaign.py              # sample, run what is not cached, table
    python benchmarks/mutation_campaign.py --plan       # population and sample per module
    python benchmarks/mutation_campaign.py --table      # the table from the cache, no run
    python benchmarks/mutation_campaign.py --survivors  # each survivor's diff and triage
    python benchmarks/mutation_campaign.py --only contact/solver.py --fresh

The library.  cosmic-ray (PyPI, pinned below; installed in a virtual environment under
~/.cache/asperity-mutation when it is not importable) enumerates the mutants with its own
operators on a parso tree, writes each mutant into the module's file, runs the test command
with a timeout and puts the file back.  It mutates the source on disk, so numba's cache sees
the mutated kernel's file change and compiles it again (kernels included, decorated or not).
mutmut 3 cannot reach the kernels: it rewrites each function into a trampoline that picks a
variant at call time and skips decorated functions and classes (boxed/mutmut#558), so no
``@njit`` kernel and no dataclass gets a mutant.  What cosmic-ray does not know is done here:
numba's cache does not notice a change in a module a cached kernel calls into, so the caches
of the dependent kernel modules (benchmarks/mutants.py's KERNEL_DEPENDENTS) are dropped
before and after each mutant of a kernel module; and each module gets its own test files and
timeout.  Everything runs in a scratch copy of the working tree (--scratch, default
/tmp/mutcopy: the tree's files, a link to ../shared), never in the tree itself; serially.

Operators: cosmic-ray's core set, binary operators replaced within their class (arithmetic
by arithmetic, | & ^ by each other: a float given to a bit operator only raises a TypeError
every run kills).  Left out as equivalent by construction: mutants inside annotations (never
evaluated, ``from __future__ import annotations``) and inside a numba decorator (removing
``@njit`` or ``cache=True`` runs the same function, slower).  Sample: per module, the
mutants with the smallest hash of (seed, mutant id), every module the same share of --n
(stratified; the total's score is also given weighted by each module's mutants, the estimate
for the whole population).  A mutant's id is its module, operator and the text and
column of its line (not the line number), so it keeps its id, and its place in the sample,
when other lines move.  Results are cached per id in --cache with the hashes of the module
and of the test files: a killed mutant is reused while its module is unchanged, a survivor
while its test files are unchanged too.  Survivors judged equivalent (or left without a
test) are listed with the reason in benchmarks/mutation_triage.py.  Score =
(killed + timeout) / (mutants - equivalent).
"""
from __future__ import annotations

import argparse
import fcntl
import hashlib
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE))
sys.path.insert(1, str(REPO))      # mutants.py reads asperity.kernel_cache of this tree
from mutants import KERNEL_DEPENDENTS
from mutation_triage import EQUIVALENT, LEFT

COSMIC_RAY = "cosmic-ray==8.7.0"
VENV = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "asperity-mutation" / "venv"
SCOPE = ("contact/*.py", "bodies/*.py", "dynamics/body*.py", "dynamics/_body*_kernels.py",
         "laws/family*.py", "friction/elastic*.py", "surface/contact_facets.py",
         "surface/mesh_grid.py", "crawling/*.py", "fe/*.py", "cli/law_fe.py",
         "study/blocks.py", "microslip/two_node_batch.py", "microslip/_two_node_kernels.py",
         "microslip/batch.py", "microslip/_batch_kernels.py", "microslip/friction_batch.py",
         "microslip/_friction_batch_kernels.py", "microslip/strip_batch.py")
#: test files per module glob, the first match wins: globs in tests/ (missing ones ignored),
#: "file::test_name" for one test function (all its cases), and an optional third item, a
#: pytest -k expression over the whole selection (it sees file names too: "not (convergence
#: and X)" thins that file's cases and leaves the other files whole)
_CONTACT = ("test_contact_solver.py", "test_contact_invariants.py", "test_contact_capped.py",
            "test_metamorphic_contact.py", "test_option_pairs.py::test_contact_option_pairs")
_BODIES = ("test_bodies_footprint.py", "test_footprint_invariants.py",
           "test_metamorphic_bodies.py")
_BODY = ("test_body_invariants.py", "test_body_convergence.py", "test_body_limits.py",
         "test_slide_body_cli.py", "test_dynamics_body.py", "test_metamorphic_bodies.py")
#: test_body_convergence without what cannot see a kernel's or body.py's mutant (the slip
#: ratio: body_horizon's own NumPy) and a third of the pivot cases (those launched along x)
_BODY_K = "not (convergence and (slip_ratio or u02))"
#: the FE routines' tests (every module of the fe room that has no entry of its own)
_FE = ("test_fe_fric.py", "test_fe_fric_family.py", "test_fe_vfric_law.py", "test_fe_explicit.py",
       "test_fe_fric_driver.py", "test_fe_law_cli.py")
TESTS = (
    ("contact/bench.py", ("test_contact_bench_limits.py", "test_contact_oracle.py")),
    ("contact/plot.py", ("test_contact_plot.py", "test_contact_cli.py")),
    ("contact/curve.py", _CONTACT + ("test_contact_oracle.py",)),
    ("contact/*.py", _CONTACT),
    ("bodies/body_file.py", _BODIES + ("test_slide_body_cli.py",)),
    ("bodies/closed_forms.py", ("test_bodies_closed_forms.py",)),
    ("bodies/*.py", _BODIES),
    ("dynamics/body_bench.py", ("test_body_bench_measures.py", "test_bench_body.py")),
    ("dynamics/body_api.py", ("test_body_limits.py", "test_slide_body_cli.py",
                              "test_dynamics_body.py", "test_metamorphic_bodies.py",
                              "test_body_convergence.py::test_t_end_below_one_step_is_refused",
                              "test_option_pairs.py::test_slide_body_option_pairs")),
    ("dynamics/body_horizon.py", _BODY),
    # the body kernels also step crawling bodies (per-point rows): the crawl's tests too
    ("dynamics/_body*_kernels.py", _BODY + ("test_crawl.py",), _BODY_K),
    ("dynamics/*.py", _BODY, _BODY_K),
    ("laws/family_report.py", ("test_family_report.py", "test_family_axes.py",
                               "test_law_family_cli.py")),
    ("laws/family.py", ("test_family_members_and_range.py", "test_law_family.py",
                        "test_law_family_cli.py", "test_metamorphic_laws.py",
                        "test_option_pairs.py::test_law_pressure_option_pairs")),
    ("friction/elastic_windows.py", ("test_window_defaults.py", "test_contact_windows.py",
                                     "test_contact_windows_more.py",
                                     "test_option_pairs.py::test_contact_window_option_pairs")),
    ("friction/elastic.py", ("test_wedge_resolution.py", "test_contact_friction.py",
                             "test_contact_friction_cli.py", "test_metamorphic_contact.py",
                             "test_option_pairs.py::test_derive_and_fit_elastic_option_pairs")),
    ("surface/contact_facets.py", ("test_elastic_contact_inputs.py", "test_contact_friction.py",
                                   "test_contact_mesh.py", "test_metamorphic_contact.py")),
    ("surface/mesh_grid.py", ("test_mesh_grid_invariants.py", "test_contact_mesh.py",
                              "test_metamorphic_contact.py")),
    ("crawling/gait*.py", ("test_crawl_gait.py", "test_crawl.py")),
    ("crawling/design*.py", ("test_crawl_design.py",)),
    ("crawling/output.py", ("test_crawl.py", "test_crawl_cli.py")),
    ("crawling/*.py", ("test_crawl.py",)),
    ("fe/getfem*.py", ("test_fe_getfem*.py",)),
    ("fe/strip.py", ("test_fe_getfem*.py",)),
    ("fe/gwfl.py", ("test_fe_getfem*.py",)),
    ("fe/checks.py", ("test_fe_getfem*.py",)),
    ("fe/table.py", ("test_fe_table.py", "test_fe_fric.py", "test_fe_fric_family.py")),
    ("fe/abaqus_deck.py", ("test_fe_law_cli.py",)),
    ("fe/conventions_figure.py", ("test_fe_law_cli.py",)),
    ("cli/law_fe.py", ("test_fe_law_cli.py",)),
    ("fe/fortran_harness.py", ("test_fe_harness.py",) + _FE),
    ("fe/*.py", _FE),
    ("study/blocks.py", ("test_study_blocks.py",)),
    ("microslip/*two_node*.py", ("test_two_node_batch.py", "test_study_blocks.py")),
    ("microslip/strip_batch.py", ("test_strip_batch.py", "test_study_blocks.py")),
    ("microslip/*friction_batch*.py", ("test_friction_batch.py",)),
    ("microslip/_batch_kernels.py", ("test_microslip_batch.py",)),
    ("microslip/batch.py", ("test_microslip_batch.py",)),
)
#: seconds a kernel module's mutant may spend compiling its kernels and their dependents again
COMPILE_ALLOWANCE = 150.0
_BIN = re.compile(r"ReplaceBinaryOperator_(\w+?)_(\w+)$")
_ARITH = {"Add", "Sub", "Mul", "Div", "FloorDiv", "Mod", "Pow"}
_BITS = {"BitOr", "BitAnd", "BitXor"}


def ensure_library() -> None:
    """Import cosmic-ray, or install it in VENV and run this script again with VENV's Python
    (the tests still run with this interpreter, passed on in ASPERITY_MUTATION_PYTHON)."""
    try:
        import cosmic_ray  # noqa: F401
        return
    except ImportError:
        pass
    py = VENV / "bin" / "python"
    if not py.exists() or subprocess.run([py, "-c", "import cosmic_ray"], check=False).returncode:
        print(f"installing {COSMIC_RAY} in {VENV}", file=sys.stderr, flush=True)
        subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", VENV], check=True)
        subprocess.run([py, "-m", "pip", "install", "-q", COSMIC_RAY], check=True)
    env = dict(os.environ, ASPERITY_MUTATION_PYTHON=os.environ.get("ASPERITY_MUTATION_PYTHON",
                                                                   sys.executable))
    os.execve(py, [str(py), __file__, *sys.argv[1:]], env)


def sha(*parts) -> str:
    return hashlib.sha1("\0".join(map(str, parts)).encode()).hexdigest()


def scope_modules(root: Path) -> list[str]:
    pkg = root / "asperity"
    return sorted({p.relative_to(pkg).as_posix() for g in SCOPE for p in pkg.glob(g)
                   if p.name != "__init__.py"})


def tests_of(module: str, root: Path) -> tuple[list[str], str]:
    """The module's test selection: files (or file::test), and a -k expression or ''."""
    from fnmatch import fnmatch
    for pattern, files, *k in TESTS:
        if fnmatch(module, pattern):
            sel = []
            for f in files:
                name, sep, node = f.partition("::")
                sel += [p.name + sep + node for p in sorted((root / "tests").glob(name))]
            return list(dict.fromkeys(sel)), (k[0] if k else "")
    raise SystemExit(f"no test files for asperity/{module}: add it to TESTS")


def tests_hash(files, root: Path, k: str = "") -> str:
    helpers = sorted(p for p in (root / "tests").glob("*.py") if not p.name.startswith("test_"))
    texts = {f.partition("::")[0]: (root / "tests" / f.partition("::")[0]).read_text()
             for f in files}
    return sha(*files, k, *texts.values(), *[p.read_text() for p in helpers])


def _spans(tree):
    """(start, end) of every annotation and numba decorator in a parso tree."""
    out = []
    for node in _walk(tree):
        if node.type in ("tfpdef", "annassign"):
            ann = node.children[2 if node.type == "tfpdef" else 1]
            out.append((ann.start_pos, ann.end_pos))
        elif node.type == "funcdef" and getattr(node, "annotation", None) is not None:
            out.append((node.annotation.start_pos, node.annotation.end_pos))
        elif node.type == "decorator" and re.match(r"@(numba\.)?(njit|jit|vectorize)\b",
                                                   node.get_code().strip()):
            out.append((node.start_pos, node.end_pos))
    return out


def _walk(node):
    yield node
    for child in getattr(node, "children", ()):
        yield from _walk(child)


def enumerate_mutants(root: Path, module: str) -> tuple[list[dict], int]:
    """The module's mutants (those kept) and the count left out as equivalent by
    construction."""
    from cosmic_ray import plugins
    from cosmic_ray.ast import ast_nodes, get_ast_from_path
    path = root / "asperity" / module
    tree = get_ast_from_path(path)
    lines = path.read_text().splitlines()
    nodes = list(ast_nodes(tree))
    spans = _spans(tree)
    kept, dropped, seen = [], 0, {}
    for name in plugins.operator_names():
        cls = plugins.get_operator(name)
        short = name.split("/")[-1]
        b = _BIN.match(short)
        if cls.arguments() or (b and not ({b[1], b[2]} <= _ARITH or {b[1], b[2]} <= _BITS)):
            continue
        op = cls()
        occ = 0
        for node in nodes:
            for start, end in op.mutation_positions(node):
                if any(s <= start < e for s, e in spans):
                    dropped += 1
                else:
                    text = lines[start[0] - 1]
                    key = (short, text.strip(), start[1] - (len(text) - len(text.lstrip())))
                    seen[key] = seen.get(key, -1) + 1
                    kept.append({"id": f"{module}:{short}:{sha(*key, seen[key])[:10]}",
                                 "module": module, "operator": name, "occurrence": occ,
                                 "start": list(start), "end": list(end), "line": start[0]})
                occ += 1
    return kept, dropped


def plan(root: Path, per_module: int, seed: int, only=()):
    """{module: (population, dropped, sample)}: each module the same number of mutants (its
    own score then has the same resolution), the sample in rank order, kernel modules last
    (their mutants recompile kernels: the slowest)."""
    mods = scope_modules(root)
    k = per_module
    out = {}
    for m in sorted(mods, key=lambda m: (is_kernel(m), m)):
        kept, dropped = enumerate_mutants(root, m)
        if not only or m in only:
            out[m] = (len(kept), dropped, sorted(kept, key=lambda x: sha(seed, x["id"]))[:k])
    return out


def is_kernel(module: str) -> bool:
    return Path(module).name.startswith("_") and Path(module).name.endswith("_kernels.py")


def sync_scratch(scratch: Path) -> Path:
    """Copy the working tree's files (tracked and untracked, not ignored) to scratch/repo
    where they differ, with a link scratch/shared -> ../shared; returns scratch/repo.  A
    kernel file rewritten (e.g. a mutant left by a stopped run) has its dependents'
    caches dropped."""
    root = scratch / "repo"
    files = subprocess.run(["git", "-C", REPO, "ls-files", "-z", "--cached", "--others",
                            "--exclude-standard"], capture_output=True, check=True).stdout
    for rel in sorted(set(files.decode().split("\0")) - {""}):
        src, dst = REPO / rel, root / rel
        if src.is_file() and (not dst.is_file() or dst.read_bytes() != src.read_bytes()):
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst)
            if rel.startswith("asperity/"):
                drop_dependents(root, rel[len("asperity/"):])
    link = scratch / "shared"
    if not link.exists():
        link.symlink_to(REPO.parent / "shared", target_is_directory=True)
    return root


def drop_dependents(root: Path, module: str) -> None:
    for rel in KERNEL_DEPENDENTS.get(module, ()):
        mod = Path(rel)
        for c in (root / "asperity" / mod.parent / "__pycache__").glob(mod.stem + ".*.nb[ic]"):
            c.unlink()


def test_command(files, k: str = "") -> str:
    py = os.environ.get("ASPERITY_MUTATION_PYTHON", sys.executable)
    return (f"{py} -m pytest -q -x -p no:cacheprovider -p no:xdist --no-header -rfE --tb=no "
            + (f"-k {shlex.quote(k)} " if k else "")
            + " ".join(shlex.quote(f"tests/{f}") for f in files))


def first_failure(output: str | None) -> str:
    hit = re.search(r"^(?:FAILED|ERROR) (\S+)", output or "", re.MULTILINE)
    if hit:
        return re.sub(r"^tests/", "", hit.group(1))
    tail = (output or "").strip().splitlines()
    return tail[-1][:120] if tail else "?"


def run_mutant(root: Path, m: dict, files, k: str, timeout: float) -> dict:
    from cosmic_ray.mutating import mutate_and_test
    from cosmic_ray.work_item import MutationSpec, TestOutcome, WorkerOutcome
    spec = MutationSpec(root / "asperity" / m["module"], m["operator"], m["occurrence"],
                        tuple(m["start"]), tuple(m["end"]))
    drop_dependents(root, m["module"])
    t0 = time.perf_counter()
    try:
        r = mutate_and_test([spec], test_command(files, k), timeout)
    finally:
        drop_dependents(root, m["module"])
    dt = time.perf_counter() - t0
    diff = [ln for ln in (r.diff or "").splitlines()
            if ln[:1] in "+-" and ln[1:].strip() and not ln.startswith(("---", "+++"))]
    if r.worker_outcome == WorkerOutcome.NO_TEST:
        status = "stale"
    elif r.worker_outcome != WorkerOutcome.NORMAL:
        status = "incompetent"
    elif r.test_outcome == TestOutcome.SURVIVED:
        status = "survived"
    elif r.output == "timeout":
        status = "timeout"
    else:
        status = "killed"
    by = "" if status == "survived" else first_failure(r.output)
    return {"status": status, "by": by, "seconds": round(dt, 1), "diff": diff[:6]}


def baseline(root: Path, files, k: str, cache: dict, key: str) -> float:
    """Seconds of the test files on the unmutated copy (cached); stops on a failure."""
    if key in cache:
        return cache[key]
    t0 = time.perf_counter()
    out = subprocess.run(shlex.split(test_command(files, k)), cwd=root, capture_output=True,
                         text=True, check=False)
    dt = time.perf_counter() - t0
    if out.returncode:
        sys.exit(f"baseline fails ({' '.join(files)} {k}): {first_failure(out.stdout)}\n"
                 "every kill would be meaningless; stopping")
    print(f"baseline {' '.join(files)}{f' -k {k!r}' if k else ''}: pass ({dt:.0f} s)",
          flush=True)
    cache[key] = round(dt, 1)
    return dt


def save(path: Path, data: dict) -> None:
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
    os.replace(tmp, path)


def verdict(r: dict | None, mid: str) -> str:
    if r is None:
        return "pending"
    if r["status"] == "survived" and mid in EQUIVALENT:
        return "equivalent"
    return r["status"]


def table(sample: dict, results: dict) -> tuple[list[dict], dict]:
    rows = []
    for m, (_, _, pick) in sample.items():
        c = {"module": m, "mutants": len(pick)}
        for v in ("killed", "survived", "equivalent", "timeout", "pending", "other"):
            c[v] = 0
        for x in pick:
            v = verdict(results.get(x["id"]), x["id"])
            c[v if v in c else "other"] += 1
        rows.append(c)
    tot = {k: sum(r[k] for r in rows) for k in rows[0] if k != "module"} | {"module": "total"}
    for r in rows + [tot]:
        done = r["killed"] + r["timeout"] + r["survived"]
        r["score"] = round(100 * (r["killed"] + r["timeout"]) / done, 1) if done else None
    w = [(sample[r["module"]][0], r["score"]) for r in rows if r["score"] is not None]
    tot["weighted"] = round(sum(n * s for n, s in w) / sum(n for n, _ in w), 1) if w else None
    return rows, tot


def print_table(rows, tot) -> None:
    cols = ("mutants", "killed", "survived", "equivalent", "timeout", "pending", "other")
    print(f"\n| module | {' | '.join(cols)} | score |\n|---|" + "---:|" * (len(cols) + 1))
    for r in rows + [tot]:
        s = "-" if r["score"] is None else f"{r['score']:.1f} %"
        print(f"| {r['module']} | " + " | ".join(str(r[c]) for c in cols) + f" | {s} |")
    if tot.get("weighted") is not None:
        print(f"\nweighted by each module's mutants (population estimate): {tot['weighted']:.1f} %")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--per-module", type=int, default=8, metavar="K",
                    help="mutants sampled in each module (default 8)")
    ap.add_argument("--seed", type=int, default=25, help="sampling seed (default 25)")
    ap.add_argument("--scratch", type=Path, default=Path("/tmp/mutcopy"),
                    help="scratch copy of the working tree (default /tmp/mutcopy)")
    ap.add_argument("--cache", type=Path, default=HERE / "mutation_results.json",
                    help="results per mutant id (default benchmarks/mutation_results.json)")
    ap.add_argument("--only", nargs="+", default=(), metavar="MODULE",
                    help="only these modules (paths under asperity/)")
    ap.add_argument("--fresh", action="store_true", help="run again what is cached")
    ap.add_argument("--ids", nargs="+", default=(), metavar="ID",
                    help="only these mutants, run again, in the sample or not (e.g. to check "
                         "a new test: with another --scratch and --cache while a campaign "
                         "runs)")
    ap.add_argument("--plan", action="store_true", help="population and sample, no run")
    ap.add_argument("--table", action="store_true", help="the table from the cache, no run")
    ap.add_argument("--survivors", action="store_true", help="list survivors with their diffs")
    ap.add_argument("--json", type=Path, help="also write the table and results as JSON")
    ap.add_argument("--merge", type=Path, metavar="CACHE",
                    help="first take the kills recorded in another cache file")
    a = ap.parse_args(argv)
    ensure_library()
    run = not (a.plan or a.table or a.survivors)
    if run:
        a.scratch.mkdir(parents=True, exist_ok=True)
        lock = open(a.scratch / ".lock", "w")   # noqa: SIM115 (held until the process ends)
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            sys.exit(f"another campaign runs in {a.scratch}; stopping")
    root = sync_scratch(a.scratch) if run else REPO   # reading needs no copy
    only = set(a.only) | {i.split(":")[0] for i in a.ids}
    sample = plan(root, a.per_module, a.seed, only)
    data = json.loads(a.cache.read_text()) if a.cache.is_file() else {}
    results, base = data.setdefault("results", {}), data.setdefault("baselines", {})
    if a.merge:
        print(f"{merge(data, a.merge)} kills taken from {a.merge}", flush=True)
        save(a.cache, data)
    if a.plan:
        for m, (n, dropped, pick) in sample.items():
            files, k = tests_of(m, root)
            print(f"{m:34s} {n:5d} mutants ({dropped} equivalent by construction), "
                  f"{len(pick)} sampled, tests: {' '.join(files)}"
                  + (f" -k {k!r}" if k else ""))
        return 0
    if run:
        os.chdir(root)
        os.environ["PYTHONPATH"] = str(root)
        for m, (_, _, pick) in sample.items():
            files, k = tests_of(m, root)
            mh = sha((root / "asperity" / m).read_text())
            th = tests_hash(files, root, k)
            if a.ids:       # any of the module's mutants, in the sample or not
                todo = [x for x in enumerate_mutants(root, m)[0] if x["id"] in a.ids]
            else:
                todo = [x for x in pick if a.fresh or not reusable(results.get(x["id"]), mh, th)]
            if not todo:
                continue
            bkey = sha(th, *[(root / "asperity" / p).read_bytes()
                             for p in sorted(scope_modules(root))], *files, k)
            timeout = (3 * baseline(root, files, k, base, bkey) + 60
                       + COMPILE_ALLOWANCE * is_kernel(m))
            for x in todo:
                r = run_mutant(root, x, files, k, timeout)
                results[x["id"]] = x | r | {"module_hash": mh, "tests_hash": th,
                                            "tests": files, "k": k}
                save(a.cache, data)
                print(f"{r['status']:9s} {x['id']:58s} {r['seconds']:6.1f} s  {r['by']}",
                      flush=True)
    rows, tot = table(sample, results)
    if a.survivors:
        for m, (_, _, pick) in sample.items():
            for x in pick:
                r = results.get(x["id"])
                if r and r["status"] == "survived":
                    why = EQUIVALENT.get(x["id"]) or LEFT.get(x["id"]) or "NOT TRIAGED"
                    print(f"{x['id']}  (line {r['line']}): {why}\n    " +
                          "\n    ".join(d for d in r["diff"] if d[1:].strip()))
    print_table(rows, tot)
    if a.json:
        save(a.json, {"table": rows + [tot], "seed": a.seed,
                      "per_module": a.per_module,
                      "results": {x["id"]: results.get(x["id"]) for _, _, p in
                                  sample.values() for x in p}})
    return 0


def reusable(r: dict | None, module_hash: str, tests_hash_: str) -> bool:
    """A cached result still holds: the module unchanged and the mutant killed, or judged
    equivalent (a property of the code, not of the tests), or run with these tests."""
    if r is None or r.get("module_hash") != module_hash:
        return False
    return r["status"] in ("killed", "timeout") or r.get("tests_hash") == tests_hash_ or \
        (r["status"] == "survived" and r["id"] in EQUIVALENT)


def merge(data: dict, other: Path) -> int:
    """Take the kills of another cache (a campaign run elsewhere, e.g. in a second scratch
    to check new tests) for mutants this one has not killed; returns how many."""
    got = 0
    for mid, r in json.loads(other.read_text()).get("results", {}).items():
        mine = data["results"].get(mid)
        if r["status"] in ("killed", "timeout") and (mine is None or mine["status"] not in (
                "killed", "timeout")) and (mine is None or
                                           mine["module_hash"] == r["module_hash"]):
            data["results"][mid] = r
            got += 1
    return got


if __name__ == "__main__":
    sys.exit(main())
