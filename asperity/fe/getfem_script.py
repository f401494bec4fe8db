"""GetFEM runs of asperity's FE hand-off, as a script for the system Python.

Run as ``/usr/bin/python3 -I getfem_script.py`` with a JSON job on stdin; it prints one JSON
object on stdout.  It imports NOTHING from asperity (GetFEM's Debian build needs the system
numpy, which the project's interpreter does not have): the friction law arrives in the job
as the GWFL macros that ``asperity law --gwfl`` writes (asperity/fe/gwfl.py), so the runs
use exactly that text.  Jobs (``task``):

* ``probe``: GetFEM's version (or the import error).
* ``strip``: the strip assembly as a 2D plane-stress body (side view: x along the length l,
  y through the height h, per metre of width) on a rigid support: the bottom face held in y
  and tied in x by the bed (stiffness k_t per area in series with the slider of the
  macros ``asp_tx``), marched through the load history.  Also its elastic limit.
* ``drag``: a square plate in plan view (the contact plane is the model plane), friction
  as an area term (macro ``asp_t`` of the slip increment, the law's table in the functions
  ``asp_px``, ``asp_py``), dragged by one edge along each direction; the pull force per
  unit normal load.

The process dies with its parent (PR_SET_PDEATHSIG, and a thread watching the parent id).
"""
import json
import os
import sys
import threading
import time


def _die_with_parent():
    parent = os.getppid()
    try:
        import ctypes
        ctypes.CDLL(None, use_errno=True).prctl(1, 9, 0, 0, 0)   # PR_SET_PDEATHSIG, SIGKILL
    except (OSError, AttributeError):
        pass
    if os.getppid() != parent:
        os._exit(1)

    def watch():
        while True:
            time.sleep(0.25)
            if os.getppid() != parent:
                os._exit(1)
    threading.Thread(target=watch, daemon=True).start()


def _macros(md, macros):
    for name, expr in macros:
        md.add_macro(name, expr)


def _functions(gf, functions):
    """The law's tables as GetFEM functions of one argument (compiled once)."""
    for name, expr, der in functions:
        gf.asm_define_function(name, 1, expr, der)


def _elastic(gf, md, E, nu):
    """Plane-stress Hooke's law with the thermal strain alpha_T dT (macros sig, eps)."""
    for k, v in (("E", E), ("nu", nu)):
        md.add_initialized_data(k, [v])
    md.add_macro("lps", "E*nu/(1-nu*nu)")
    md.add_macro("mus", "E/(2*(1+nu))")
    md.add_macro("epsm", "Sym(Grad_u) - alphaT*dT*Id(2)")
    md.add_macro("sig", "lps*Trace(epsm)*Id(2) + 2*mus*epsm")


def _strip_mesh(gf, np, job):
    l, h, nx, ny = job["l"], job["h"], job["nx"], job["ny"]
    m = gf.Mesh("cartesian", np.linspace(0.0, l, nx + 1), np.linspace(0.0, h, ny + 1))
    for reg, d in ((1, [0.0, -1.0]), (2, [-1.0, 0.0]), (3, [1.0, 0.0])):
        m.set_region(reg, m.outer_faces_with_direction(d, 0.01))
    return m


def _strip_model(gf, np, job, m, macros):
    """The strip model (regions 1 bottom, 2 left end, 3 right end); friction from
    ``macros`` (asp_tx: the bed's traction on the body, x)."""
    mfu = gf.MeshFem(m, 2)
    mfu.set_classical_fem(1)
    mim = gf.MeshIm(m, 2)
    # the bed acts at the bottom nodes (vertex quadrature: the chain's lumped tributary
    # lengths, and the slip history is exact nodal history)
    mimN = gf.MeshIm(m, gf.Integ("IM_NC_PARALLELEPIPED(2,1)"))
    mfs = gf.MeshFem(m, 1)
    mfs.set_classical_fem(1)
    md = gf.Model("real")
    md.add_fem_variable("u", mfu)
    for k, v in (("alphaT", job["alpha_T"]), ("dT", 0.0), ("asp_kt", job["k_t"]),
                 ("asp_p", job["p"]), ("Fx", 0.0)):
        md.add_initialized_data(k, [v])
    md.add_fem_data("asp_s0", mfs)
    _elastic(gf, md, job["E"], job["nu"])
    _macros(md, macros)
    md.add_nonlinear_term(mim, "sig:Grad_Test_u")
    md.add_nonlinear_term(mimN, "-asp_tx*Test_u(1)", 1)
    # the support holds the bottom face in y (bilateral; a penalty 1e3 x the bed's stiffness)
    md.add_nonlinear_term(mimN, "1e3*asp_kt*u(2)*Test_u(2)", 1)
    at = job.get("force_at", "uniform")
    if at == "uniform":                         # F (N/m of width) spread over the length
        md.add_nonlinear_term(mimN, f"-Fx/{job['l']!r}*Test_u(1)", 1)
    else:                                       # on the end face x = 0 or x = l
        md.add_nonlinear_term(mim, f"-Fx/{job['h']!r}*Test_u(1)", 2 if at == "start" else 3)
    return md, mfu, mfs, mim, mimN


