"""Closed-form homogenised friction of faceted textures (SPEC.md sections 1-2).

A spring tip sliding on a plane face of gradient ``g`` and local friction ``mu`` in the
horizontal direction ``s`` moves with the lifted velocity ``v = (s, g.s)``; the contact
force on it is proportional to ``m - mu v/|v|`` (``m`` the upward unit normal of the
face).  The tangential/normal ratio of that force, with the sign that makes it resist the
motion, is the face's reservoir point

    p_f(s) = -F_h / F_z ,      F = m - mu v/|v| .

Averaging over the faces with their horizontal-area weights (uniformly spread springs,
equal mean compression on every face) gives the texture's reservoir point
``p(psi) = sum_f w_f p_f / sum_f w_f`` over the faces in contact:

* ``all-faces`` -- compliant springs touch every face (Antoni et al.);
* ``windward``  -- rigid asperities: only faces that the motion climbs (``g.s > 0``) carry
  load (Michalowski-Mroz).  When no face is climbed but some are level with the motion
  (sliding exactly along the ridges) the reservoir is set-valued; the point returned is
  the all-faces average of the level faces, which lies on that segment, and the direction
  is flagged ``set_valued``.

Where ``F_z <= 0`` on a loaded face the tip cannot climb: the direction is *self-locking*
(the macroscopic coefficient is infinite).  It is flagged, never returned as NaN.

For psi = 0 on a wedge this reduces to ``H(x, y) = (x + tan y)/(1 - x tan y)`` and the
formulas of :func:`asperity.texture.closed_form.compute_wedge_axis_closed_form`.  Many faces
(measured surfaces) go through the streamed kernel of :mod:`asperity.friction.facet_reservoir`,
which gives the same result.
"""
from __future__ import annotations

import numpy as np

from ..errors import InputError
from .reservoir import (
    LEVEL_SLOPE_TOL,
    LOCK_TOL,
    NO_WINDWARD_FACE,
    Reservoir,
    check_contact,
    check_progress,
    check_psi,
)


def compute_face_reservoir(gradient, mu, weight, psi, contact: str = "all-faces") -> Reservoir:
    """Reservoir points of a set of plane faces for the sliding directions ``psi``.

    gradient : (n, 2) float, face gradients (dz/dx, dz/dy)
    mu       : (n,) float, local friction of each face (>= 0)
    weight   : (n,) float, horizontal-area weights (>= 0, not all zero)
    psi      : (m,) float, sliding directions in radians
    contact  : "all-faces" or "windward"

    Memory is O(n m); this is the reference implementation used for wedge textures.
    """
    check_contact(contact)
    g = np.atleast_2d(np.asarray(gradient, dtype=float))
    mu = np.atleast_1d(np.asarray(mu, dtype=float))
    w = np.atleast_1d(np.asarray(weight, dtype=float))
    psi = check_psi(psi)
    if g.ndim != 2 or g.shape[1] != 2:
        raise InputError(f"gradient must have shape (n, 2), got {g.shape}")
    if mu.shape != (g.shape[0],) or w.shape != (g.shape[0],):
        raise InputError(f"mu and weight must have shape ({g.shape[0]},), got {mu.shape} and {w.shape}")
    if np.any(w < 0) or not np.any(w > 0):
        raise InputError("weight must be >= 0 and not all zero")
    if not (np.all(np.isfinite(g)) and np.all(np.isfinite(mu))):
        raise InputError("gradient and mu must be finite")

    sx, sy = np.cos(psi)[:, None], np.sin(psi)[:, None]          # (m, 1)
    gx, gy = g[None, :, 0], g[None, :, 1]                         # (1, n)
    nrm = np.sqrt(1.0 + gx * gx + gy * gy)
    slope = gx * sx + gy * sy                                     # (m, n): g . s
    vlen = np.sqrt(1.0 + slope * slope)
    fz = 1.0 / nrm - mu * slope / vlen                            # vertical part of m - mu v/|v|
    # horizontal part of -(m - mu v/|v|) = g/nrm + mu s/|v|
    hx = gx / nrm + mu * sx / vlen
    hy = gy / nrm + mu * sy / vlen

    if contact == "all-faces":
        loaded = np.broadcast_to(w[None, :] > 0, slope.shape)
        set_valued = np.zeros(psi.shape, dtype=bool)
    else:
        windward = (slope > LEVEL_SLOPE_TOL) & (w[None, :] > 0)
        none = ~windward.any(axis=1)
        level = (np.abs(slope) <= LEVEL_SLOPE_TOL) & (w[None, :] > 0)
        loaded = np.where(none[:, None], level, windward)
        steep = np.hypot(gx, gy) > LEVEL_SLOPE_TOL
        set_valued = none & (level & steep).any(axis=1)
        if np.any(none & ~level.any(axis=1)):
            # cannot happen with weights > 0: some face is level or climbed in every direction
            raise InputError(NO_WINDWARD_FACE)

    locked_faces = loaded & (fz <= LOCK_TOL)
    locked = locked_faces.any(axis=1)
    locked_face = np.where(locked, np.argmax(locked_faces, axis=1), -1)
    ww = np.where(loaded, w[None, :], 0.0)
    safe_fz = np.where(fz > LOCK_TOL, fz, 1.0)
    wsum = ww.sum(axis=1)
    pa = (ww * hx / safe_fz).sum(axis=1) / wsum
    pb = (ww * hy / safe_fz).sum(axis=1) / wsum
    p = np.column_stack([pa, pb])
    p[locked] = np.inf
    return Reservoir(psi=psi, p=p, locked=locked, locked_face=locked_face.astype(np.int64),
                     set_valued=set_valued, contact=contact)


