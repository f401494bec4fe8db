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

Generated mutants are measured by ``benchmarks/mutation_campaign.py`` (cosmic-ray): this
list keeps what the library cannot make (a dropped or moved statement, swapped arguments
or variables, a changed string or key, a new value) and the modules outside the
campaign's scope; the seven hand mutants that were exactly one of cosmic-ray's in its
scope (sign and operator swaps in the body solver, the contact solver and the disc's spin
drift) were left to it.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
TESTS = REPO / "tests"
sys.path.insert(0, str(REPO))  # the package of this checkout, installed or not

#: numba kernel modules and the kernel modules that compile them in (numba's cache does not
#: notice a change in a module a cached kernel calls into: their caches are dropped too)
from asperity.kernel_cache import CALLS, dependents  # noqa: E402 (the package's one list)

KERNEL_DEPENDENTS = {m: dependents(m) for m in {d for deps in CALLS.values() for d in deps}}

BLOCKS = ("test_study_blocks.py",)
TWO_NODE_BATCH = ("test_two_node_batch.py", "test_study_blocks.py")
TEXTURE = ("test_texture_closed_form.py", "test_law_fitting.py", "test_derive_cli.py")
FRICTION = ("test_texture_closed_form.py", "test_surface_facets.py", "test_derive_cli.py",
            "test_friction_facet_kernel.py", "test_law_fitting.py")
LAWS = ("test_law_sets.py", "test_law_fitting.py", "test_gauge_file.py", "test_fit_law_cli.py",
        "test_dynamics_moreau.py")
DYNAMICS = ("test_dynamics_moreau.py", "test_slide_cli.py")
WARM = ("test_law_warm.py", "test_dynamics_moreau.py")
MICROSLIP = ("test_microslip.py", "test_microslip_verdict.py", "test_microslip_risk.py",
             "test_risk_cli.py", "test_chain_reference.py")
CHAIN = ("test_microslip_events.py", "test_chain_reference.py", "test_microslip.py",
         "test_hostile_microslip.py", "test_chain_march.py")
WEB_PAGES = ("test_web_pages.py",)
WEB_BROWSER = ("test_web_pages_browser.py",)
PROCS = "test_processes.py"
SURFACE = ("test_surface_facets.py", "test_surface_detrend_friction_map.py",
           "test_surface_measured.py", "test_derive_cli.py")
CONFINE = ("test_study_inputs.py", "test_web_security.py")
FINGERPRINT = ("test_study_fingerprint.py",)
WEB_SECURITY = ("test_web_security.py", "test_web_http.py")
CONTACT_FRICTION = ("test_contact_friction.py", "test_contact_friction_cli.py")
CONTACT_SOLVER = ("test_contact_solver.py",)
CONTACT_CLI = ("test_contact_cli.py",)
FAMILY = ("test_law_family.py", "test_law_family_cli.py")
WINDOWS = ("test_contact_windows.py",)
MESH_CONTACT = ("test_contact_mesh.py",)
WINDOWS_MORE = ("test_contact_windows_more.py",)
STUDY_CONTACT = ("test_study_contact.py",)
WEB_CONTACT = ("test_web_contact.py",)
REPORT = ("test_report.py",)
FAMILY_AXES = ("test_family_axes.py",)
WEB_FAMILY = ("test_web_law_family.py",)
BODIES = ("test_bodies_closed_forms.py", "test_bodies_footprint.py")
WEB_BODY = ("test_web_body.py",)
BODY_CLI = ("test_slide_body_cli.py",)
REPORT_BODIES = ("test_report_bodies.py",)
BODY = ("test_dynamics_body.py", "test_body_convergence.py")
CRAWL = ("test_crawl.py",)
CRAWL_CLI = ("test_crawl_cli.py",)
FE_FRIC = ("test_fe_fric.py", "test_fe_fric_family.py")
METAMORPHIC_CONTACT = ("test_metamorphic_contact.py",)
METAMORPHIC_LAWS = ("test_metamorphic_laws.py",)
METAMORPHIC_BODIES = ("test_metamorphic_bodies.py", "test_option_pairs.py")


@dataclass(frozen=True)
class Mutant:
    name: str
    path: str           # relative to asperity/
    old: str
    new: str
    tests: tuple        # test files (in tests/) to run
    what: str           # the bug, in words


