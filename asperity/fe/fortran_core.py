"""The law inside a Fortran user routine: the table as DATA statements and the core that
every generated routine calls (fixed form, 72 columns, double precision, IMPLICIT NONE).

``ASPLAW(IOP, PRESS, X, Y, OUT, NCLAMP)`` holds the table and answers, in the law's frame
(forces per unit normal load; PRESS the contact pressure, which picks the law of a family,
blended linearly in ln p between its levels and clamped outside them, NCLAMP = 1 then):

* IOP = 1: the force for sliding along X (rad): OUT(1:2), and d/dPRESS of it: OUT(3:4);
* IOP = 2: the distance OUT(1) from the origin to the boundary of C along the ray X (rad);
* IOP = 3: the return map of the trial stress (X, Y) from the start stress given in
  OUT(1:2) on entry: the stress OUT(1:2), its derivative
  with respect to the trial stress OUT(3:6) (column-major 2x2) and to PRESS OUT(7:8),
  OUT(9) = 0 stick / 1 slip, OUT(10) = |trial - stress|, OUT(11) the slip direction (rad);
* IOP = 4: the 1D return map along the line at angle Y (rad) of the trial stress X: the
  stress OUT(1), d/dX OUT(2), d/dPRESS OUT(3), OUT(9) = 0 stick / 1 slip.

``ASPFRC(PRESS, PSI, PX, PY, NCLAMP)`` and ``ASPRAD(PRESS, PHI, R, NCLAMP)`` are IOP 1 and 2
as plain subroutines (the explicit wrappers call them).

The return map (:mod:`asperity.fe.table`'s piecewise-linear force ``P(psi)`` on nodes):
stick while ``q = trial / PRESS`` lies in the nodes' polygon (C); otherwise the force
``P(psi)`` with ``q - P(psi) = lam (cos psi, sin psi)``, ``lam >= 0`` (the plastic slip is
along the law's own sliding direction for that force).  A non-associated law may have
several such roots: the one nearest the point where the elastic path from the start stress
leaves C is taken (the start itself when it lies on the boundary, so steady sliding stays
put), which is where the flow of the law goes on from.  The tangent is the exact derivative
of that root.
"""
from __future__ import annotations

from importlib import resources

import numpy as np

from ..laws.geometry import TWO_PI, polar_angle

#: the core's Fortran (package data), appended to every generated routine
CORE = (resources.files(__package__) / "fortran" / "asp_core.f").read_text(encoding="ascii")
#: values per continuation line and continuation lines per DATA statement
PER_LINE, LINES = 3, 19
#: nodes per block of the root search
BLOCK = 32



def comment_block(lines) -> str:
    """Fixed-form comment lines ``C text``, wrapped within 72 columns."""
    out = []
    for text in lines:
        text = text.rstrip()
        while len(text) > 70:
            cut = text.rfind(" ", 0, 70)
            cut = cut if cut > 20 else 70
            out.append("C " + text[:cut])
            text = "   " + text[cut:].lstrip()
        out.append("C " + text if text else "C")
    return "".join(x + "\n" for x in out)


def _num(v: float) -> str:
    """A double in at most 21 characters: 15 significant digits, D exponent."""
    m, e = f"{v:.14e}".split("e")
    return f"{m}D{int(e)}"


def data_lines(name: str, values: np.ndarray) -> list[str]:
    """DATA statements filling the 1-D array ``name`` with ``values`` (fixed form)."""
    vals = [_num(float(v)) for v in np.asarray(values, dtype=float).ravel()]
    out = []
    chunk = PER_LINE * LINES
    for a in range(0, len(vals), chunk):
        part = vals[a:a + chunk]
        out.append(f"      DATA ({name}(I),I={a + 1},{a + len(part)}) /")
        rows = [part[i:i + PER_LINE] for i in range(0, len(part), PER_LINE)]
        for r, row in enumerate(rows):
            end = "/" if r == len(rows) - 1 else ","
            out.append("     &" + ",".join(row) + end)
    return out