#: from this many faces on, reservoirs are computed by the streamed numba facet kernel
FACET_KERNEL_MIN_FACES = 64


def compute_faces_reservoir(faces, psi, contact: str = "all-faces", progress=None) -> Reservoir:
    """Reservoir points of :class:`~asperity.friction.reservoir.Faces`: the NumPy reference for a few
    faces (wedge textures), the parallel streamed kernel for many (surfaces); both give
    the same result.  ``progress(fraction)`` is called during long kernel runs."""
    n = faces.gradient.shape[0]
    check_progress(progress)
    if n < FACET_KERNEL_MIN_FACES:
        return compute_face_reservoir(faces.gradient, faces.mu, faces.weight, psi, contact)
    from .facet_reservoir import compute_facet_reservoir
    mu = faces.mu
    if mu.strides == (0,):                       # uniform friction broadcast over the facets
        mu = float(mu[0])
    return compute_facet_reservoir(faces.gradient[:, 0], faces.gradient[:, 1], mu,
                                   faces.weight, psi, contact, progress=progress)


def faces_source(texture):
    """``texture`` if it has faces (a wedge texture, a FacetSurface); a HeightMap or a
    TriangleMesh as its facets (default friction, mean slope removed as by load_surface);
    else InputError."""
    from ..surface.topography import HeightMap, TriangleMesh
    if isinstance(texture, (HeightMap, TriangleMesh)):
        from ..surface.facets import surface_facets
        return surface_facets(texture, level_slope=True)
    if not callable(getattr(texture, "faces", None)) or isinstance(texture, type):
        from ..errors import _kind, _show
        raise InputError(f"texture must be a wedge texture, a surface (load_surface) or a "
                         f"HeightMap or TriangleMesh, got {_show(texture)} ({_kind(texture)})")
    return texture


def compute_reservoir(texture, psi, contact: str = "all-faces", progress=None) -> Reservoir:
    """Reservoir points p(psi) of a texture or surface (anything with ``faces()``, or a
    HeightMap/TriangleMesh), psi in radians."""
    return compute_faces_reservoir(faces_source(texture).faces(), psi, contact, progress)


def compute_axis_coefficients(texture, contact: str = "all-faces") -> dict:
    """mu_a+, mu_a-, mu_b+, mu_b- = p . s for psi = 0, 180, 90, 270 deg (inf if self-locking).

    Sliding exactly along the ridges in the windward regime is set-valued; the value
    returned there is that of the level faces' average (see module docstring).
    """
    psi = np.array([0.0, np.pi, 0.5 * np.pi, 1.5 * np.pi])
    r = compute_reservoir(texture, psi, contact)
    t = r.tangential
    return {"mu_a_plus": float(t[0]), "mu_a_minus": float(t[1]),
            "mu_b_plus": float(t[2]), "mu_b_minus": float(t[3])}