MUTANTS = [
    # ---- risk: --contact on the assembly file's texture (issue 29's review)
    Mutant("risk-contact-dropped-for-file-texture", "microslip/risk.py",
           "        asm = replace(asm, friction_table=dict(fr, contact=contact))\n",
           "", ("test_risk_cli.py",),
           "--contact silently ignored when the texture comes from the assembly file"),
    Mutant("risk-contact-refusal-dropped", "microslip/risk.py",
           "        if \"texture\" not in fr:\n            raise InputError(",
           "        if False:\n            raise InputError(", ("test_risk_cli.py",),
           "--contact accepted (and ignored) with explicit mu_plus/mu_minus"),
    # ---- the Motion page's body (issue 20, item 5)
    Mutant("web-body-texture-angle-dropped", "web/tasks_body.py",
           "texture_angle_deg=spec.get(\"texture_angle_deg\", 0.0))",
           "texture_angle_deg=0.0)", WEB_BODY,
           "the page's texture angle never reaches the solver"),
    Mutant("web-body-form-mass-dropped", "web/tasks_body.py",
           "centre_of_pressure=spec.get(\"centre_of_pressure\"), mass=mass)",
           "centre_of_pressure=spec.get(\"centre_of_pressure\"), mass=None)", WEB_BODY,
           "the form's mass not given to the body (1 kg whatever is typed)"),
    Mutant("web-body-spin-sign", "web/tasks_body.py",
           "u0, angle_deg, spec.get(\"omega0\", 0.0),",
           "u0, angle_deg, -spec.get(\"omega0\", 0.0),", WEB_BODY,
           "the initial spin with the wrong sense"),
    Mutant("web-body-path-xy-swapped", "web/figures_body.py",
           "\"x\": _r(k * q[sel, 0], 9), \"y\": _r(k * q[sel, 1], 9),",
           "\"x\": _r(k * q[sel, 1], 9), \"y\": _r(k * q[sel, 0], 9),", WEB_BODY,
           "the path drawn with x and y swapped"),
    Mutant("web-body-cop-field-swapped", "web/pages_body.py",
           "return \"cop_x\" if abs(cx) / ax >= abs(cy) / ay else \"cop_y\"",
           "return \"cop_x\" if abs(cx) / ax <= abs(cy) / ay else \"cop_y\"", WEB_BODY,
           "a centre of pressure outside the core refused at the wrong coordinate"),
    Mutant("web-body-wave-always-square", "web/tasks_body.py",
           "return Force(amplitude=v, period=f[\"period\"], waveform=f[\"waveform\"])",
           "return Force(amplitude=v, period=f[\"period\"], waveform=\"square\")", WEB_BODY,
           "a sine force run as a square wave"),
    Mutant("web-body-named-files-not-checked", "web/pages_body.py",
           "        for key in NAMED_FILES:", "        for key in ():", WEB_BODY,
           "a body file naming a mesh passes the form (the job refuses it late, a 422)"),
    Mutant("web-body-orientation-arm-y", "web/figures_body.py",
           "arms.append(_turned(np.array([[0.0, 0.0], [edge, 0.0]]), q[i]))",
           "arms.append(_turned(np.array([[0.0, 0.0], [0.0, edge]]), q[i]))", WEB_BODY,
           "the orientation drawn along the body's y axis, not its x"),
    Mutant("web-body-stop-marks-joint", "web/figures_body.py",
           "        ts = obj.get(key)", "        ts = obj.get(\"stop_time\")", WEB_BODY,
           "the slide and spin stop marks both at the joint rest time"),
    Mutant("web-body-pressure-for-any-upload", "web/pages_motion.py",
           "GaugeFamily) else []", "GaugeFamily) else [\"upload\"]", WEB_BODY,
           "the law family's pressure shown for a kept single-law gauge file"),
    # ---- bodies (issue 20): closed forms of the disc and ring, footprints
    Mutant("disc-f-constant", "bodies/closed_forms.py",
           "f = np.where(low, (4.0 / (3.0 * math.pi)) * e * (E + B),",
           "f = np.where(low, (4.0 / (9.0 * math.pi)) * e * (E + B),", BODIES,
           "disc force below eps = 1 with 4/(9 pi) instead of 4/(3 pi)"),
    Mutant("disc-m-constant", "bodies/closed_forms.py",
           "(4.0 / (9.0 * math.pi)) * ((3.0 - 2.0 * x) * E + x * B)",
           "(4.0 / (9.0 * math.pi)) * ((3.0 - x) * E + x * B)", BODIES,
           "disc torque below eps = 1: (3 - x) E instead of (3 - 2x) E"),
    Mutant("disc-wrong-branch", "bodies/closed_forms.py",
           "f = np.where(low, (4.0 / (3.0 * math.pi)) * e",
           "f = np.where(e < 1.5, (4.0 / (3.0 * math.pi)) * e", BODIES,
           "disc force: the eps <= 1 branch used up to eps = 1.5"),
    Mutant("ring-m-beyond-one", "bodies/closed_forms.py",
           "m = np.where(low, small, big * inv)", "m = np.where(low, small, small * inv)",
           BODIES, "ring torque beyond eps = 1 from E instead of B"),
    Mutant("elliptic-series-unsquared", "bodies/closed_forms.py",
           "c[j] = c[j - 1] * ((2 * j - 1) / (2 * j)) ** 2",
           "c[j] = c[j - 1] * ((2 * j - 1) / (2 * j))", BODIES,
           "power series of K and E with the ratio of double factorials not squared"),
    Mutant("reference-without-inertia-factor", "bodies/closed_forms.py",
           "return [e - kI * f / m, dt, e * w * dt, w / R * dt]",
           "return [e - f / m, dt, e * w * dt, w / R * dt]", BODIES,
           "reference ODE: d eps/d lambda without k_I (the disc's I = m R^2 / 2 ignored)"),
    Mutant("disc-ring-weight-no-r", "bodies/footprint.py",
           "W = w * r                                        # int 2 r g dr",
           "W = w                                            # int 2 r g dr", BODIES,
           "disc quadrature: a ring's weight without the Jacobian r"),
    Mutant("polygon-crossing-check-off", "bodies/polygon.py",
           "hit = _crossing(v)", "hit = None", BODIES,
           "a polygon whose boundary crosses itself is accepted"),
    Mutant("linear-pressure-without-area", "bodies/footprint.py",
           "return np.linalg.solve(J, area * cop)", "return np.linalg.solve(J, cop)", BODIES,
           "linear pressure: J beta = c instead of J beta = A c"),
    Mutant("clip-piece-at-its-start", "bodies/polygon.py",
           "ym = ay[..., None] + dy[..., None] * tm", "ym = ay[..., None] + dy[..., None] * t0",
           BODIES, "cell clipping: a piece's strip decided at its start (on the strip line)"),
    Mutant("pressure-merge-unweighted", "bodies/pressure.py",
           "X = np.bincount(inv, weights=w * p[:, 0], minlength=uniq.size) / W",
           "X = np.bincount(inv, weights=p[:, 0], minlength=uniq.size) / np.bincount(inv)",
           BODIES, "merged pressure points at their cell's mean, not its load centroid"),
    Mutant("mesh-patch-upside", "bodies/pressure.py",
           "sel, s = sel[s < 0], s[s < 0]", "sel, s = sel[s > 0], s[s > 0]", BODIES,
           "a closed mesh's patch from the faces facing up"),
    # ---- slide --body and slide_body (issue 20, item 4)
    Mutant("body-launch-angle-in-degrees", "dynamics/body_api.py",
           "a = math.radians(angle)", "a = angle", BODY_CLI,
           "slide_body: the launch direction's degrees taken as radians"),
    Mutant("terminal-ratio-of-the-final-state", "dynamics/body.py",
           "u = self.last_moving if self.last_moving is not None else self.u_final",
           "u = self.u_final", BODY_CLI + BODY,
           "terminal ratio of the final state (at rest: none) instead of the last moving one"),
    Mutant("terminal-ratio-diameter", "dynamics/body.py",
           "return float(math.hypot(u[0], u[1]) / (R * abs(u[2])))",
           "return float(math.hypot(u[0], u[1]) / (2 * R * abs(u[2])))", BODY_CLI + BODY,
           "terminal ratio v / (D omega) with the diameter"),
    Mutant("body-inertia-per-unit-mass", "dynamics/body_api.py",
           "inertia = mass * fp.inertia_per_mass", "inertia = fp.inertia_per_mass", BODY_CLI,
           "the lamina's inertia of a 1 kg body whatever --mass"),
    Mutant("drift-per-cycle-off-by-one", "dynamics/body_api.py",
           "k = cycles - first", "k = cycles - first + 1", BODY_CLI,
           "drift per cycle divided by one cycle too many"),
    Mutant("drift-from-the-first-cycle", "dynamics/body_api.py",
           "first = 1 if cycles >= 2 else 0", "first = 0", BODY_CLI,
           "drift per cycle with the first (transient) cycle in it"),
    Mutant("body-csv-theta-omega-swapped", "dynamics/body_api.py",
           "(res.t[i], q[0], q[1], q[2], u[0], u[1],", "(res.t[i], q[0], q[1], u[2], u[0], u[1],",
           BODY_CLI, "CSV: omega written in the theta column"),
    Mutant("torque-on-fy", "cli/slide.py",
           "const[2] = check_range(\"--torque\"", "const[1] = check_range(\"--torque\"",
           BODY_CLI, "--torque applied as a force along y"),
    Mutant("texture-angle-dropped", "cli/slide.py",
           "texture_angle_deg=tex,\n", "texture_angle_deg=0.0,\n", BODY_CLI,
           "--texture-angle read but not passed to the solver"),
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
           "return k * rd / (1.0 - k + k * rd / rc)", "return k * rc",
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
           "theta = math.radians(gl.principal_direction_deg)\n    phi",
           "theta = gl.principal_direction_deg\n    phi",
           ("test_fit_law_cli.py", "test_law_fitting.py", "test_abaqus_block.py"),
           "orthotropic (Abaqus) fit in a frame turned by degrees read as radians"),
    # ---- dynamics
    Mutant("moreau-midpoint-full-step", "dynamics/_moreau_kernels.py",
           "qm[j] = q[j] + 0.5 * dt * u[j]", "qm[j] = q[j] + dt * u[j]", DYNAMICS,
           "Moreau midpoint q_M = q_A + dt u_A (factor 1/2 missing)"),
    # ---- the warm-started law kernels of the point mass (issue 20)
    Mutant("warm-taylor-h-second-order", "laws/_warm_kernels.py",
           "st * (Ta + st * (0.5 * h2 + st", "st * (Ta + st * (h2 + st", WARM,
           "Taylor series of h about the anchor: h''/2 written h'' (wrong constant)"),
    Mutant("warm-taylor-tan-third-order-dropped", "laws/_warm_kernels.py",
           "(1.0 + Ta * dT + (1.0 + 3.0 * T2) * dT * dT * _THIRD)", "(1.0 + Ta * dT)", WARM,
           "Taylor series of tan delta about the anchor without its third-order term"),
    Mutant("warm-taylor-sin-sign", "laws/_warm_kernels.py",
           "return wk[PW_C] * cs - wk[PW_S] * sn, wk[PW_S] * cs + wk[PW_C] * sn",
           "return wk[PW_C] * cs + wk[PW_S] * sn, wk[PW_S] * cs + wk[PW_C] * sn", WARM,
           "cos(psi + st) from the anchor's cos and sin with a sign error"),
    Mutant("warm-halley-factor", "laws/_warm_kernels.py",
           "cand = t - 2.0 * F * dF / den if den > 0.0 else t - F / dF",
           "cand = t - F * dF / den if den > 0.0 else t - F / dF", WARM,
           "Halley's step without its factor 2 (the iteration then stops short of the root)"),
    Mutant("warm-bracket-off-by-one", "laws/_warm_kernels.py",
           "    if -x0 * tab[rb, 6] + x1 * tab[rb, 5] - tab[rb, 4] > 0.0:\n        return 1",
           "    if -x0 * tab[rb, 6] + x1 * tab[rb, 5] - tab[rb, 4] > 0.0:\n        return 0",
           WARM, "warm projection: a root beyond the interval's end taken to be inside it"),
    Mutant("star-dir-cross-sign", "laws/_warm_kernels.py",
           "return (v0x * dy - v0y * dx) / (ux * dy - uy * dx), k",
           "return (v0x * dy + v0y * dx) / (ux * dy - uy * dx), k", WARM,
           "star polygon's radial function from the last edge: cross product with a sign error"),
    Mutant("warm-alpha-swapped", "laws/_law_kernels.py",
           "return 1.0 / (r / wk[WARM_RD] - r / wk[WARM_RC] + 1.0)",
           "return 1.0 / (r / wk[WARM_RC] - r / wk[WARM_RD] + 1.0)", WARM,
           "alpha = 1 / (k_D - k_C + 1) from the kept radial functions with C and D swapped"),
    Mutant("alpha-near-swapped", "laws/_law_kernels.py",
           "    return 1.0 / (r / rd - r / rc + 1.0)\n\n\n@njit(cache=True, _nrt=False, inline=",
           "    return 1.0 / (r / rc - r / rd + 1.0)\n\n\n@njit(cache=True, _nrt=False, inline=",
           WARM,
           "alpha at the extrapolated force with C and D swapped"),
    Mutant("radial-warm-derivative-term-dropped", "laws/_warm_kernels.py",
           "g = h * (1.0 + T2 + (1.0 + T2) * dd)", "g = h * (1.0 + T2)", WARM,
           "D's radial function from the last root: Newton with dy/dpsi missing the h'' term"),
    Mutant("point-iterate-velocity-sign", "dynamics/_moreau_kernels.py",
           "g1 = uf[1] - minv[1] * P[0, 1]", "g1 = uf[1] + minv[1] * P[0, 1]",
           DYNAMICS, "point mass: u_E = u_free + M^-1 P along t_b (impulse sign error)"),
    Mutant("point-end-velocity-component-swap", "dynamics/_moreau_kernels.py",
           "ue[1] = uf[1] - minv[1] * P[0, 1]", "ue[1] = uf[1] - minv[1] * P[0, 0]",
           DYNAMICS, "point mass: end velocity along t_b from the impulse along t_a"),
    Mutant("const-force-evaluated-per-step-skipped", "dynamics/_moreau_kernels.py",
           "        if not const_force:\n            _force(",
           "        if False:\n            _force(", DYNAMICS,
           "a time-dependent force evaluated only once (its value at t0)"),
    Mutant("const-force-periodic", "dynamics/_moreau_kernels.py",
           "const_force = ftab.shape[0] == 0 and int(fpar[0]) == FORCE_NONE",
           "const_force = ftab.shape[0] == 0", DYNAMICS,
           "a square or sine force taken as constant (evaluated once)"),
    Mutant("point-alpha-near-assoc-only", "dynamics/_moreau_kernels.py",
           "al = 1.0 if assoc else law_alpha_near(", "al = 1.0 if not assoc else law_alpha_near(",
           WARM, "point mass: alpha at the extrapolated force 1 for non-associated laws"),
    Mutant("moreau-torque-sign", "dynamics/_moreau_kernels.py",
           "ue[2] -= minv[2] * (ow[i, 0] * P[i, 1] - ow[i, 1] * P[i, 0])",
           "ue[2] -= minv[2] * (ow[i, 0] * P[i, 1] + ow[i, 1] * P[i, 0])", DYNAMICS,
           "rigid body: torque of a contact impulse with a sign error (r x P)"),
    # ---- rigid body with a footprint (issue 20)
    Mutant("body-midpoint-full-step", "dynamics/_body_kernels.py",
           "            q[j] += 0.5 * dt * u[j]\n        _force(fpar, tM, f)",
           "            q[j] += dt * u[j]\n        _force(fpar, tM, f)", BODY,
           "body solver: q_M = q_A + dt u_A (factor 1/2 missing)"),
    Mutant("body-stick-margin-loose", "dynamics/_body_kernels.py",
           "if G >= -tola:", "if G >= -0.1 * scale:", BODY,
           "body solver: the body sticks while the least margin is still negative"),
    Mutant("body-normal-impulse-no-dt", "dynamics/body.py",
           "lam = w * mass * g * dt", "lam = w * mass * g", BODY,
           "body solver: normal impulse m g w_i instead of m g w_i dt"),
    Mutant("body-table-no-interpolation", "dynamics/_body_law_kernels.py",
           "out[j] = a0 + t * (a1 - a0)", "out[j] = a0", BODY,
           "body solver: law tables read at the grid point below, not interpolated"),
    Mutant("body-kink-outside-C", "dynamics/_body_step_kernels.py",
           "if _gauge(kind, par, tab, lx, ly) > 1.0 + 1e-12:",
           "if _gauge(kind, par, tab, lx, ly) > 1.1:", BODY,
           "body solver: a point held sticking with a force outside its friction set"),
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
           "    return k1 * k2 / (k1 + k2)", "    return min(k1, k2)", CHAIN,
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
    Mutant("march-nonuniform-in-increments", "microslip/quasi_static.py",
           "events_only = tol.events_only or not is_uniform(chain)",
           "events_only = tol.events_only", CHAIN,
           "a chain outside the uniform class taken in increments (its sliders stop inside "
           "segments)"),
    # ---- surface
    Mutant("detrend-dropped", "surface/detrend.py",
           "heights=surface.heights - fit.form(", "heights=surface.heights + 0 * fit.form(",
           SURFACE,
           "height-map form removal returns the heights unchanged"),
    Mutant("heightmap-gy-over-dx", "surface/grid_facets.py",
           "(1, dy, ((z01, z00), (z11, z10)))", "(1, dx, ((z01, z00), (z11, z10)))",
           SURFACE, "height-map facet slope dz/dy divided by dx (non-square pixels)"),
    # ---- files a study names: confinement (issue 18, section 1)
    Mutant("confine-skips-string-files", "study/inputs.py",
           "    if isinstance(pats, str):\n        items = [(\"study.files\", pats)]",
           "    if isinstance(pats, str):\n        items, confine = [(\"study.files\", pats)], "
           "None", CONFINE,
           "study.files given as one string (a glob) is not confined, only a list is"),
    Mutant("confine-links-not-followed", "paths.py",
           "real = os.path.realpath(path)", "real = os.path.abspath(path)", CONFINE,
           "the confinement resolves .. but not symbolic links (a link pointing out passes)"),
    Mutant("confine-glob-matches-unchecked", "study/inputs.py",
           "            inside_matches(key, pat, hits, confine.root, confine.outside)\n", "",
           CONFINE, "the matches of a pattern are not checked (a matched link pointing out)"),
    Mutant("confine-skips-assembly-names", "study/inputs.py",
           "        if confine is not None:\n            check_inside(key, v, base,",
           "        if confine is not None and \"friction\" not in key:\n"
           "            check_inside(key, v, base,", CONFINE,
           "the gauge and texture an assembly names are not confined, only the study's keys"),
    Mutant("confine-sees-tilde-unexpanded", "paths.py",
           "    full = str(named_path(value, folder))\n    fixed = full",
           "    full = str(Path(folder) / value)\n    fixed = full", CONFINE,
           "the check joins the name itself (~ not expanded) while the reader expands it"),
    # ---- study fingerprint and --restart (issue 18, section 6)
    Mutant("fingerprint-by-size", "study/inputs.py",
           "return {p: file_digest(p) for p in paths}",
           "return {p: str(Path(p).stat().st_size) for p in paths}", FINGERPRINT,
           "the inputs are fingerprinted by their size, not their content"),
    Mutant("fingerprint-study-keys-only", "study/inputs.py",
           "for n in self.named for p in n.paths if p.is_file()",
           "for n in self.named if n.key.startswith(\"study.\") for p in n.paths "
           "if p.is_file()", FINGERPRINT,
           "the files an assembly names (gauge, texture) are left out of the fingerprint"),
    Mutant("resume-ignores-input-digests", "study/store.py",
           "same = meta.get(\"fingerprint\") == fp and meta.get(\"input_digests\") == digests",
           "same = meta.get(\"fingerprint\") == fp", FINGERPRINT,
           "a store resumes whatever the inputs' digests say"),
    Mutant("restart-keeps-cases", "study/store.py",
           "con.execute(\"DROP TABLE IF EXISTS cases\")\n            con.execute(\"DROP TABLE "
           "IF EXISTS meta\")\n        con.execute(\"CREATE TABLE meta (key TEXT PRIMARY KEY, "
           "value TEXT)\")\n        con.execute(f\"CREATE TABLE cases (",
           "con.execute(\"DROP TABLE IF EXISTS meta\")\n        con.execute(\"CREATE TABLE "
           "meta (key TEXT PRIMARY KEY, value TEXT)\")\n        con.execute(f\"CREATE TABLE "
           "IF NOT EXISTS cases (", FINGERPRINT,
           "--restart replaces the study's meta but keeps the stored cases (a mixed store)"),
    Mutant("restart-not-one-transaction", "study/store.py",
           "con.execute(\"BEGIN IMMEDIATE\")", "con.execute(\"SELECT 1\")", FINGERPRINT,
           "the restart's drops and creates commit one by one (an interrupt loses the store)"),
    # ---- web security (issue 18, section 10)
    Mutant("token-cookie-name-only", "web/security.py",
           "if name == cookie and secrets.compare_digest(value, self.token):",
           "if name == cookie:", WEB_SECURITY, "any value of the token's cookie is let in"),
    Mutant("host-begins-with-localhost", "web/settings.py",
           "    if host == \"localhost\":", "    if host.startswith(\"localhost\"):",
           WEB_SECURITY, "a Host header that begins with localhost counts as loopback"),
    Mutant("upload-limit-per-chunk", "web/security.py",
           "seen += len(msg.get(\"body\", b\"\"))", "seen = len(msg.get(\"body\", b\"\"))",
           WEB_SECURITY, "the upload limit is compared with each chunk, not the whole body"),
    Mutant("download-undeclared-files", "web/store.py",
           "if rec is None or name not in rec.get(\"files\", []):", "if rec is None:",
           WEB_SECURITY, "any file of an existing job's folder is served"),
    # ---- issue 18: the Python API's bad arguments, the Abaqus block, the spike filter
    Mutant("api-psi-2d-unchecked", "friction/reservoir.py",
           "    if a.ndim != 1:\n        raise InputError(f\"{name} must be a number or a 1-d",
           "    if a.ndim > 2:\n        raise InputError(f\"{name} must be a number or a 1-d",
           ("test_hostile_api.py",), "a 2-D psi reaches the reservoir (IndexError inside)"),
    Mutant("api-empty-psi-accepted", "friction/reservoir.py",
           "a = np.atleast_1d(check_array(name, psi, min_size=1))",
           "a = np.atleast_1d(check_array(name, psi, min_size=0))",
           ("test_hostile_api.py",), "an empty psi gives an empty reservoir instead of a refusal"),
    Mutant("api-facet-shapes-unchecked", "surface/facet_checks.py",
           "        if a.shape != (n,):\n            raise InputError(f\"{name} must have the shape",
           "        if a.ndim != 1:\n            raise InputError(f\"{name} must have the shape",
           ("test_hostile_api.py",), "FacetSurface of arrays of different shapes accepted"),
    Mutant("api-x3p-overflow-warns", "surface/readers/_x3p_points.py",
           'with np.errstate(over="ignore", invalid="ignore"):\n            if axis.increment',
           'with np.errstate(invalid="ignore"):\n            if axis.increment',
           ("test_hostile_api.py",), "an overflowing x3p Increment warns before its refusal"),
    Mutant("api-huge-int-in-message", "errors.py",
           "    if abs(n) < 10**30:\n        return str(n)\n",
           "    if abs(n) < 10**30:\n        return str(n)\n    return f\"{float(n):g}\"\n",
           ("test_hostile_api.py",), "10**400 as a whole number: OverflowError building the message"),
    Mutant("abaqus-fits-the-data", "laws/export.py",
           "e = fit_truncated_ellipse(polar, theta, symmetric=True)",
           "e = fit_truncated_ellipse(gl.data, theta, symmetric=True)",
           ("test_abaqus_block.py",),
           "Abaqus ellipse of the data (the star's polar) whatever the law: one block for both"),
    Mutant("abaqus-own-axes-swapped", "laws/export.py",
           "TruncatedEllipse(C.mu_a_plus, C.mu_a_plus, C.mu_b_plus, C.mu_b_plus, theta=theta)",
           "TruncatedEllipse(C.mu_b_plus, C.mu_b_plus, C.mu_a_plus, C.mu_a_plus, theta=theta)",
           ("test_abaqus_block.py",), "an orthotropic ellipse law's own mu1 and mu2 swapped"),
    Mutant("abaqus-asymmetry-b-from-a", "laws/export.py",
           "asymmetry_b=abs(t[2] - t[3]) / (0.5 * (t[2] + t[3])),",
           "asymmetry_b=abs(t[0] - t[1]) / (0.5 * (t[0] + t[1])),",
           ("test_abaqus_block.py",), "LOSES line: the asymmetry along t_b is t_a's"),
    Mutant("abaqus-axes-in-source-frame", "laws/export.py",
           "t = gl.force(theta + np.array([0.0, np.pi, 0.5 * np.pi, 1.5 * np.pi])).tangential",
           "t = gl.force(np.array([0.0, np.pi, 0.5 * np.pi, 1.5 * np.pi])).tangential",
           ("test_abaqus_block.py",), "LOSES line: mu+- along x and y, not the principal axes"),
    Mutant("abaqus-radial-error-absolute", "laws/export.py",
           "rad = (e.radial(phi) - r) / r", "rad = e.radial(phi) - r",
           ("test_abaqus_block.py",), "LOSES line: absolute, not relative, radial error"),
    Mutant("spike-window-one-row-short", "surface/_spike_kernels.py",
           "for ii in range(max(0, i - r), min(nr, i + r + 1)):",
           "for ii in range(max(0, i - r), min(nr, i + r)):",
           ("test_spike_filter.py",), "spike filter window one row short (its last row)"),
    Mutant("spike-window-one-column-short", "surface/_spike_kernels.py",
           "for jj in range(max(0, j - r), min(nc, j + r + 1)):",
           "for jj in range(max(0, j - r + 1), min(nc, j + r + 1)):",
           ("test_spike_filter.py",), "spike filter window one column short (its first column)"),
    Mutant("spike-min-neighbours-one-fewer", "surface/_spike_kernels.py",
           "if n < min_neighbours:", "if n < min_neighbours - 1:",
           ("test_spike_filter.py",), "pixels with W - 1 defined neighbours judged"),
    Mutant("spike-mad-unscaled", "surface/_spike_kernels.py",
           "s = 1.4826 * _median(dev, n)", "s = _median(dev, n)",
           ("test_spike_filter.py",), "robust standard deviation without the 1.4826 factor"),
    # ---- web page as a new user meets it (issue 18, section 8)
    Mutant("web-download-name-fixed", "web/app.py",
           "return FileResponse(path, filename=shown)",
           "return FileResponse(path, filename=name.rsplit(\"/\", 1)[-1])", WEB_PAGES,
           "every law downloads as gauge.json / law.csv / law.inp again"),
    Mutant("web-unit-always-um", "web/units.py",
           "return Unit(pick + base, SCALE[pick])", "return Unit(\"u\" + base, 1e-6)",
           WEB_PAGES, "the engineering-unit chooser answers um whatever the values"),
    Mutant("web-colour-bar-um", "web/figures.py",
           "up = choose([float(np.nanmax(np.abs(zm)))])", "up = choose(1e-6)", WEB_PAGES,
           "the height map's colour bar in um whatever the heights"),
    Mutant("web-risk-figure-in-m", "web/figures.py",
           "un = choose([float(np.max(np.abs(u))) for _, u, _ in h[\"nodes\"]])",
           "un = choose(1.0)", WEB_PAGES, "the risk figure's node displacements in m"),
    Mutant("web-tolerance-mm-again", "web/pages_motion.py",
           "\"tolerance\": tol}", "\"tolerance\": None if tol is None else tol * 1e-3}",
           WEB_PAGES, "the risk form's tolerance read in mm while its label says m"),
    Mutant("web-delete-leaves-files", "web/store.py",
           "folder.rename(trash)", "(folder / \"job.json\").rename(trash)", WEB_PAGES,
           "deleting a result removes its record but leaves its files"),
    Mutant("web-token-page-path", "web/app.py",
           "kept={}, bare=True)", "kept={}, bare=False)", WEB_PAGES,
           "the token-refused page shows the data folder's path"),
    Mutant("web-elapsed-restarts", "web/store.py",
           "t0 = rec.get(\"started_at\") if running else rec.get(\"created_at\")",
           "t0 = now", WEB_PAGES, "a job's elapsed time starts at 0 on every reload"),
    Mutant("web-time-left-wrong", "web/store.py",
           "left = elapsed * (1.0 - f) / f", "left = elapsed / f", WEB_PAGES,
           "time left estimated as the whole run's time"),
    Mutant("web-duplicate-ids", "web/templates/surface.html",
           "values, fid='f-file-contact', form='file') }}", "values, form='file') }}",
           WEB_PAGES,
           "the Surface page's two forms give one id to two fields again"),
    Mutant("web-settings-miss-max-slope", "web/labels.py",
           "(\"max_slope\", lambda v: f\"max slope {_num(v)} deg\"),", "", WEB_PAGES,
           "results that differ only by their max slope look alike in the lists"),
    Mutant("web-slide-law-of-a-gauge-file", "web/tasks_motion.py",
           "return params.get(\"law_text\") or f\"the {law.name} law of result "
           "{spec['job']}{at}\", \\", "return law.description, \\", WEB_PAGES,
           "a slide on a fitted law titled 'law of a gauge file'"),
    Mutant("web-home-numbered-twice", "web/static/style.css",
           ".steps { list-style: none; padding-left: 0; }", ".steps { padding-left: 0; }",
           WEB_PAGES + WEB_BROWSER, "the home list shows '1. 1. Surface'"),
    Mutant("web-long-cells-overflow", "web/static/style.css",
           "main h1, main p, main td, main li, main small, main legend, .card "
           "{ overflow-wrap: anywhere; }", "", WEB_BROWSER,
           "long values run out of their cards at 1280 px"),
    Mutant("web-prose-cells-nowrap", "web/static/style.css",
           "table.numbers.prose td:nth-child(2), table.numbers.prose th { white-space: normal; }",
           "", WEB_BROWSER,
           "the data-quality notes kept on one line, past the card's edge"),
    Mutant("web-title-under-toolbar", "web/static/app.js",
           "delete fig.layout.title;", "", WEB_BROWSER,
           "Plotly's toolbar covers the plot titles again"),
    Mutant("web-risk-figure-static", "web/templates/result_risk.html",
           "{% if result.figures %}{{ plot('risk-plot', result.figures.history) }}",
           "{% if false %}", WEB_PAGES + WEB_BROWSER,
           "the risk figure is a static image again"),
    # ---- study statistics (issue 18)
    Mutant("sobol-min-samples-removed", "study/sampling.py",
           "    if samples < MIN_SOBOL_BASE:", "    if samples < 1:",
           ("test_study_distributions.py",),
           "a Sobol study of base sample 1 (zero-width intervals) is accepted"),
    Mutant("sd-below-resolution-accepted", "study/sampling.py",
           "    if sd < least:", "    if sd < 0:", ("test_study_distributions.py",),
           "an sd that rounds every sample to the mean passes its check"),
    Mutant("truncnorm-tail-unchecked", "study/sampling.py",
           "    if lo > mean + MAX_TAIL_SD * sd:", "    if lo > mean + 1e6 * sd:",
           ("test_study_distributions.py",),
           "a truncated normal whose interval lies 50 sd from its mean is accepted"),
    Mutant("constant-output-ranked", "study/influence.py",
           "    if np.ptp(vals) <= CONSTANT_RTOL * np.max(np.abs(vals)):",
           "    if np.ptp(vals) < 0:",
           ("test_study_statistics.py", "test_study_web_summary.py"),
           "the zero-variance branch skipped: a constant output names a parameter"),
    Mutant("sobol-missing-not-counted", "study/influence.py",
           "    missing = n_cases - ok.size", "    missing = 0", ("test_study_statistics.py",),
           "an interrupted Saltelli design is not reported as waiting for its cases"),
    Mutant("bootstrap-collapse-shown", "study/influence.py",
           "            if not (math.isfinite(c) and c > COLLAPSED):",
           "            if not math.isfinite(c):", ("test_study_statistics.py",),
           "a collapsed bootstrap is printed as an interval of zero width"),
    Mutant("bootstrap-seed-zero", "study/influence.py",
           "conf_level=0.95, seed=int(seed) + 1)", "conf_level=0.95, seed=int(seed))",
           ("test_study_statistics.py",),
           "SALib's bootstrap unseeded for seed = 0: intervals change on every summary"),
    Mutant("rank-interval-ignored", "study/influence.py",
           "        if ci is None or ci[0] > 0.0 or ci[1] < 0.0:", "        if True:",
           ("test_study_statistics.py",),
           "a parameter whose rank correlation's interval holds 0 is named as mattering"),
    Mutant("rank-min-cases-2", "study/influence.py",
           "MIN_RANK_CASES = 5", "MIN_RANK_CASES = 2", ("test_study_statistics.py",),
           "rank correlations of 2 cases (+-1 always) name a parameter"),
    Mutant("grid-share-with-interval", "study/summary.py",
           '        if st["kind"] == "grid":', "        if False:",
           ("test_study_statistics.py",),
           "a grid's share of ratchet gets a Wilson interval as if it were a sample"),
    Mutant("export-drops-file-column", "study/store.py",
           "    cols = store.columns()\n    with atomic_path(path) as tmp:",
           '    cols = [c for c in store.columns() if c != "file"]\n'
           "    with atomic_path(path) as tmp:",
           ("test_study_statistics.py", "test_study_web_summary.py"),
           "the export of a scan library without its file column"),
    Mutant("export-file-as-resolved", "study/store.py",
           '    if "file" not in store.inputs:\n        return rows',
           "    if True:\n        return rows",
           ("test_study_statistics.py", "test_study_web_summary.py"),
           "the export names files by the resolved (server) path, not as the study does"),
    # ---- web forms (issue 18): hostile fields, kept forms, quiet logs, self-locking pages
    Mutant("web-whole-int-float", "web/forms.py",
           "return _read(name, check_int, label, _read(name, number_from_text, label, t), "
           "low, high)", "return int(float(t))", ("test_web_forms.py",),
           "a whole-number field parsed with int(float()) (inf: OverflowError, a 500)"),
    Mutant("web-refusal-drops-the-form", "web/common.py",
           "values=values, kept=kept,", "values={}, kept=kept,", ("test_web_forms.py",),
           "a refused form comes back empty (what was typed lost)"),
    Mutant("web-refusal-drops-uploads", "web/common.py",
           "values=values, kept=kept,", "values=values, kept={},", ("test_web_forms.py",),
           "a refused form forgets the files it stored (the user must choose them again)"),
    Mutant("web-bug-reraised", "web/app.py",
           "except Exception:                  # answered (and logged) by the bug handler\n"
           "            pass",
           "except Exception:                  # answered (and logged) by the bug handler\n"
           "            raise", ("test_web_forms.py",),
           "an exception answered with a 500 goes on to the server (uvicorn logs its traceback)"),
    Mutant("web-disconnect-is-a-bug", "web/app.py",
           "@app.exception_handler(ClientDisconnect)", "@app.exception_handler(ConnectionError)",
           ("test_web_forms.py",),
           "a client gone mid-upload is handled as a bug (an internal error in the log)"),
    Mutant("web-library-refusal-not-placed", "web/words.py",
           "            field = field or f\n", "            field = field\n",
           ("test_web_http.py", "test_web_forms.py"),
           "a job refused by the library comes back without the field it is about"),
    Mutant("web-share-the-worst-direction", "web/templates/result_derive.html",
           "{% set share = q.load_share_above_locking_limit if surface else "
           "d.self_locking_load_share %}", "{% set share = d.self_locking_load_share %}",
           ("test_web_new_user.py",),
           "the page's load share is the worst direction's while the rest say the steep facets'"),
    Mutant("web-locked-all-not-seen", "web/templates/result_derive.html",
           "{% set locked_all = d.self_locking and d.self_locking | length == d.directions | "
           "length %}", "{% set locked_all = false %}", ("test_web_new_user.py",),
           "a result locked in every direction shows anisotropy 0, admissible yes, a fit button"),
    Mutant("x3p-unit-not-on-the-spacing", "surface/readers/x3p.py",
           "        dx, dy = dx * factor, dy * factor\n", "        dx, dy = dx, dy\n",
           ("test_surface_readers.py", "test_web_new_user.py"),
           "an x3p read in another unit converts its heights but not its spacing"),
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
           "        if store.discard() and", "        if store.close() and",
           (f"{PROCS}::test_a_run_that_fails_before_its_first_case_leaves_the_folder_as_it_"
            "was",),
           "a run that fails before its first case leaves an empty store behind"),
    Mutant("store-without-tables-stuck", "study/store.py",
           "new = con.execute(\"SELECT 1 FROM sqlite_master WHERE type = 'table'\").fetchone() "
           "is None", "new = db.stat().st_size == 0",
           (f"{PROCS}::test_a_store_killed_before_its_tables_were_made_is_taken_as_new",),
           "a store file left without tables (a kill before the first transaction) refused "
           "for ever unless it is empty"),
    # ---- issue 19: friction weighted by the elastic contact force
    Mutant("contact-weight-one-sided", "surface/facets.py",
           "        grid.centroid_heights(pressure, force)\n",
           "        force[:] = np.tile(pressure[:-1, :-1].ravel(), 2)\n", CONTACT_FRICTION,
           "each facet takes its cell's first corner's pressure (first order), not the mean "
           "of its own corners"),
    Mutant("contact-weight-is-area", "surface/facets.py",
           "w = grid.pressure_weight(area, force)", "w = area", CONTACT_FRICTION,
           "the pressure field is ignored: facets weighted by their area"),
    Mutant("periodic-edges-left-out", "surface/facets.py",
           "    if periodic:\n        z = grid.wrap_periodic(z)",
           "    if False:\n        z = grid.wrap_periodic(z)", CONTACT_FRICTION,
           "a periodic map's cells across its edges are not facets"),
    Mutant("contact-heights-not-levelled", "surface/contact_facets.py",
           "return z - a * x[:, None] - b * y[None, :]", "return z", CONTACT_FRICTION,
           "a free map's slope removed from the facets but not from the heights the "
           "half-space meets"),
    Mutant("wedge-face-forces-swapped", "friction/elastic.py",
           "w = np.array([force[prof.face == k].sum() for k in range(nfaces)])",
           "w = np.array([force[prof.face == k].sum() for k in range(nfaces)])[::-1]",
           CONTACT_FRICTION, "a wedge's alpha face weighs the force on its beta face"),
    Mutant("wedge-force-left-node", "friction/elastic.py",
           "return cum[i] + dx * (q[i] * t + 0.5 * (q[i + 1] - q[i]) * t * t)",
           "return cum[i] + dx * q[i] * t", CONTACT_FRICTION,
           "a face's partial pixel integrated with the left node's pressure only"),
    Mutant("contact-hardness-dropped", "surface/contact_facets.py",
           "boundary=boundary, hardness=elastic.hardness,", "boundary=boundary, hardness=None,",
           CONTACT_FRICTION, "the hardness never reaches the contact solve"),
    Mutant("contact-block-missing", "friction/derive.py",
           'out["elastic_contact"] = dict(d.texture.elastic)', "pass", CONTACT_FRICTION,
           "derive's JSON loses its elastic_contact block"),
    # ---- issue 19: the contact solver against closed forms, load curves, asperity contact
    Mutant("free-padding-half", "contact/elastic.py",
           "ix = np.where(ix <= nx, ix, ix - 2 * nx) * self.dx",
           "ix = np.where(ix <= nx // 2, ix, ix - 2 * nx) * self.dx", CONTACT_SOLVER,
           "the padded free kernel's offsets wrap at half the map: far pixels interact as "
           "near ones on the other side"),
    Mutant("contact-load-over-defined-pixels", "contact/solver.py",
           "load = pbar * nx * ny ", "load = pbar * n_def ", CONTACT_SOLVER,
           "the nominal pressure taken over the defined pixels, not the map's area"),
    Mutant("plastic-clip-dropped", "contact/_pk_kernels.py", "        elif q > H:\n",
           "        elif q > 2.0 * H:\n", CONTACT_SOLVER,
           "the pressure step clips at 2 H, not at the hardness"),
    Mutant("plastic-displacement-left-out", "contact/plastic.py", "        h2 = z - u\n",
           "        h2 = z.copy()\n", CONTACT_SOLVER,
           "the outer plastic loop's elastic solve ignores the plastic pixels' displacement"),
    Mutant("plastic-set-grows-at-2h", "contact/plastic.py", "        over = pe > H\n",
           "        over = pe > 2.0 * H\n", CONTACT_SOLVER,
           "the outer plastic loop lets elastic pressures up to 2 H stand"),
    Mutant("load-curve-cold", "contact/curve.py", "previous = res.pressure",
           "previous = None", CONTACT_SOLVER,
           "each pressure of a load curve solved from the uniform start"),
    Mutant("load-curve-order", "contact/curve.py", "waiting[int(k)] = res",
           "waiting[len(waiting) + nxt] = res", CONTACT_SOLVER,
           "a load curve's results in increasing pressure, not in the order given"),
    # ---- issue 19: the preconditioned iteration, the benchmark's load curve
    Mutant("contact-precond-laplacian", "contact/elastic.py",
           "m[i] = np.sqrt(qx[i] * qx[i] + qy * qy) * (0.5 * self.E_star)",
           "m[i] = (qx[i] * qx[i] + qy * qy) * (0.5 * self.E_star)", CONTACT_SOLVER,
           "the preconditioner multiplies by q^2 (a Laplacian), not by |q| (the inverse "
           "half-space)"),
    Mutant("contact-precond-entering-left-out", "contact/_pk_kernels.py",
           "if 0.0 < pi < H or (pi <= 0.0 and g < 0.0) or (pi >= H and g > 0.0):\n"
           "            w[i] = g", "if 0.0 < pi < H:\n            w[i] = g", CONTACT_SOLVER,
           "the preconditioner's input leaves out the pixels the gap moves (they enter "
           "or leave contact by M of the free set's gap alone)"),
    Mutant("contact-precond-moves-by-gap", "contact/_pk_kernels.py",
           "q = pi - tau * (z[i] if pre else g)", "q = pi - tau * g", CONTACT_SOLVER,
           "pixels entering contact moved by the gap g, not by the preconditioned gap M g "
           "(the step tau is in the preconditioned units)"),
    Mutant("contact-precond-sum-unshifted", "contact/_pk_kernels.py",
           "sgz += (u[i] - hi - gbar) * z[i]", "sgz += (u[i] - hi) * z[i]", CONTACT_SOLVER,
           "the preconditioned residual norm Z taken with the gap before its mean shift"),
    Mutant("bench-curve-pressures-unscaled", "contact/bench.py",
           'curve(h, PIXEL, E_STAR, [f * E_STAR for f in spec["pressures"]],',
           'curve(h, PIXEL, E_STAR, spec["pressures"],', ("test_contact_oracle.py",),
           "the benchmark's load curve solved at p/E* in Pa, not at p"),
    Mutant("saved-pressure-undefined-zero", "cli/contact.py",
           'np.save(f, np.asarray(pic["save"], dtype=np.float64))',
           'np.save(f, np.nan_to_num(pic["save"]))', CONTACT_CLI,
           "--save-pressure writes 0, not NaN, on undefined pixels"),
    Mutant("contact-default-boundary-periodic", "cli/contact.py",
           'boundary = ec.boundary_or("free")', 'boundary = ec.boundary_or("periodic")',
           CONTACT_CLI, "a measured file taken as one period by default"),
    # ---- issue 19: law families over the pressure (gauge files version 2)
    Mutant("family-weight-linear-in-p", "laws/family.py",
           "return k, math.log(p / ps[k]) / math.log(ps[k + 1] / ps[k])",
           "return k, (p - ps[k]) / (ps[k + 1] - ps[k])", FAMILY,
           "the law between members weighted linearly in p, not in ln p"),
    Mutant("family-weights-swapped", "laws/family.py",
           "return (1.0 - w) * a + w * b", "return w * a + (1.0 - w) * b", FAMILY,
           "between two members the weight goes to the farther one"),
    Mutant("family-wrong-member", "laws/family.py",
           "return ps.index(p), 0.0", "return min(ps.index(p) + 1, len(ps) - 1), 0.0", FAMILY,
           "at a member's pressure the next member is taken"),
    Mutant("family-wrong-pair", "laws/family.py",
           'k = int(np.searchsorted(ps, p, side="right")) - 1',
           'k = max(int(np.searchsorted(ps, p, side="right")) - 2, 0)', FAMILY,
           "between members k and k+1 the pair below them is used"),
    Mutant("family-ellipse-not-aligned", "laws/family.py",
           "if abs(turn) > 0.5 * math.pi:", "if False:", FAMILY,
           "an ellipse member written with t_a reversed is interpolated semi-axis by "
           "semi-axis as if it were not"),
    Mutant("family-set-valued-merged", "laws/family.py",
           "if np.array_equal(left[j], right[j]):", "if True:", FAMILY,
           "a set-valued direction's right limit dropped from the interpolated points"),
    Mutant("family-written-as-version-1", "laws/gauge_file.py",
           '"version": FAMILY_VERSION, "asperity_version"',
           '"version": VERSION, "asperity_version"', FAMILY,
           "a family written with the schema version of a single law"),
    Mutant("family-member-texture-lost", "laws/gauge_file.py",
           'one["source"]["texture"] = {**obj["source"]["texture"], **m["texture"]}',
           'one["source"]["texture"] = obj["source"]["texture"]', FAMILY,
           "a member's load-dependent texture figures (facets carrying load) lost on reading"),
    Mutant("family-law-at-first-member", "laws/family.py",
           "gl = gauge.at(pressure, name)", "gl = gauge.members[0]", FAMILY,
           "slide / law / risk take a family's first member whatever the pressure"),
    Mutant("risk-family-first-pressure", "microslip/friction.py",
           "gl, how = law_at(gauge, p, where, name)",
           "gl, how = law_at(gauge, gauge.pressures[0], where, name)", FAMILY,
           "risk takes a family at its lightest pressure, not the assembly's"),
    Mutant("two-node-pressure-times-area", "microslip/assembly.py",
           'else (self.params["N"] / area, where)', 'else (self.params["N"] * area, where)',
           FAMILY, "the two-node contact pressure N x contact_area"),
    Mutant("risk-elastic-pressure-ignored", "cli/risk.py",
           "        args.pressure = [p]\n", "        args.pressure = [1e6]\n", FAMILY,
           "risk --elastic without --pressure solves at a fixed pressure, not the "
           "assembly's"),
    # ---- issue 19: windows of a scan beyond one solve, contact parameters of studies
    Mutant("window-read-axes-swapped", "friction/elastic_windows.py",
           "        a0, b0 = j0, i0", "        a0, b0 = i0, j0", WINDOWS,
           "a file whose lines are columns (Fortran .npy, x3p, text matrices) read with the "
           "window's x and y origins swapped"),
    Mutant("window-origin-past-the-edge", "friction/elastic_windows.py",
           "sx, sy = nx - window + 1, ny - window + 1", "sx, sy = nx - window + 2, ny - window + 2",
           WINDOWS, "random windows' strata one origin wider than the scan holds (the last stratum's "
           "draws piled on the edge)"),
    Mutant("window-sd-population", "friction/window_summary.py",
           "float(v.std(ddof=1))", "float(v.std())", WINDOWS,
           "the spread between windows as the population sd (n) instead of the sample's "
           "(n - 1)"),
    Mutant("window-axes-not-turned", "friction/axes.py",
           "    if abs(d) <= 90.0:", "    if True:", WINDOWS,
           "windows whose t_a point opposite ways averaged without exchanging + and -"),
    Mutant("window-holes-not-skipped", "friction/elastic_windows.py",
           "    if share < MIN_DEFINED_SHARE:", "    if share < 0.0:", WINDOWS,
           "windows with too few defined pixels solved as if whole"),
    Mutant("study-contact-value-ignored", "study/contact.py",
           '            d[k.split(".", 1)[1]] = float(v)', "            pass", STUDY_CONTACT,
           "a case's contact.* value never replaces the [contact] table's"),
    Mutant("study-library-cases-misordered", "study/spec.py",
           "return tuple(f for f in self.files for _ in range(self._per_file))",
           "return tuple(self.files) * self._per_file", STUDY_CONTACT,
           "a library's cases pair each file with another file's grid point"),
    Mutant("study-contact-zero-allowed", "study/contact.py",
           "    check_range(where if p.distribution == \"grid\" else f\"{where}.low\", low, 0.0, "
           "None,\n                low_open=True,",
           "    check_range(where if p.distribution == \"grid\" else f\"{where}.low\", low, 0.0, "
           "None,\n                low_open=False,", STUDY_CONTACT,
           "a contact parameter whose distribution reaches 0 Pa accepted"),
    # ---- issue 19: the Surface page's elastic contact and the report's section
    Mutant("web-contact-family-collapsed", "web/elastic.py",
           "ps[0] if len(ps) == 1 else tuple(ps)", "ps[0]", WEB_CONTACT,
           "several pressures of the Surface page solved at the first only"),
    Mutant("web-contact-range-linear", "web/elastic.py",
           "lo * math.exp(r * k / (n - 1))", "lo + (hi - lo) * k / (n - 1)", WEB_CONTACT,
           "a range of pressures spaced linearly while the page says in log"),
    Mutant("web-contact-materials-nu-dropped", "web/elastic.py",
           'E = effective_modulus(mat["E1"], mat["nu1"], mat["E2"], mat["nu2"])',
           'E = effective_modulus(mat["E1"], 0.0, mat["E2"], mat["nu2"])', WEB_CONTACT,
           "E* from the materials without the body's Poisson ratio"),
    Mutant("web-contact-hardness-unplaced", "web/elastic.py",
           "if H is not None and H <= max(ps):", "if H is not None and H <= 0:", WEB_CONTACT,
           "a hardness below the pressure refused by the library, not next to its field"),
    Mutant("web-contact-boundary-periodic", "web/elastic.py",
           'boundary=e.get("boundary"), hardness', 'boundary=e.get("boundary") or '
           '"periodic", hardness', WEB_CONTACT,
           "a measured scan solved as periodic by default on the page"),
    Mutant("web-contact-law-first-pressure", "web/elastic.py",
           "        k = int(idx)", "        k = 0", WEB_CONTACT,
           "the Law page fits the first pressure of a family whatever was chosen"),
    Mutant("web-contact-map-unit-fixed", "web/figures_contact.py",
           'for m in maps], "Pa")', 'for m in maps][:0] + [1e6], "Pa")', WEB_CONTACT,
           "the contact map in MPa whatever the pressures"),
    Mutant("web-contact-undefined-hidden", "web/figures_contact.py",
           '"z": np.where(undefined, 1.0, np.nan).T.tolist(),',
           '"z": np.full(z.shape, np.nan).T.tolist(),', WEB_CONTACT,
           "undefined pixels of the contact map not drawn as such"),
    Mutant("web-contact-undefined-as-zero", "web/figures_contact.py",
           "return np.where(n > 0, s / np.where(n > 0, n, 1), np.nan)",
           "return np.where(n > 0, s / np.where(n > 0, n, 1), 0.0)", WEB_CONTACT,
           "undefined blocks of a large contact map shown as out of contact"),
    Mutant("report-hertz-radius-halved-area", "report/contact.py",
           "a_num = math.sqrt(res.contact.sum() * dx * dx / math.pi)",
           "a_num = math.sqrt(res.contact.sum() * dx * dx / (2 * math.pi))", REPORT,
           "the Hertz contact radius measured from half the contact area"),
    Mutant("report-westergaard-width-wrong", "report/contact.py",
           "2.0 / math.pi * math.asin(math.sqrt(f))", "1.0 / math.pi * math.asin(f)", REPORT,
           "the Westergaard closed form of the report mis-stated"),
    # ---- issue 20: the report's section on bodies
    Mutant("report-bodies-range-open-end", "report/bodies_runs.py",
           "(eps >= lo) & (eps <= hi)", "(eps >= lo) & (eps < hi)", REPORT_BODIES,
           "the sampling table's ranges of eps leave out their upper ends"),
    Mutant("report-bodies-stage-time-unscaled", "report/bodies_runs.py",
           "offset += scale * r.t[j]", "offset += r.t[j]", REPORT_BODIES,
           "a magnified stage's cut time added unscaled to the physical time"),
    Mutant("report-bodies-stage-speed-unscaled", "report/bodies_runs.py",
           "us.append(scale * r.u[first_row:j + 1])", "us.append(r.u[first_row:j + 1])",
           REPORT_BODIES, "a magnified stage's velocities recorded without scaling back"),
    Mutant("report-bodies-stage-join-twice", "report/bodies_runs.py",
           "first_row = 0 if k == 0 else 1", "first_row = 0", REPORT_BODIES,
           "the state at a cut recorded twice (once per stage)"),
    Mutant("report-bodies-fixed-point-inertia", "report/bodies_runs.py",
           "return -float(F @ e_v) - eps * (-T) / k", "return -float(F @ e_v) - eps * (-T) * k",
           REPORT_BODIES, "the footprint's own fixed point with k multiplied, not divided"),
    Mutant("report-bodies-drift-radial", "report/bodies_runs.py",
           "psi = np.arctan2(r[:, 0], -r[:, 1])", "psi = np.arctan2(r[:, 1], r[:, 0])",
           REPORT_BODIES, "the footprint's own drift with each point sliding radially, not "
           "along omega x r"),
    Mutant("report-bodies-drift-without-g", "report/bodies_runs.py",
           "a_ref = G * spin_drift_force(law)", "a_ref = spin_drift_force(law)", REPORT_BODIES,
           "the drift's closed-form acceleration without g"),
    Mutant("report-bodies-crossing-ratio-inverted", "report/bodies_bench.py",
           "ratio = float(v[k[0]] / w[k[0]])", "ratio = float(w[k[0]] / v[k[0]])", REPORT_BODIES,
           "the benchmark's end ratio as R omega / v"),
    Mutant("report-bodies-crossing-slide-only", "report/bodies_bench.py",
           "    s = v + w\n", "    s = v\n", REPORT_BODIES,
           "the end of the benchmark's motion judged by the sliding speed alone"),
    Mutant("report-bodies-reference-log10", "report/bodies_runs.py",
           "np.interp(math.log(w_fraction)", "np.interp(math.log10(w_fraction)", REPORT_BODIES,
           "the reference's eps looked up at log10 of the speed fraction against ln"),
    Mutant("report-bodies-point-mass-angle", "report/bodies_runs.py",
           "pm = slide(law, U0, 30.0, dt=1e-4)", "pm = slide(law, U0, 60.0, dt=1e-4)",
           REPORT_BODIES, "the rectangle compared with a point mass launched at another angle"),
    # ---- issue 19: family summaries read every member along one common axis
    Mutant("family-summary-axes-not-aligned", "friction/family.py",
           "    ref = align_rows(rows)\n", "    ref = align_rows([dict(r) for r in rows])\n",
           FAMILY_AXES, "derive's family summary lists each member along its own t_a (a "
           "member whose t_a crosses 0/180 deg shows mu_a+ and mu_a- exchanged)"),
    Mutant("fit-family-axes-not-aligned", "laws/family_report.py",
           '"axes": axes[k],', '"axes": member_axes(gl),', FAMILY_AXES,
           "fit's family summary gives each law's axes along its own t_a"),
    Mutant("study-load-axes-over-all-files", "study/contact.py",
           '            groups.setdefault(r.get("file") or "", [])',
           '            groups.setdefault("", [])',
           FAMILY_AXES, "a study's load-dependence rows turned to one axis over all the "
           "files, not each file's own"),
    Mutant("study-load-axes-not-aligned", "study/contact.py",
           "            ref = align_rows(g)\n",
           "            ref = align_rows([dict(r) for r in g])\n",
           FAMILY_AXES, "a study's load-dependence rows listed along each case's own t_a"),
    Mutant("family-reference-first-member", "friction/axes.py",
           'ref = axial_spread([r["principal_direction_deg"] for r in rows])["mean"]',
           'ref = rows[0]["principal_direction_deg"] if rows else None', FAMILY_AXES,
           "the reference direction is the first member's t_a, not the axial mean the "
           "output states"),
    Mutant("family-reference-directional-mean", "friction/axes.py",
           "m = 0.5 * np.angle(np.exp(2j * a).sum())", "m = np.angle(np.exp(1j * a).sum())",
           FAMILY_AXES + WINDOWS, "the reference is the mean of the t_a as directions, not "
           "as axes (two t_a 179 and 1 deg average to 90)"),
    Mutant("family-mu-b-not-exchanged", "friction/axes.py",
           '"mu_b_plus": r["mu_b_minus"], "mu_b_minus": r["mu_b_plus"]}',
           '"mu_b_plus": r["mu_b_plus"], "mu_b_minus": r["mu_b_minus"]}', FAMILY_AXES,
           "a turned member's mu_a+/- exchanged but not its mu_b+/-"),
    # ---- issue 19: the Law page fits the law family; the Motion page slides on one
    Mutant("web-family-members-unsorted", "web/law_family.py",
           "    for k in order:", "    for k in range(len(pressures)):", WEB_FAMILY,
           "the members fitted in the order typed while the pressures are sorted"),
    Mutant("web-family-collapsed", "web/tasks_contact.py",
           "if len(elastic.pressures) < 2:", "if len(elastic.pressures) < 200:", WEB_FAMILY,
           "the Law page's family fitted as the law of its first pressure alone"),
    Mutant("web-family-choice-collapsed", "web/elastic.py",
           'return {"elastic": e, "family"', 'return {"elastic": {**e, "pressures": ps[:1]}, '
           '"family"', WEB_FAMILY, "the family chosen on the Law page fitted at one pressure"),
    Mutant("web-family-motion-pressure-ignored", "web/tasks_motion.py",
           'law_at(gauge, spec.get("pressure"), PRESSURE',
           'law_at(gauge, spec.get("pressure") and gauge.pressures[0], PRESSURE',
           WEB_FAMILY, "the Motion page slides on a family's first member whatever pressure "
           "was given"),
    Mutant("web-family-motion-range-unchecked", "web/pages_motion.py",
           "if p is None or not lo <= p <= hi:", "if p is None:", WEB_FAMILY,
           "a pressure outside the family refused by the job, not next to its field"),
    Mutant("web-family-opened-as-one-law", "web/law_family.py",
           "if not isinstance(gauge, GaugeFamily):\n        return None",
           "if True:\n        return None", WEB_FAMILY,
           "a version-2 gauge file opened on the Law page as one law (a failed job)"),
    Mutant("web-family-csv-one-member", "web/law_family.py",
           'family_table(fam, n_csv)', 'family_table(GaugeFamily(fam.pressures[:1], '
           'fam.members[:1]), n_csv)', WEB_FAMILY, "the family's CSV table holds its first "
           "member only"),
    Mutant("web-family-download-unnamed", "web/law_family.py",
           'law_downloads(f"{source}_family", fam.kind)', 'law_downloads(source, fam.kind)',
           WEB_FAMILY, "a family's downloads named as a single law's"),
    Mutant("web-family-one-colour", "web/law_family.py",
           '"color": colour(k, n)', '"color": colour(0, n)', WEB_FAMILY,
           "every member's reservoir drawn in the same colour"),
    Mutant("web-risk-elastic-source-area-weighted", "web/tasks_motion.py",
           "texture, contact = _elastic_at_assembly(source, elastic, asm, ctx, bar)",
           "texture = load_source(source, ctx)[0]", WEB_CONTACT,
           "the web risk of an elastic Surface result uses its area-weighted surface"),
    # ---- issue 19: meshes pressed on their height grid, windows of contact, redraws
    Mutant("mesh-grid-last-triangle-wins", "surface/_mesh_grid_kernels.py",
           "                        if zz > z[i, j]:\n", "                        if True:\n",
           MESH_CONTACT, "a node takes the last triangle over it, not the highest (no upper "
           "envelope: a closed mesh shows its underside)"),
    Mutant("mesh-grid-edges-excluded", "surface/mesh_grid.py", "EDGE_EPS = 1e-9",
           "EDGE_EPS = -1e-9", MESH_CONTACT,
           "nodes on a triangle's edge or vertex belong to none (holes along every edge)"),
    Mutant("mesh-grid-one-node-short", "surface/mesh_grid.py",
           "min(c, MAX_NODES_PER_SIDE)) + 1 for c", "min(c, MAX_NODES_PER_SIDE)) for c",
           MESH_CONTACT, "the grid stops one node short of the mesh's far edges"),
    Mutant("mesh-force-edge-node-to-each", "surface/_mesh_grid_kernels.py",
           "                            out[t] += p[i, j] / count[i, j]",
           "                            out[t] += p[i, j]", MESH_CONTACT,
           "a node on an edge gives its whole force to each triangle there (the load counted "
           "twice or six times)"),
    Mutant("mesh-force-area-weighted", "surface/facets.py", "fpc = F[facing] / area",
           "fpc = np.full_like(area, total / area.sum())", MESH_CONTACT,
           "a mesh's triangles weighted by their area, not by the contact force"),
    Mutant("mesh-default-step-coarsest", "surface/mesh_grid.py",
           "step = min(step, float(np.median(e)) / NODES_PER_EDGE)",
           "step = max(step, float(np.median(e)) / NODES_PER_EDGE)", MESH_CONTACT,
           "the default grid step the coarser of the two rules, not the finer"),
    Mutant("window-redraw-same-origin", "friction/elastic_windows.py",
           "origin = _draw(plan.strata[k], src.shape, w, rng)", "origin = plan.origins[k]",
           WINDOWS_MORE, "a skipped random window 'redrawn' at the same place"),
    Mutant("window-grid-redrawn", "friction/elastic_windows.py",
           'window_strata(src.shape, w, k) if placement == "random" else None',
           "window_strata(src.shape, w, k) if placement else None",
           WINDOWS_MORE, "grid windows moved when they have too few defined pixels"),
    Mutant("window-family-first-member", "friction/window_summary.py",
           '**r["members"][i]}', '**r["members"][0]}', WINDOWS_MORE,
           "every pressure's spread computed from the first pressure's windows"),
    Mutant("window-redraws-miscounted", "friction/window_summary.py",
           '"redraws": sum(len(r["redrawn_from"]) for r in redrawn)',
           '"redraws": len(redrawn)', WINDOWS_MORE,
           "the redraws counted as the windows redrawn"),
    Mutant("window-contact-derives", "friction/elastic_windows.py",
           "    if not plan.derive:", "    if False:", WINDOWS_MORE,
           "contact --window derives friction it does not report (and its cost)"),
    # ---- the silent bugs of issue 25 (item 5) and their kin: the metamorphic tests'
    Mutant("mesh-forces-origin-zero", "surface/mesh_grid.py",
           "    x0, y0 = mg.origin\n", "    x0, y0 = 0.0, 0.0\n", METAMORPHIC_CONTACT,
           "a mesh's triangle forces looked up on a grid at the origin: load lost when the "
           "mesh's lowest corner is elsewhere"),
    Mutant("mesh-grid-origin-zero", "surface/mesh_grid.py",
           "np.ascontiguousarray(f), float(lo[0]), float(lo[1]),",
           "np.ascontiguousarray(f), 0.0, 0.0,", METAMORPHIC_CONTACT,
           "a mesh's height grid laid from the origin, not from its lowest corner"),
    Mutant("contact-footprint-squeezed-y", "bodies/pressure.py",
           "pts = np.column_stack([i * dx, j * dy])", "pts = np.column_stack([i * dx, j * dx])",
           METAMORPHIC_BODIES, "a footprint from a contact of oblong pixels squeezed along y"),
    Mutant("family-ellipse-turn-long-way", "laws/family.py",
           "        theta = e0.theta + w * turn\n",
           "        theta = e0.theta + w * (e1.theta - e0.theta)\n", METAMORPHIC_LAWS,
           "a family's ellipse t_a turned the long way between members"),
    Mutant("family-ellipse-turn-no-remainder", "laws/family.py",
           "        turn = math.remainder(e1.theta - e0.theta, 2 * math.pi)\n",
           "        turn = e1.theta - e0.theta\n", METAMORPHIC_LAWS,
           "a family's ellipse turn not reduced (a member written with t_a reversed)"),
    Mutant("family-star-turn-no-remainder", "laws/family.py",
           "turn = math.remainder(g1.principal_direction_deg - g0.principal_direction_deg, "
           "180.0)", "turn = g1.principal_direction_deg - g0.principal_direction_deg",
           METAMORPHIC_LAWS, "a family's star t_a interpolated the long way across 0/180 deg"),
    Mutant("family-bracket-next-pair", "laws/family.py",
           'k = int(np.searchsorted(ps, p, side="right")) - 1',
           'k = min(int(np.searchsorted(ps, p, side="right")), len(ps) - 2)',
           METAMORPHIC_LAWS, "a family's law between members 0 and 1 taken from members 1, 2"),
    Mutant("body-force-turned-wrong-way", "dynamics/body.py",
           "    R = _rot(-a)\n    c = np.asarray(force.constant)",
           "    R = _rot(a)\n    c = np.asarray(force.constant)", METAMORPHIC_BODIES,
           "an external force turned the wrong way into the frame of a turned law"),
    # ---- issue 26: crawling (what cosmic-ray cannot make: dropped terms, a changed flag,
    # word or key, a statement switched off)
    Mutant("crawl-gait-spin-dropped", "crawling/_kernels.py",
           "uf[2] = (iA * u[2] + spin[k] - spin[k + 1]) / iE",
           "uf[2] = (iA * u[2]) / iE", CRAWL,
           "the gait's own angular momentum left out of the body's turning"),
    Mutant("crawl-ground-texture-ignored", "crawling/solver.py",
           'QS_EPS if qs else 0.0, side == "body",', 'QS_EPS if qs else 0.0, True,', CRAWL,
           "--texture-on ground crawls with the texture on the body"),
    Mutant("crawl-no-transient", "crawling/solver.py",
           "transient_periods=0 if qs else done // 2,", "transient_periods=0,", CRAWL,
           "dynamic runs average their transient from rest into the speed"),
    Mutant("crawl-json-drift-key", "crawling/output.py",
           '"heading_drift_rad_per_period": res.heading_drift_rad_per_period,',
           '"heading_drift": res.heading_drift_rad_per_period,', CRAWL_CLI,
           "the JSON's heading drift under another key"),
    Mutant("crawl-rule-spelling", "crawling/solver.py", 'return "colinear"',
           'return "collinear"', CRAWL_CLI, "the colinear rule named otherwise than --rule"),
    Mutant("crawl-qs-start-from-rest", "crawling/_kernels.py",
           "if start == 0 and qs_eps > 0.0:", "if start == 0 and qs_eps < 0.0:", CRAWL,
           "quasi-static runs start from rest (a first half step of order dt)"),
    Mutant("crawl-fit-law-ignored", "cli/crawl.py",
           "fitted_law(texture, args.fit_law,", 'fitted_law(texture, "star",', CRAWL_CLI,
           "--fit-law ellipse fits the star law"),
    # ---- issue 27: the FE hand-off (the Fortran text is also mutated by
    # benchmarks/fortran_mutants.py; these are bugs its operators cannot make)
    Mutant("fe-fric-side-ignored", "fe/abaqus_fric.py", "THD = THD + PID", "THD = THD",
           FE_FRIC, "PROPS(3) = -1 (texture on the secondary surface) ignored"),
    Mutant("fe-fric-angle-in-radians", "fe/abaqus_fric.py", "THD = PROPS(2)*PID/180.0D0",
           "THD = PROPS(2)", FE_FRIC, "PROPS(2) read as radians, not degrees"),
    Mutant("fe-fric-ddtddg-transposed", "fe/abaqus_fric.py",
           "        DDTDDG(1,2) = AKD*(B11*ST + B12*CT)\n        DDTDDG(2,1) = AKD*(B21*CT - B22*ST)",
           "        DDTDDG(2,1) = AKD*(B11*ST + B12*CT)\n        DDTDDG(1,2) = AKD*(B21*CT - B22*ST)",
           FE_FRIC, "DDTDDG written transposed (row-major thinking)"),
    Mutant("fe-fric-start-stress-unturned", "fe/abaqus_fric.py",
           "        OUT(1) = CT*TAU(1) + ST*TAU(2)\n        OUT(2) = -ST*TAU(1) + CT*TAU(2)",
           "        OUT(1) = TAU(1)\n        OUT(2) = TAU(2)", FE_FRIC,
           "the start stress handed to the core in local, not law, axes"),
    Mutant("fe-vfric-state-by-contact-point", "fe/abaqus_explicit.py",
           'jn="jConSlvid(k)"', 'jn="k"', ("test_fe_vfric_law.py", "test_fe_explicit.py"),
           "VFRIC's statev indexed by contact point instead of surface node"),
    Mutant("fe-deck-props-order", "fe/abaqus_deck.py",
           "f\"{k}, {_g(pr['angle_deg'])}, {side}\",", "f\"{_g(pr['angle_deg'])}, {k}, {side}\",",
           ("test_fe_law_cli.py",), "FRIC's data line with PROPS(1) and PROPS(2) swapped"),
    Mutant("fe-family-low-clamp-uncounted", "fe/fortran/asp_core.f",
           "          IF (PL .LT. TLNP(1)-1.0D-12) NCLAMP = 1\n", "", FE_FRIC,
           "a pressure below a family's members clamped without being counted"),
    Mutant("fe-table-edges-ignored", "fe/table.py", "    edges = _edges(gl)\n    psi = TWO_PI",
           "    edges = np.empty(0)\n    psi = TWO_PI", ("test_fe_table.py",),
           "a star law's flat edges of D tabulated as if its force were continuous"),
    Mutant("fe-getfem-thermal-strain-sign", "fe/getfem_script.py",
           '"Sym(Grad_u) - alphaT*dT*Id(2)"', '"Sym(Grad_u) + alphaT*dT*Id(2)"',
           ("test_fe_getfem.py",), "the FE strip expands when it cools"),
    # ---- risk studies in blocks (issue 28)
    Mutant("blocks-dT-order-unchecked", "study/blocks.py",
           "valid &= _in(a, *L.DT) & _in(b, *L.DT) & (b >= a)",
           "valid &= _in(a, *L.DT) & _in(b, *L.DT)", BLOCKS,
           "a case with dT_min > dT_max answered in a block instead of refused"),
    Mutant("blocks-study-cycles-ignored", "study/blocks.py",
           "    if spec.get(\"cycles\") is not None:\n        cycles = np.full(m, "
           "float(spec[\"cycles\"]))\n    elif cycles is None:",
           "    if cycles is None:", BLOCKS,
           "the study's cycles (the command line's override) ignored by the block path"),
    Mutant("blocks-force-max-not-force-min", "study/blocks.py",
           "np.full(m, float(lo[\"force_max\"])) if \"force_max\" in lo else f0",
           "np.full(m, float(lo.get(\"force_max\", 0.0)))", BLOCKS,
           "a varied force_min without force_max: the force ramps to the file's default"),
    Mutant("blocks-texture-face-default-part", "microslip/friction_batch.py",
           'return axis, textured or fr.get("textured", "support")',
           'return axis, textured or fr.get("textured", "part")', BLOCKS,
           "the block path's textured face defaults to the part (mu+ and mu- swapped)"),
    Mutant("blocks-explicit-mu-chain-range", "study/blocks.py",
           "ok = ok & _in(x, L.MU[0], L.MU_FILE)", "ok = ok & _in(x, *L.MU)", BLOCKS,
           "an explicit mu above the file's 100 answered instead of refused"),
    Mutant("blocks-explicit-mu-over-the-texture", "study/blocks.py",
           "            if spec.get(\"texture\") is None:\n                arr[:] = x",
           "            arr[:] = x", BLOCKS,
           "a varied explicit mu_plus used where the study's texture gives the friction"),
    Mutant("blocks-refused-cases-not-rerun", "study/blocks.py",
           "        return [i for i, st in enumerate(self.status) if st is None]",
           "        return []",
           BLOCKS, "cases the arrays refuse are stored as empty ok rows, never run alone"),
    Mutant("blocks-inputs-of-another-block", "study/engine.py",
           "results.inputs = matrix[np.asarray(results.ids, np.int64)].tolist()",
           "results.inputs = matrix[:len(results.ids)].tolist()",
           ("test_study_blocks.py", "test_study_engine.py"),
           "a block's rows stored with the inputs of the study's first cases"),
    Mutant("two-node-no-split-at-the-kink", "microslip/_two_node_kernels.py",
           "    if (Fa - Fk) * (Fb - Fk) < 0.0:", "    if False:", TWO_NODE_BATCH,
           "a force crossing cp - cm inside an increment: the slip put on one node"),
    Mutant("two-node-lead-in-skipped", "microslip/_two_node_kernels.py",
           "        if dT[c, 0] != 0.0 or F[c, 0] != 0.0:", "        if False:",
           TWO_NODE_BATCH, "the way from the stress-free state to the cycle's first point "
           "skipped (dT_min != 0)"),
    Mutant("two-node-force-shares-swapped", "microslip/two_node_batch.py",
           '"start": (1.0, 0.0), "end": (0.0, 1.0)', '"start": (0.0, 1.0), "end": (1.0, 0.0)',
           TWO_NODE_BATCH, "force_at start and end swapped in the closed form"),
    Mutant("two-node-mean-of-the-sliders", "microslip/_two_node_kernels.py",
           "mean[cyc] = 0.5 * (st[1] + q0 / kt[c]) + 0.5 * (st[2] + q1 / kt[c])",
           "mean[cyc] = 0.5 * (st[1] + st[2])", TWO_NODE_BATCH,
           "the assembly's displacement taken as the sliders', without the contact springs"),
    Mutant("strip-dT_c-half-length-off-by-one", "microslip/strip_batch.py",
           "np.tanh(0.5 * (n - 1) * theta)", "np.tanh(0.5 * n * theta)",
           ("test_strip_batch.py",), "the discrete strip's half length counted in nodes, "
           "not elements"),
    Mutant("strip-shakedown-ignores-the-force", "microslip/strip_batch.py",
           "    ok = ((np.abs(F) == 0.0).all(axis=1) & (reach", "    ok = ((reach",
           ("test_strip_batch.py",), "a strip under a force taken as shaking down below dT_c"),
    Mutant("strip-shakedown-shared-drift-array", "microslip/strip_batch.py",
           '            "dT_c": dT_c, "margin": margin, "drift_per_cycle": np.where(ok, 0.0, '
           'np.nan),\n            "drift_after_cycles": np.where(ok, 0.0, np.nan),',
           '            "dT_c": dT_c, "margin": margin, "drift_per_cycle": (zero := '
           'np.where(ok, 0.0, np.nan)),\n'
           '            "drift_after_cycles": zero,',
           ("test_strip_batch.py", "test_study_blocks.py"),
           "one array for the drift per cycle and after the life: the exact solver's answers "
           "written into it overwrite each other (a bug made and caught here)"),
    # ---- command-line names of library fields
    Mutant("cli-spring-ratio-flags-dropped", "cli/sources.py",
           '{"springs.k_f / k_n ": "--k-f / --k-n ", **fields}', "{**fields}",
           ("test_hostile_texture.py",),
           "the spring stiffness ratio's refusal names k_f / k_n, not the flags given"),
    Mutant("cli-componentwise-field-not-flag", "cli/parsing.py",
           'with flag_names({dest + " ": flag + " "', 'with flag_names({dest + " ": dest + " "',
           ("test_componentwise_law.py",),
           "a componentwise coefficient refused under its field name, not its flag"),
]