def _bottom(np, mfs, l, nx):
    dofs = mfs.basic_dof_on_region(1)
    x = mfs.basic_dof_nodes()[0, dofs]
    order = np.argsort(x)
    w = np.full(dofs.size, 1.0 / nx)
    w[0] = w[-1] = 0.5 / nx
    return dofs[order], x[order], w


def _elastic_limit(gf, np, job, m):
    """dT_c of the FE model: the elastic response to dT = 1 K (no slip), then the smallest
    dT at which a bottom node's bed traction reaches mu+ p (slides +x) or mu- p (-x)."""
    elastic_bed = [("asp_tx", "-asp_kt*(u(1)-asp_s0)")]
    md, _mfu, mfs, _mim, _mimN = _strip_model(gf, np, job, m, elastic_bed)
    md.set_variable("dT", [1.0])
    it, ok = md.solve("max_res", job["max_res"], "max_iter", 5)
    if not ok:
        raise RuntimeError(f"the elastic solve did not converge ({it} iterations)")
    dofs, x, _ = _bottom(np, mfs, job["l"], job["nx"])
    q = -md.interpolation("asp_tx", mfs, 1)[dofs]      # bed force on the support per K, Pa
    mup = job["mu_plus"] if job["mu_plus"] is not None else float("inf")
    mum = job["mu_minus"] if job["mu_minus"] is not None else float("inf")
    with np.errstate(divide="ignore"):
        lim = np.where(q > 0, mup * job["p"] / np.where(q > 0, q, 1.0),
                       np.where(q < 0, mum * job["p"] / np.where(q < 0, -q, 1.0), np.inf))
    i = int(np.argmin(lim))
    return {"elastic_limit_K": float(lim[i]) if np.isfinite(lim[i]) else None,
            "first_slip_x_m": float(x[i]), "first_slip_towards": "+x" if q[i] > 0 else "-x"}


def run_strip(gf, np, job):
    t0 = time.time()
    m = _strip_mesh(gf, np, job)
    out = {"elements": int(m.nbcvs()), "nodes": int(m.nbpts()),
           "elements_along_l": job["nx"], "elements_through_h": job["ny"]}
    out.update(_elastic_limit(gf, np, job, m))
    md, mfu, mfs, _mim, _mimN = _strip_model(gf, np, job, m, job["macros"])
    out["dofs"] = int(mfu.nbdof())
    dofs, x, w = _bottom(np, mfs, job["l"], job["nx"])
    res = job["max_res"]
    newton = incs = 0
    worst = 0

    state = {"dT": 0.0, "F": 0.0}
    cuts = 0

    def solve(dT, F, depth=0):
        """One increment to (dT, F); halved (up to 10 times) when semismooth Newton
        stalls on the slider's kinks."""
        nonlocal newton, worst, cuts
        u0 = md.variable("u").copy()
        md.set_variable("dT", [dT])
        md.set_variable("Fx", [F])
        it, ok = md.solve("max_res", res, "max_iter", job["max_iter"], "lsearch", "basic")
        newton += int(it)
        if ok:
            worst = max(worst, int(it))
            md.set_variable("asp_s0", md.interpolation("u(1) + asp_tx/asp_kt", mfs, 1))
            state.update(dT=dT, F=F)
            return
        if depth >= 10:
            raise RuntimeError(f"Newton did not converge at dT = {dT:g} K (increment "
                               f"{incs + 1}, {it} iterations, halved 10 times)")
        cuts += 1
        md.set_variable("u", u0)
        a, b = state["dT"], state["F"]
        solve(0.5 * (a + dT), 0.5 * (b + F), depth + 1)
        solve(dT, F, depth + 1)

    def step(dT, F):
        nonlocal incs
        solve(dT, F)
        incs += 1

    def profile():
        return md.interpolation("u(1)", mfs, 1)[dofs]
    for dT, F in zip(job["lead_in"]["dT"], job["lead_in"]["F"]):
        step(dT, F)
    ends = [profile()]
    drifts = []
    for c in range(job["max_cycles"]):
        for dT, F in zip(job["cycle"]["dT"], job["cycle"]["F"]):
            step(dT, F)
        ends.append(profile())
        drifts.append(float((ends[-1] - ends[-2]) @ w))
        if c + 1 >= job["min_cycles"] and abs(drifts[-1] - drifts[-2]) <= job["stabilised"]:
            break
    out.update({"drifts_m": drifts, "drift_per_cycle_m": drifts[-1],
                "mean_u_m": [float(u @ w) for u in ends], "x_m": x.tolist(),
                "u_end_m": ends[-1].tolist(), "cycles_run": len(drifts),
                "increments": incs, "newton_iterations": newton,
                "max_newton_per_increment": worst, "halvings": cuts,
                "seconds": time.time() - t0})
    return out


