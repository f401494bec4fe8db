"""Mutation testing of the physics (issue 11, class 9): plant one small realistic bug at a
time in a *copy* of the package and see whether the physics tests catch it.

Each mutant is a text substitution in one library file (it must match exactly once, else the
mutant is reported ``stale``: the code moved, update the mutant).  The package is copied
once into a temporary folder (with its numba caches, mtimes kept, so unchanged kernels are
not recompiled); each mutant gets its own copy of that snapshot, the bug is planted there,
and pytest runs the mutant's test files with that copy first on ``sys.path``.  The working
tree is never touched, so others' tests never see a planted bug.

    python benchmarks/mutants.py                  # every mutant: caught / missed table
    python benchmarks/mutants.py --list           # names, files, what each plants
    python benchmarks/mutants.py --check          # does every mutant still apply?
    python benchmarks/mutants.py NAME [NAME ...]  # only these
    python benchmarks/mutants.py --json out.json  # also write the results as JSON
    python benchmarks/mutants.py --from-head      # mutate the committed package instead

A mutant is ``caught`` when its tests fail (the first failing test is shown), ``missed``
when they pass.  Before the mutants, the same test files run on the unmutated copy
(``--no-baseline`` skips it): a failing baseline makes every "caught" meaningless and
stops the run.  Tests run serially (one core) with ``-x``; the whole list takes about
five minutes on a quiet machine (kernel mutants recompile their numba kernels).
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
TESTS = REPO / "tests"

#: numba kernel modules and the kernel modules that compile them in (numba's cache does not
#: notice a change in a module a cached kernel calls into: their caches are dropped too)
KERNEL_DEPENDENTS = {
    "laws/_set_kernels.py": ("laws/_law_kernels.py", "dynamics/_moreau_kernels.py"),
    "laws/_law_kernels.py": ("dynamics/_moreau_kernels.py",),
    "texture/_tip_kernels.py": ("texture/_spring_kernels.py",),
    "microslip/_chain_kernels.py": ("microslip/_dynamic_kernels.py",
                                    "microslip/_march_kernels.py"),
}

TEXTURE = ("test_texture_closed_form.py", "test_law_fitting.py", "test_derive_cli.py")
FRICTION = ("test_texture_closed_form.py", "test_surface_facets.py", "test_derive_cli.py",
            "test_friction_facet_kernel.py", "test_law_fitting.py")
LAWS = ("test_law_sets.py", "test_law_fitting.py", "test_gauge_file.py", "test_fit_law_cli.py",
        "test_dynamics_moreau.py")
DYNAMICS = ("test_dynamics_moreau.py", "test_slide_cli.py")
MICROSLIP = ("test_microslip.py", "test_microslip_verdict.py", "test_microslip_risk.py",
             "test_risk_cli.py", "test_chain_reference.py")
CHAIN = ("test_microslip_events.py", "test_chain_reference.py", "test_microslip.py",
         "test_hostile_microslip.py")
PROCS = "test_processes.py"
SURFACE = ("test_surface_facets.py", "test_surface_detrend_friction_map.py",
           "test_surface_measured.py", "test_derive_cli.py")


@dataclass(frozen=True)
class Mutant:
    name: str
    path: str           # relative to asperity/
    old: str
    new: str
    tests: tuple        # test files (in tests/) to run
    what: str           # the bug, in words


MUTANTS = [
    # ---- the five that the suite missed in issue 11
    Mutant("admissibility-hard-wired", "friction/diagnostics.py",
           "return Admissibility(dmin >= -ADMISSIBILITY_TOL, dmin,",
           "return Admissibility(True, dmin,",
           ("test_texture_closed_form.py", "test_derive_cli.py", "test_law_fitting.py"),
           "check_admissibility always answers admissible"),
    Mutant("csv-not-principal-frame", "laws/export.py",
           "p = _to_local(f.p, theta)", "p = f.p",
           ("test_fit_law_cli.py", "test_gauge_file.py", "test_law_fitting.py"),
           "the CSV polar table is left in the x-y frame, not turned into t_a, t_b"),
    Mutant("criterion-minus-one", "laws/sets.py",
           'return self.gauge(points_array("tau", tau)) - sn',
           'return self.gauge(points_array("tau", tau)) - 1.0',
           ("test_law_sets.py", "test_law_fitting.py"),
           "truncated-ellipse criterion g = k(tau) - 1 instead of k(tau) - sigma_n"),
    Mutant("strip-dTc-mu-minus", "microslip/closed_forms.py",
           "return min(mp, mm) * p * lam", "return mm * p * lam", MICROSLIP,
           "strip elastic limit with mu- instead of min(mu+, mu-)"),
    Mutant("wl-stick-ignores-alpha", "laws/_law_kernels.py",
           "t = k * rd / (1.0 - k + k * rd / rc)", "t = k * rc",
           ("test_law_sets.py", "test_dynamics_moreau.py"),
           "Walker-Leine sticking map scales y to C's gauge k_D(y), ignoring alpha"),
    # ---- texture
    Mutant("H-denominator-sign", "texture/closed_form.py",
           "den = 1.0 - x * t", "den = 1.0 + x * t", TEXTURE,
           "H(x, y) = (x + tan y)/(1 + x tan y): sign error in Antoni's eq. 8"),
    Mutant("mu-b-cos-multiplied", "texture/closed_form.py",
           "mu_alpha * tb / math.cos(alpha)", "mu_alpha * tb * math.cos(alpha)", TEXTURE,
           "mu_b: multiplied by cos(alpha) instead of divided"),
    Mutant("springs-kt-without-density", "texture/spring_model.py",
           "return self.density * self.k_f", "return self.k_f",
           ("test_texture_springs.py", "test_derive_cli.py"),
           "tangential stiffness per unit area k_t = k_f (density dropped)"),
    # ---- friction
    Mutant("face-friction-sign", "friction/faces.py",
           "fz = 1.0 / nrm - mu * slope / vlen", "fz = 1.0 / nrm + mu * slope / vlen",
           FRICTION, "vertical part of m - mu v/|v| with the friction term's sign flipped"),
    Mutant("facet-kernel-leeward", "friction/_facet_kernels.py",
           "g2 = gy[i]\n        wi = w[i]\n        sl = g1 * c + g2 * s\n"
           "        q = math.sqrt(1.0 + sl * sl)\n        aq = a[i] * q\n        d = aq - m * sl\n"
           "        wind = sl > stol",
           "g2 = gy[i]\n        wi = w[i]\n        sl = g1 * c + g2 * s\n"
           "        q = math.sqrt(1.0 + sl * sl)\n        aq = a[i] * q\n        d = aq - m * sl\n"
           "        wind = sl < -stol",
           FRICTION + ("test_surface_measured.py",),
           "windward facet kernel (one mu for all facets) loads the lee faces"),
    Mutant("principal-direction-no-half", "friction/derive.py",
           "theta = float(np.mod(0.5 * np.angle(c2), np.pi))",
           "theta = float(np.mod(np.angle(c2), np.pi))",
           ("test_surface_facets.py", "test_derive_cli.py", "test_surface_measured.py"),
           "principal direction: phase of the 2nd harmonic not halved"),
    Mutant("anisotropy-over-max", "friction/derive.py",
           "return float((T.max() - T.min()) / T.mean())",
           "return float((T.max() - T.min()) / T.max())",
           ("test_surface_facets.py", "test_derive_cli.py", "test_surface_measured.py"),
           "anisotropy divided by max T instead of mean T"),
    # ---- laws
    Mutant("ellipse-mu-a-swapped", "laws/sets.py",
           "A = np.where(xl[:, 0] >= 0, self.mu_a_plus, self.mu_a_minus)",
           "A = np.where(xl[:, 0] >= 0, self.mu_a_minus, self.mu_a_plus)", LAWS,
           "truncated ellipse: mu_a+ and mu_a- swapped"),
    Mutant("sliding-rule-sign", "laws/fitting.py",
           "D = ConvexSet(psi, h, h * np.tan(dc))", "D = ConvexSet(psi, h, -h * np.tan(dc))",
           LAWS, "fit_star: h' = -h tan(delta), the sliding rule's sign flipped"),
    Mutant("abaqus-degrees-as-radians", "laws/export.py",
           "theta = math.radians(gl.principal_direction_deg)\n    data",
           "theta = gl.principal_direction_deg\n    data",
           ("test_fit_law_cli.py", "test_law_fitting.py"),
           "orthotropic (Abaqus) fit in a frame turned by degrees read as radians"),
    # ---- dynamics
    Mutant("moreau-midpoint-full-step", "dynamics/_moreau_kernels.py",
           "qm[j] = q[j] + 0.5 * dt * u[j]", "qm[j] = q[j] + dt * u[j]", DYNAMICS,
           "Moreau midpoint q_M = q_A + dt u_A (factor 1/2 missing)"),
    Mutant("moreau-torque-sign", "dynamics/_moreau_kernels.py",
           "ue[2] -= minv[2] * (ow[i, 0] * P[i, 1] - ow[i, 1] * P[i, 0])",
           "ue[2] -= minv[2] * (ow[i, 0] * P[i, 1] + ow[i, 1] * P[i, 0])", DYNAMICS,
           "rigid body: torque of a contact impulse with a sign error (r x P)"),
    Mutant("stop-distance-factor-2", "dynamics/references.py",
           "return u0 * u0 / (2.0 * mu * g)", "return u0 * u0 / (mu * g)", DYNAMICS,
           "closed-form Coulomb stop distance u0^2/(mu g) (factor 2 missing)"),
    # ---- microslip
    Mutant("two-node-dTc-factor-2", "microslip/closed_forms.py",
           "(1.0 / k + 2.0 / k_t)", "(1.0 / k + 1.0 / k_t)", MICROSLIP,
           "two-node dT_c with 1/k_t instead of 2/k_t"),
    Mutant("two-node-drift-direction", "microslip/closed_forms.py",
           "(-1.0 if mp > mm else 1.0)", "(-1.0 if mp < mm else 1.0)", MICROSLIP,
           "closed-form drift towards the larger coefficient"),
    Mutant("strip-dTc-coth-full-length", "microslip/closed_forms.py",
           "math.tanh(0.5 * lam * l)", "math.tanh(lam * l)", MICROSLIP,
           "strip dT_c with coth(lam l) instead of coth(lam l / 2)"),
    Mutant("elastic-limit-max", "microslip/chains.py",
           "= float(lim.min())", "= float(lim.max())", MICROSLIP,
           "chain elastic limit: the last slider to slip instead of the first"),
    Mutant("march-one-cycle-short", "microslip/quasi_static.py",
           "for c in range(1, cycles + 1):", "for c in range(1, cycles):", MICROSLIP,
           "quasi-static march: one cycle fewer than asked (off by one)"),
    Mutant("gauge-mu-minus-at-90-deg", "microslip/friction.py",
           "psi = math.radians(psi_deg) + np.array([0.0, math.pi])\n    f = law.force(psi)",
           "psi = math.radians(psi_deg) + np.array([0.0, 0.5 * math.pi])\n    f = law.force(psi)",
           MICROSLIP + ("test_gauge_file.py",),
           "mu- of a gauge taken at +90 deg instead of +180 deg"),
    # ---- the exact march of the slider chain (issue 18)
    Mutant("chain-series-spring", "microslip/_chain_kernels.py",
           "            sr = kb[e] * G[e] / (kb[e] + G[e])\n            p = sr",
           "            sr = min(kb[e], G[e])\n            p = sr", CHAIN,
           "condensation: an element and the part left of it combined by min, not in series"),
    Mutant("chain-no-least-motion", "microslip/_chain_kernels.py",
           "    t = min(max(t, tlo), thi)", "    t = min(max(0.0, tlo), thi)", CHAIN,
           "a chain free to translate takes the smallest admissible shift, not least motion"),
    Mutant("chain-degenerate-kept", "microslip/_chain_kernels.py",
           "if code == 0 and _all_at_bounds(", "if code == 3 and _all_at_bounds(", CHAIN,
           "a degenerate solution (a slider stuck exactly at a bound) kept, not the family's "
           "least motion"),
    Mutant("chain-ties-missed", "microslip/_chain_kernels.py",
           "AT_THRESHOLD = 1e-13", "AT_THRESHOLD = 1e-17", CHAIN,
           "a slider within rounding of its threshold not taken as at it (ties missed)"),
    Mutant("march-increment-under-force-change", "microslip/_march_kernels.py",
           "    if dF != 0.0:\n        return False", "    if dF != dF:\n        return False",
           CHAIN, "a segment whose force changes taken in one increment (inexact)"),
    Mutant("march-increment-unchecked-start", "microslip/_march_kernels.py",
           "        if st[i] != 0 and guess[i] != st[i]:\n            return False",
           "        if st[i] != 0 and guess[i] != st[i] and n < 0:\n            return False",
           CHAIN, "the increment taken although a slider sliding at the start stopped in it"),
    # ---- surface
    Mutant("detrend-dropped", "surface/detrend.py",
           "heights=surface.heights - fit.form(", "heights=surface.heights + 0 * fit.form(",
           SURFACE,
           "height-map form removal returns the heights unchanged"),
    Mutant("heightmap-gy-over-dx", "surface/grid_facets.py",
           "(1, dy, ((z01, z00), (z11, z10)))", "(1, dx, ((z01, z00), (z11, z10)))",
           SURFACE, "height-map facet slope dz/dy divided by dx (non-square pixels)"),
    # ---- processes, locks, workers, schedulers (issue 18, sections 3 and 4)
    Mutant("lifeline-no-death-signal", "lifeline.py",
           "return prctl is not None and prctl(PR_SET_PDEATHSIG, int(sig), 0, 0, 0) == 0",
           "return False",
           (f"{PROCS}::test_dask_workers_die_with_the_client_even_inside_a_kernel",),
           "no parent-death signal: only the watch thread, which a kernel holding the "
           "interpreter lock keeps from running"),
    Mutant("dask-workers-not-watching", "study/clusters.py",
           "preload=[lifeline.PRELOAD],", "preload=[],",
           (f"{PROCS}::test_dask_workers_die_with_the_client_even_inside_a_kernel",),
           "local Dask workers without the lifeline preload (only Dask's own watch)"),
    Mutant("serve-worker-not-watching", "web/worker.py",
           "    die_with_parent(parent)\n", "",
           (f"{PROCS}::test_serve_killed_mid_study_takes_its_workers_and_the_restart_"
            "finishes_it",),
           "a worker of asperity serve does not watch the server: it goes on with its study"),
    Mutant("stale-lock-kept", "locks.py",
           "                    _replace_lock(path)            # apart",
           "                    pass                           # apart",
           (f"{PROCS}::test_a_lock_left_to_a_child_of_a_finished_holder_is_taken_over",),
           "a lock left to a forked child of a finished holder is never taken over"),
    Mutant("lock-shared", "locks.py",
           "fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)",
           "fcntl.flock(fh, fcntl.LOCK_SH | fcntl.LOCK_NB)",
           (f"{PROCS}::test_two_studies_on_one_folder_exclude_each_other_and_a_killed_one_"
            "frees_it", f"{PROCS}::test_two_servers_on_one_data_folder_exclude_each_other"),
           "the folder lock is a shared lock: two runs on one folder both get it"),
    Mutant("worker-cap-ignores-memory", "resources.py",
           "n = max(1, min(want, cores, fit))", "n = max(1, min(want, cores))",
           (f"{PROCS}::test_local_workers_fit_the_cores_and_the_free_memory",
            f"{PROCS}::test_study_with_1000_workers_starts_what_the_machine_allows"),
           "local workers limited by the cores only, not by the free memory"),
    Mutant("worker-cap-ignores-cores", "resources.py",
           "n = max(1, min(want, cores, fit))", "n = max(1, min(want, fit))",
           (f"{PROCS}::test_local_workers_fit_the_cores_and_the_free_memory",
            f"{PROCS}::test_study_with_1000_workers_starts_what_the_machine_allows"),
           "local workers limited by the free memory only, not by the cores"),
    Mutant("scheduler-port-unchecked", "study/clusters.py",
           "if not 1 <= port <= 65535:", "if port < 0:",
           (f"{PROCS}::test_bad_schedulers_are_refused_in_one_line_and_leave_nothing",),
           "a scheduler port out of range reaches the socket library"),
    Mutant("scheduler-silence-misread", "study/clusters.py",
           "    if not head:\n", "    if not head and False:\n",
           (f"{PROCS}::test_bad_schedulers_are_refused_in_one_line_and_leave_nothing",),
           "a service that sends nothing (an HTTP server) is said to answer in another "
           "protocol (handing it to Dask instead hangs the client: no mutant for that)"),
    Mutant("failed-run-leaves-its-store", "study/run.py",
           "        store.discard()", "        store.close()",
           (f"{PROCS}::test_a_run_that_fails_before_its_first_case_leaves_the_folder_as_it_"
            "was",),
           "a run that fails before its first case leaves an empty store behind"),
    Mutant("store-without-tables-stuck", "study/store.py",
           "new = con.execute(\"SELECT 1 FROM sqlite_master WHERE type = 'table'\").fetchone() "
           "is None", "new = db.stat().st_size == 0",
           (f"{PROCS}::test_a_store_killed_before_its_tables_were_made_is_taken_as_new",),
           "a store file left without tables (a kill before the first transaction) refused "
           "for ever unless it is empty"),
]


def snapshot(dest: Path, from_head: bool = False) -> Path:
    """Copy asperity/ (numba caches included, mtimes kept) into dest, or with ``from_head``
    the committed package (``git archive HEAD``: no caches, compiled once by the baseline
    run); returns dest."""
    if from_head:
        dest.mkdir(parents=True)
        tar = subprocess.run(["git", "-C", str(REPO), "archive", "HEAD", "asperity"],
                             capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", str(dest)], input=tar, check=True)
    else:
        shutil.copytree(REPO / "asperity", dest / "asperity", copy_function=shutil.copy2)
    return dest


def source(path: str, from_head: bool) -> str:
    """Text of asperity/``path`` in the working tree or at git HEAD."""
    if from_head:
        return subprocess.run(["git", "-C", str(REPO), "show", f"HEAD:asperity/{path}"],
                              capture_output=True, text=True, check=True).stdout
    return (REPO / "asperity" / path).read_text()


def plant(root: Path, m: Mutant) -> str | None:
    """Apply m in the copy at root; None if done, else why it could not be."""
    f = root / "asperity" / m.path
    text = f.read_text()
    k = text.count(m.old)
    if k != 1:
        return f"text to replace found {k} times in asperity/{m.path}"
    f.write_text(text.replace(m.old, m.new))
    stale = [m.path] + list(KERNEL_DEPENDENTS.get(m.path, ()))
    for rel in stale:
        mod = Path(rel)
        for c in (root / "asperity" / mod.parent / "__pycache__").glob(mod.stem + ".*.nb[ic]"):
            c.unlink()
    return None


def run_tests(root: Path, tests, timeout: float) -> tuple[bool, str, float]:
    """(passed, first failing test or '', seconds) of pytest on ``tests`` with root first."""
    env = dict(os.environ, PYTHONPATH=str(root) + os.pathsep + os.environ.get("PYTHONPATH", ""),
               PYTHONDONTWRITEBYTECODE="1")
    env.pop("PYTEST_XDIST_WORKER", None)
    cmd = [sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider", "-p", "no:xdist",
           "--no-header", "-rfE", "--tb=no", *[str(TESTS / t) for t in tests]]
    t0 = time.perf_counter()
    try:
        out = subprocess.run(cmd, cwd=root, env=env, capture_output=True, text=True,
                             timeout=timeout)
    except subprocess.TimeoutExpired:
        return False, f"timeout after {timeout:g} s", time.perf_counter() - t0
    dt = time.perf_counter() - t0
    if out.returncode == 0:
        return True, "", dt
    text = out.stdout + out.stderr
    hit = re.search(r"^(?:FAILED|ERROR) (\S+)", text, re.M)
    first = hit.group(1) if hit else text.strip().splitlines()[-1] if text.strip() else "?"
    return False, re.sub(r"^\S*?tests/", "", first), dt


def check_import(root: Path) -> None:
    env = dict(os.environ, PYTHONPATH=str(root))
    got = subprocess.run([sys.executable, "-c", "import asperity; print(asperity.__file__)"],
                         cwd=root, env=env, capture_output=True, text=True).stdout.strip()
    if not got.startswith(str(root)):
        sys.exit(f"the copy is not imported first (asperity from {got}); stopping")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("names", nargs="*", help="mutants to run (default: all)")
    ap.add_argument("--list", action="store_true", help="list the mutants and exit")
    ap.add_argument("--json", help="write the results to this JSON file")
    ap.add_argument("--no-baseline", action="store_true",
                    help="skip the run of the test files on the unmutated copy")
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds per mutant")
    ap.add_argument("--from-head", action="store_true",
                    help="mutate the committed package (git HEAD) instead of the working "
                         "tree, e.g. while others have unfinished edits in it")
    ap.add_argument("--check", action="store_true",
                    help="only check that every mutant still applies (no tests run)")
    a = ap.parse_args(argv)
    if a.list:
        for m in MUTANTS:
            print(f"{m.name:30s} asperity/{m.path:28s} {m.what}")
        return 0
    if a.check:
        bad = 0
        for m in MUTANTS:
            k = source(m.path, a.from_head).count(m.old)
            bad += k != 1
            print(f"{'ok' if k == 1 else 'STALE':5s} {m.name}" + ("" if k == 1 else
                                                                  f": found {k} times"))
        return 1 if bad else 0
    known = {m.name: m for m in MUTANTS}
    unknown = [n for n in a.names if n not in known]
    if unknown:
        sys.exit(f"unknown mutant(s): {', '.join(unknown)} (see --list)")
    todo = [known[n] for n in a.names] if a.names else MUTANTS
    results = []
    with tempfile.TemporaryDirectory(prefix="asperity-mutants-") as tmp:
        base = snapshot(Path(tmp) / "base", a.from_head)
        check_import(base)
        if not a.no_baseline:
            files = sorted({t for m in todo for t in m.tests})
            ok, first, dt = run_tests(base, files, a.timeout)
            print(f"baseline ({len(files)} test files, unmutated): "
                  f"{'pass' if ok else 'FAIL ' + first} ({dt:.0f} s)", flush=True)
            if not ok:
                return 2
        for m in todo:
            root = Path(tmp) / "mutant"
            shutil.rmtree(root, ignore_errors=True)
            shutil.copytree(base, root, copy_function=shutil.copy2)
            why = plant(root, m)
            if why:
                status, first, dt = "stale", why, 0.0
            else:
                ok, first, dt = run_tests(root, m.tests, a.timeout)
                status = "missed" if ok else "caught"
            shutil.rmtree(root, ignore_errors=True)
            results.append({"name": m.name, "file": f"asperity/{m.path}", "status": status,
                            "by": first, "seconds": round(dt, 1), "what": m.what})
            print(f"{status:7s} {m.name:30s} {dt:5.0f} s  {first}", flush=True)
    counts = {s: sum(r["status"] == s for r in results) for s in ("caught", "missed", "stale")}
    print(f"\n{counts['caught']} caught, {counts['missed']} missed, {counts['stale']} stale "
          f"of {len(results)} mutants")
    if a.json:
        Path(a.json).write_text(json.dumps(results, indent=1) + "\n")
    return 0 if counts["missed"] == counts["stale"] == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
