"""A gauge file's law as GetFEM weak-form language (GWFL) macros (``asperity law --gwfl``).

GetFEM's own friction operators project on a Coulomb ball (isotropic), so an asymmetric law
(mu+ != mu-) is written out by hand:

* **plan view** (the contact plane is the model plane, friction an area term): the traction
  of the textured support on the sliding body, ``asp_t = -asp_p p(psi)``, psi the angle of
  the slip increment ``asp_du`` in the law's frame; p(psi) (SPEC.md 3: force per unit normal
  load, along the slip) is the law's periodic piecewise-linear table written with
  ``pos_part``, exact with its derivative (GetFEM differentiates the macros for Newton).
  Regularised at vanishing slip over the slip length ``asp_eps``.
* **strip** (side view, x along the strip's axis = the law's +x): the bed's traction
  ``asp_tx``, an elastic spring ``asp_kt`` in series with a slider that holds
  ``mu+ asp_p`` towards +x and ``mu- asp_p`` towards -x, mu+ = p(0).x = T(0),
  mu- = -p(180 deg).x = T(180 deg): the return mapping of one increment,
  clamp(kt (u - s0), -mu- p, mu+ p), written with pos_part.

The file holds ``name(t) = expression`` / ``name'(t) = derivative`` lines (functions for
``gf.asm_define_function``) and ``name = expression`` lines (macros), ``#`` comments;
:func:`parse_gwfl` reads it back, and the GetFEM runs use exactly this text.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from .table import TOL as TABLE_TOL  # the table's accuracy: the Abaqus routines' own


def law_table(gl, tol: float = TABLE_TOL):
    """(psi (n,), p (n, 2)): the law's periodic piecewise-linear table over one turn, within
    ``tol`` of ``gl.force(psi).p`` everywhere (:func:`asperity.fe.table.law_table`, the table
    the Abaqus routines bake in too; TableError names the directions it cannot meet)."""
    from .table import law_table as table
    t = table(gl, tol=tol)
    return np.asarray(t.psi, float), np.asarray(t.p, float)


def _num(x: float) -> str:
    return repr(float(x))


def piecewise_linear(psi, f, var: str = "t") -> tuple[str, str]:
    """A periodic piecewise-linear function of ``var`` in [-pi, pi] through the knots
    ``(psi, f)`` (one turn, any start) as ``f0 + b (t + pi) + sum c_k pos_part(t - t_k)``,
    and its derivative ``b + sum c_k Heaviside(t - t_k)``: only pos_part, exact."""
    psi = np.asarray(psi, float)
    f = np.asarray(f, float)
    t = np.mod(psi + math.pi, 2.0 * math.pi) - math.pi          # knots in [-pi, pi)
    t = np.where(t >= math.pi, t - 2.0 * math.pi, t)    # a knot a rounding below -pi
    order = np.argsort(t)
    t, f = t[order], f[order]
    # close the period: the value at -pi (and pi) interpolated between the last and first
    span = (t[0] + math.pi) + (math.pi - t[-1])
    w = (math.pi - t[-1]) / span if span > 0 else 0.0
    f_pi = f[-1] + w * (f[0] - f[-1])
    if t[0] > -math.pi:
        t = np.concatenate([[-math.pi], t])
        f = np.concatenate([[f_pi], f])
    t = np.concatenate([t, [math.pi]])
    f = np.concatenate([f, [f_pi]])
    slopes = np.diff(f) / np.diff(t)
    terms = [_num(f[0]), f"{_num(slopes[0])}*({var}+{_num(math.pi)})"]
    dterms = [_num(slopes[0])]
    for tk, c in zip(t[1:-1], np.diff(slopes)):
        if c != 0.0:
            terms.append(f"{_num(c)}*pos_part({var}-{_num(tk)})")
            dterms.append(f"{_num(c)}*Heaviside({var}-{_num(tk)})")
    return _tidy(" + ".join(terms)), _tidy(" + ".join(dterms))


def _tidy(expr: str) -> str:
    return expr.replace("+ -", "- ").replace("--", "+")


def plan_law(gl, tol: float = TABLE_TOL) -> dict:
    """The plan-view vector law: ``functions`` (name, expression in t, derivative) for
    ``gf.asm_define_function`` -- p_x and p_y of the sliding angle t -- and ``macros``
    (name, expression): ``asp_t`` the support's traction on the body for the slip
    increment ``asp_du`` under the pressure ``asp_p``.  The table sits in functions, which
    GetFEM compiles once, not in the macros it compiles at every assembly."""
    psi, p = law_table(gl, tol)
    fx, dfx = piecewise_linear(psi, p[:, 0])
    fy, dfy = piecewise_linear(psi, p[:, 1])
    return {"functions": [("asp_px", fx, dfx), ("asp_py", fy, dfy)],
            "macros": [("asp_psi", "atan2(asp_du(2), asp_du(1))"),
                       ("asp_slip", "sqrt(asp_du.asp_du)"),
                       ("asp_t", ("-asp_p*asp_slip/sqrt(asp_slip*asp_slip + asp_eps*asp_eps)"
                                 "*[asp_px(asp_psi), asp_py(asp_psi)]"))],
            "knots": int(psi.size)}


def strip_limits(gl) -> tuple[float, float]:
    """(mu+, mu-) along the law's x axis: p(0).x and -p(180 deg).x (inf where the law
    holds the direction: self-locking)."""
    f = gl.force(np.array([0.0, math.pi]))
    mp, mm = float(f.p[0, 0]), -float(f.p[1, 0])
    return mp, mm


def strip_macros(mu_plus: float, mu_minus: float) -> list[tuple[str, str]]:
    """The strip's bed law: ``asp_tx``, the bed's traction on the body along x for the
    trial ``asp_kt (u(1) - asp_s0)``, clamped to [-mu- asp_p, mu+ asp_p] (an infinite
    coefficient: no limit that way)."""
    out = [("asp_ttr", "asp_kt*(u(1) - asp_s0)")]
    q = "asp_ttr"
    if math.isfinite(mu_minus):
        q = f"-{_num(mu_minus)}*asp_p + pos_part(asp_ttr + {_num(mu_minus)}*asp_p)"
    if math.isfinite(mu_plus):
        q = f"{q} - pos_part(asp_ttr - {_num(mu_plus)}*asp_p)"
    out.append(("asp_tx", f"-({q})"))
    return out


HEADER = """\
# GetFEM weak-form language (GWFL) macros of a friction law, written by asperity {version}
# law: {law}
# Units: SI (Pa, m); p(psi) is the force per unit normal load (SPEC.md 3), in the law's frame
# ({frame}).  The texture is on the rigid support; the body slides over it.
# Load (skip '#' lines): each pair 'NAME(t) = F' and "NAME'(t) = DF":
#   gf.asm_define_function(NAME, 1, F, DF); each 'NAME = EXPR': md.add_macro(NAME, EXPR)
#
# 1. Plan view (contact plane = model plane, friction as an area term): functions asp_px,
#    asp_py of the sliding angle t in [-pi, pi] (p's components), macros asp_psi .. asp_t.
#    Expects: asp_du (the slip increment u - u_prev, a macro you define), asp_p
#    (contact pressure, Pa), asp_eps (slip length of the regularisation, m, << the slip per
#    increment).  Gives asp_t = -asp_p p(psi) |du|/sqrt(|du|^2 + asp_eps^2), the support's
#    traction on the body (Pa); weak form: md.add_nonlinear_term(mim, '-asp_t.Test_u').
#    p(psi) is the law's periodic piecewise-linear table ({knots} knots), within {tol:g} of
#    `asperity law --psi` everywhere.  Sliding only (no stick): start Newton from a non-zero
#    slip increment (atan2 has no derivative at du = 0).
# 2. Strip (side view, x along the strip's axis = the law's +x), macros asp_ttr, asp_tx.
#    Expects: u (displacement; u(1) along x), asp_s0 (the bed's slip at the end of the
#    previous increment, m, a field on the contact face), asp_kt (tangential stiffness per
#    unit area, Pa/m), asp_p (contact pressure, Pa).  Gives asp_tx, the bed's traction on the
#    body (Pa): the return mapping of an elastic spring asp_kt and a slider holding
#    mu+ asp_p towards +x and mu- asp_p towards -x, mu+ = p(0).x = {mup}, mu- = -p(180).x =
#    {mum}.  Weak form: md.add_nonlinear_term(mim_vertex, '-asp_tx*Test_u(1)', CONTACT);
#    after each converged increment: asp_s0 <- interpolation of 'u(1) + asp_tx/asp_kt'.
#    Only +-x exist in a side view: the law's lateral part (p.y) does not enter.
"""


def gwfl_text(gl, law_name: str, tol: float = TABLE_TOL) -> str:
    """The ``--gwfl`` file: the header, the plan-view functions and macros, the strip
    macros."""
    from .. import __version__
    plan = plan_law(gl, tol)
    mp, mm = strip_limits(gl)
    frame = ("psi from t_a towards t_b" if getattr(gl, "principal_direction_deg", 0.0) == 0.0
             else "psi from +x towards +y of the source")
    head = HEADER.format(version=__version__, law=" ".join(law_name.split()), frame=frame,
                         knots=plan["knots"], tol=tol, mup=_mu(mp), mum=_mu(mm))
    lines = []
    for name, f, df in plan["functions"]:
        lines += [f"{name}(t) = {f}", f"{name}'(t) = {df}"]
    lines += [f"{k} = {v}" for k, v in plan["macros"] + strip_macros(mp, mm)]
    return head + "\n".join(lines) + "\n"


def _mu(x: float) -> str:
    return f"{x:.6g}" if math.isfinite(x) else "inf (self-locking)"


def parse_gwfl(text: str) -> dict:
    """``functions`` [(name, expression in t, derivative)] and ``macros`` [(name,
    expression)] of a ``--gwfl`` file."""
    funcs, ders, macros = {}, {}, []
    for i, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        name, eq, expr = s.partition("=")
        name, expr = name.strip(), expr.strip()
        base = name.removesuffix("(t)")
        key = base.rstrip("'")
        if not eq or not key.isidentifier() or not expr or base.count("'") > 1:
            raise InputError(f"GWFL file line {i}: expected 'name = expression' or "
                             f"'name(t) = expression', got {s[:40]!r}")
        if name.endswith("'(t)"):
            ders[key] = expr
        elif name.endswith("(t)"):
            funcs[key] = expr
        else:
            macros.append((name, expr))
    missing = sorted(set(funcs) ^ set(ders))
    if missing:
        raise InputError(f"GWFL file: function {missing[0]} needs both {missing[0]}(t) and "
                         f"{missing[0]}'(t)")
    return {"functions": [(k, funcs[k], ders[k]) for k in funcs], "macros": macros}


def write_gwfl(path, gl, law_name: str, tol: float = TABLE_TOL) -> str:
    """Write :func:`gwfl_text` atomically; returns the text."""
    from ..io import write_text_atomic
    text = gwfl_text(gl, law_name, tol)
    write_text_atomic(path, text)
    return text