def table_arrays(psi: np.ndarray, p: np.ndarray, pressures=None) -> dict:
    """The arrays of ASPLAW for nodes psi (n,) and forces p (L, n, 2) (or (n, 2))."""
    p = np.asarray(p, dtype=float)
    if p.ndim == 2:
        p = p[None]
    levels = p.shape[0]
    c, s = np.cos(psi), np.sin(psi)
    lat = c[None, :] * p[:, :, 1] - s[None, :] * p[:, :, 0]
    phi = np.stack([np.unwrap(polar_angle(p[k])) for k in range(levels)])
    phi -= TWO_PI * np.floor((phi[:, :1] + np.pi) / TWO_PI)    # first in [-pi, pi)
    lnp = np.log(np.asarray(pressures, dtype=float)) if pressures is not None else np.zeros(1)
    return {"N": psi.size, "L": levels, "TPSI": psi, "TCS": c, "TSN": s,
            "TPX": p[:, :, 0].ravel(), "TPY": p[:, :, 1].ravel(), "TLAT": lat.ravel(),
            "TPHI": phi.ravel(), "TLNP": lnp, **_blocks(lat)}


def _blocks(lat: np.ndarray) -> dict:
    """Bounds of the lateral force over blocks of NB nodes (a block's segments run from its
    first node to the first node of the next block)."""
    levels, n = lat.shape
    nbk = -(-n // BLOCK)
    lo, hi = np.empty((levels, nbk)), np.empty((levels, nbk))
    for ib in range(nbk):
        idx = np.append(np.arange(ib * BLOCK, min((ib + 1) * BLOCK, n)), min((ib + 1) * BLOCK, n) % n)
        lo[:, ib] = lat[:, idx].min(axis=1)
        hi[:, ib] = lat[:, idx].max(axis=1)
    return {"NB": BLOCK, "NBK": nbk, "TBLO": lo.ravel(), "TBHI": hi.ravel()}


def law_source(table, comment: str = "") -> str:
    """The Fortran text of ASPLAW (the table) and the core, for a LawTable or FamilyTable."""
    from .table import FamilyTable
    if isinstance(table, FamilyTable):
        arr = table_arrays(table.psi, table.p, table.pressures)
    else:
        arr = table_arrays(table.psi, table.p)
    n, levels, nbk = arr["N"], arr["L"], arr["NBK"]
    lines = ["      SUBROUTINE ASPLAW(IOP,PRESS,X,Y,OUT,NCLAMP)",
             "C     the friction law's table (asperity): see ASPW"]
    lines += [f"C     {c}" for c in comment.splitlines()]
    lines += ["      IMPLICIT NONE",
              "      INTEGER IOP,NCLAMP,I,N,L,NB,NBK",
              f"      PARAMETER (N={n},L={levels},NB={arr['NB']},NBK={nbk})",
              "      DOUBLE PRECISION PRESS,X,Y,OUT(12),TPSI(N),TCS(N),TSN(N),",
              "     1 TPX(N*L),TPY(N*L),TLAT(N*L),TPHI(N*L),TLNP(L),TBLO(NBK*L),",
              "     2 TBHI(NBK*L)",
              "      SAVE TPSI,TCS,TSN,TPX,TPY,TLAT,TPHI,TLNP,TBLO,TBHI"]
    for name in ("TPSI", "TCS", "TSN", "TPX", "TPY", "TLAT", "TPHI", "TLNP", "TBLO", "TBHI"):
        lines += data_lines(name, arr[name])
    lines += ["      CALL ASPW(IOP,PRESS,X,Y,OUT,NCLAMP,N,L,TPSI,TCS,TSN,",
              "     1 TPX,TPY,TLAT,TPHI,TLNP,NB,NBK,TBLO,TBHI)",
              "      RETURN", "      END", "C"]
    return "\n".join(lines) + "\n" + CORE