def snapshot(dest: Path, from_head: bool = False) -> Path:
    """Copy asperity/ (numba caches included, mtimes kept) and benchmarks/ (the benchmark
    tests run its peers' scripts from the checkout) into dest, or with ``from_head`` the
    committed ones (``git archive HEAD``: no caches, compiled once by the baseline run);
    returns dest."""
    if from_head:
        dest.mkdir(parents=True)
        tar = subprocess.run(["git", "-C", str(REPO), "archive", "HEAD", "asperity", "benchmarks"],
                             capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", str(dest)], input=tar, check=True)
    else:
        shutil.copytree(REPO / "asperity", dest / "asperity", copy_function=shutil.copy2)
        shutil.copytree(REPO / "benchmarks", dest / "benchmarks",
                        ignore=shutil.ignore_patterns("__pycache__"))
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


def run_tests(root: Path, tests, timeout: float, extra=()) -> tuple[bool, str, float]:
    """(passed, first failing test or '', seconds) of pytest on ``tests`` with root first
    (``extra``: more pytest arguments)."""
    env = dict(os.environ, PYTHONPATH=str(root) + os.pathsep + os.environ.get("PYTHONPATH", ""),
               PYTHONDONTWRITEBYTECODE="1")
    env.pop("PYTEST_XDIST_WORKER", None)
    cmd = [sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider", "-p", "no:xdist",
           "--no-header", "-rfE", "--tb=no", *extra, *[str(TESTS / t) for t in tests]]
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
    ap.add_argument("--pytest-args", default="",
                    help="more pytest arguments, e.g. \"-k 'not ctrl_c'\" to leave out the "
                         "timed Ctrl-C tests on a loaded machine")
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
            ok, first, dt = run_tests(base, files, a.timeout, shlex.split(a.pytest_args))
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
                ok, first, dt = run_tests(root, m.tests, a.timeout, shlex.split(a.pytest_args))
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
