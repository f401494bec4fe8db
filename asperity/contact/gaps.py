"""The complementarity of a contact iterate (:mod:`.solver`, :mod:`.plastic`): the length
its gaps are measured against, and whether an iterate holds it."""
from __future__ import annotations

import numpy as np


def reference_length(space, z, pbar: float) -> float:
    """The length the complementarity is measured against: the larger of the height range
    and the displacement of a pixel under the nominal pressure alone (the heights far
    below it: full contact, whose gaps are the rounding of the displacement)."""
    return max(float(np.nanmax(z) - np.nanmin(z)), pbar * space.self_compliance)


def complementary(K, space, p, u, h, H, fresh: int, limit: float, pbar: float) -> bool:
    """Whether the iterate (p, u) of the heights ``h`` satisfies the complementarity to
    ``limit`` of :func:`reference_length` (u recomputed first when it was updated
    incrementally; ``K``: the kernels, :mod:`._pk_kernels`)."""
    if fresh:
        space.apply(p, u)
    hf, pf, uf = h.reshape(-1), p.reshape(-1), u.reshape(-1)
    s1, _, n, _, _ = K.gap_sums(uf, hf, pf, H, 0.0)
    gbar = s1 / n if n > 0 else float(np.max(np.where(p >= H, u - h, -np.inf)))
    off = max(K.gap_violation(uf, hf, pf, H, gbar)) / reference_length(space, h, pbar)
    return off <= limit
