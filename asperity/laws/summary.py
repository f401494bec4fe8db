"""What a fitted law is, in numbers and in words: the JSON summary and the terminal text of
``asperity fit`` and ``asperity law``, and the force of a law for one sliding direction."""
from __future__ import annotations

import math


def summary(gl) -> dict:
    """JSON summary of a fitted law (no bulky arrays)."""
    from ..errors import check_instance
    from .fitting import GaugeLaw
    check_instance("gauge law", gl, GaugeLaw)
    out = {"law": gl.kind, "source": gl.source,
           "principal_direction_deg": gl.principal_direction_deg, "fit": gl.fit.to_dict()}
    if gl.kind == "truncated-ellipse":
        out["parameters"] = {**gl.law.C.axes, "theta_rad": gl.law.C.theta}
    elif gl.kind == "componentwise":
        from .componentwise import parameters
        out["parameters"] = parameters(gl.law)
    else:
        out["parameters"] = {"C_vertices": int(gl.law.C.n), "D_samples": int(gl.law.D.psi.size),
                             "D_flat_edges_deg": [math.degrees(x) for x in gl.law.D.edges]}
    return out


def format_fit(gl) -> str:
    """Fit quality for the terminal."""
    from ..errors import check_instance
    from .fitting import GaugeLaw
    check_instance("gauge law", gl, GaugeLaw)
    r = gl.fit
    tex = gl.source.get("texture", {})
    lines = [f"law: {gl.kind}   contact: {gl.source.get('contact')}   texture: "
             + ", ".join(f"{k}={v}" for k, v in tex.items() if k in
                         ("kind", "alpha_deg", "beta_deg", "mu_alpha", "mu_beta", "source")),
             f"fitted points: {r.n_points}"]
    if gl.kind == "truncated-ellipse":
        e = gl.law.C
        lines.append(f"  mu_a+ = {e.mu_a_plus:.6f}  mu_a- = {e.mu_a_minus:.6f}  "
                     f"mu_b+ = {e.mu_b_plus:.6f}  mu_b- = {e.mu_b_minus:.6f}"
                     + (f"  (t_a at {gl.principal_direction_deg:.3f} deg)"
                        if gl.principal_direction_deg else ""))
    elif gl.kind == "componentwise":
        from .componentwise import coefficients
        k = coefficients(gl.law)
        lines.append(f"  rule: componentwise (Hu et al.)  mu_f = {k['mu_f']:.6f} (+t_a)  "
                     f"mu_b = {k['mu_b']:.6f} (-t_a)  mu_t = {k['mu_t']:.6f} (+-t_b)")
    lines += [f"radial error at the data: max {r.max_radial_error:.3e}, rms {r.rms_radial_error:.3e}",
              f"largest angle between the data force and the law's force: "
              f"{r.max_angle_error_deg:.4g} deg"]
    if r.holdout_directions:
        lines.append(f"off the fitted directions ({r.holdout_directions} midway directions): "
                     f"max magnitude error {r.holdout_max_magnitude_error:.3e}, max angle "
                     f"{r.holdout_max_angle_deg:.4g} deg")
    lines.append(f"C convex: {'yes' if r.C_convex else 'no'} (smallest turning angle "
                 f"{r.C_min_turn_deg:.4g} deg)")
    if r.D_convex is not None:
        lines.append(f"D convex: {'yes' if r.D_convex else 'NO'} (min d(angle)/dpsi "
                     f"{r.D_min_turn_rate:.4g}); closure residual ln h(2pi) - ln h(0) = "
                     f"{r.closure_residual:.3e}, closed by turning the forces "
                     f"{r.closure_max_angle_deg:.3g} deg")
    lines.append(f"dissipation p.s >= 0: {'yes' if r.admissible else 'NO'} "
                 f"(min {r.min_dissipation:.4g})")
    return "\n".join(lines)


def force_at(gl, psi_deg: float) -> dict:
    """The force of the law ``gl`` for the sliding direction ``psi_deg`` (deg): the object
    printed by ``asperity law --psi DEG --json``."""
    import numpy as np

    from ..errors import check_instance, check_range
    from .fitting import GaugeLaw
    check_instance("gauge law", gl, GaugeLaw)
    x = check_range("psi_deg", psi_deg, -3600.0, 3600.0, unit="deg")
    f = gl.force(np.array([math.radians(x)]))
    out = {"psi_deg": x, "p": [float(f.p[0, 0]), float(f.p[0, 1])],
           "tangential": float(f.tangential[0]), "lateral": float(f.lateral[0]),
           "alpha": float(f.alpha[0]), "set_valued": bool(f.set_valued[0])}
    if f.set_valued[0]:
        out["segment"] = [f.p_minus[0].tolist(), f.p_plus[0].tolist()]
    return out