def run_drag(gf, np, job):
    """Pull force per unit normal load of a plate dragged along each direction."""
    t0 = time.time()
    a, n = job["size"], job["n"]
    m = gf.Mesh("cartesian", np.linspace(0.0, a, n + 1), np.linspace(0.0, a, n + 1))
    m.set_region(2, m.outer_faces_with_direction([-1.0, 0.0], 0.01))
    mfu = gf.MeshFem(m, 2)
    mfu.set_classical_fem(1)
    mim = gf.MeshIm(m, 2)
    md = gf.Model("real")
    md.add_fem_variable("u", mfu)
    md.add_fem_data("u_prev", mfu)
    for k, v in (("alphaT", 0.0), ("dT", 0.0), ("asp_p", job["p"]),
                 ("asp_eps", job["eps"]), ("ud", [0.0, 0.0])):
        md.add_initialized_data(k, v if isinstance(v, list) else [v])
    _elastic(gf, md, job["E"], job["nu"])
    md.add_macro("asp_du", "u - u_prev")
    _functions(gf, job["functions"])
    _macros(md, job["macros"])
    md.add_nonlinear_term(mim, "sig:Grad_Test_u")
    md.add_nonlinear_term(mim, "-asp_t.Test_u")
    md.add_Dirichlet_condition_with_simplification("u", 2, "ud")
    left = mfu.basic_dof_on_region(2)
    forces, newton = [], 0
    area = a * a
    for deg in job["directions_deg"]:
        d = job["drag"] * np.array([np.cos(np.radians(deg)), np.sin(np.radians(deg))])
        U = np.zeros(mfu.nbdof())
        md.set_variable("u_prev", U)
        for k in range(1, job["steps"] + 1):
            md.set_variable("ud", k * d)
            md.set_variable("u", U + np.tile(d, U.size // 2))  # predictor: a rigid slide
            it, ok = md.solve("max_res", job["max_res"], "max_iter", job["max_iter"],
                              "lsearch", "simplest")
            if not ok:
                raise RuntimeError(f"Newton did not converge dragging along {deg:g} deg")
            newton += int(it)
            if k < job["steps"]:
                U = md.variable("u").copy()
                md.set_variable("u_prev", U)
        # the last increment (u_prev its start): the reaction of the dragged edge is the
        # residual there; the friction's integral is the same force, opposite
        r = gf.asm("generic", mim, 1, "sig:Grad_Test_u - asp_t.Test_u", -1,
                   md)[:mfu.nbdof()]
        pull = np.array([r[left[left % 2 == 0]].sum(), r[left[left % 2 == 1]].sum()])
        fr = gf.asm("generic", mim, 0, "asp_t", -1, md)
        du = md.interpolation("asp_du", mfu)
        forces.append({"direction_deg": deg, "pull": (pull / (job["p"] * area)).tolist(),
                       "friction": (-fr / (job["p"] * area)).tolist(),
                       "slip_spread": float(np.ptp(du[0::2]) + np.ptp(du[1::2]))
                       / job["drag"]})
    return {"forces": forces, "elements": int(m.nbcvs()), "nodes": int(m.nbpts()),
            "newton_iterations": newton, "seconds": time.time() - t0}


def main():
    _die_with_parent()
    try:
        import getfem as gf
        import numpy as np
    except ImportError as exc:
        print(json.dumps({"error": "import", "detail": str(exc)}))
        return 0
    gf.util_trace_level(0)
    job = json.loads(sys.stdin.read())
    task = job.get("task")
    try:
        if task == "probe":
            out = {"getfem": gf.getfem_env("release"), "numpy": np.__version__}
        elif task == "strip":
            out = run_strip(gf, np, job)
        elif task == "drag":
            out = run_drag(gf, np, job)
        else:
            out = {"error": "task", "detail": f"unknown task {task!r}"}
    except (RuntimeError, ValueError) as exc:
        out = {"error": "solve", "detail": " ".join(str(exc).split())}
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
