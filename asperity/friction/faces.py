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
    """Reservoir points p(psi) of a texture or surface for the sliding directions ``psi``.

    The closed-form homogenisation of SPEC.md section 2: each face's reservoir point,
    averaged over the faces in contact with their horizontal-area weights.  A few faces
    (wedge textures) go through the NumPy reference, many (surfaces) through the streamed
    numba kernel of :func:`asperity.compute_facet_reservoir`; both give the same result.

    Parameters
    ----------
    texture : WedgeTexture, GaussianWedgeTexture, FacetSurface, HeightMap or TriangleMesh
        Anything with ``faces()`` (a wedge texture, :func:`asperity.load_surface`'s
        surface), or a height map or mesh of :func:`asperity.read_surface`, taken as its
        facets (default local friction 0.1, mean slope removed as by ``load_surface``).
    psi : float or array_like
        Sliding directions, radians from ``t_a`` towards ``t_b`` (the file's x towards y
        for a surface), a number or a 1-d array of finite angles within +-1e4.
    contact : {"all-faces", "windward"}, default "all-faces"
        Contact regime: compliant springs touch every face (Antoni et al.), or rigid
        asperities load only the faces the motion climbs (Michalowski-Mroz).
    progress : callable or None, default None
        ``progress(fraction)`` called during long kernel runs.

    Returns
    -------
    Reservoir
        ``psi`` (m,) radians; ``p`` (m, 2), ``p = -lambda_T / lambda_N`` in the
        (t_a, t_b) frame, dimensionless, ``inf`` in self-locking rows; ``locked`` (m,)
        bool; ``locked_face`` (m,) int, the first self-locking face (-1: none);
        ``set_valued`` (m,) bool; ``contact``.  Its properties ``tangential`` (T = p . s)
        and ``lateral`` (L = p . s_perp) are (m,) arrays.

    Raises
    ------
    asperity.InputError
        A texture of another kind, a direction out of range or NaN, an unknown contact
        regime, or (windward) a direction in which every face descends.

    See Also
    --------
    asperity.compute_axis_coefficients : The four axis directions only.
    asperity.derive : Every direction with the axis coefficients and the diagnostics.
    asperity.compute_facet_reservoir : The same from arrays of facet gradients.
    asperity.simulate_reservoir : The spring simulation behind the closed form.

    Notes
    -----
    A tip sliding in the horizontal direction ``s`` on a face of gradient ``g``, upward
    unit normal ``m`` and local friction ``mu`` moves with the lifted velocity
    ``v = (s, g . s)``; the contact force on it is proportional to ``F = m - mu v/|v|``, and
    the face's point is ``p_f = -F_h / F_z`` (horizontal over vertical part, the sign
    making it resist the motion).  Where ``F_z <= 0`` on a loaded face the tip cannot
    climb: the direction self-locks, flagged in ``locked`` and never returned as NaN.
    Windward contact is set-valued when no face is climbed but some are level with the
    motion (sliding exactly along the ridges): the point returned is the all-faces
    average of the level faces, which lies on that segment, and ``set_valued`` is True.

    Examples
    --------
    SPEC.md's windward check: the symmetric 30 deg wedge with mu = 0.3 has a non-convex,
    star-shaped reservoir with a jump when sliding along the ridges:

    >>> tex = asperity.WedgeTexture(30.0, 30.0, 0.3, 0.3)
    >>> r = asperity.compute_reservoir(tex, np.radians([0.0, 89.0, 90.0, 91.0]),
    ...                                contact="windward")
    >>> print(f"|p| = {np.hypot(*r.p[0]):.3f} at psi = 0")
    |p| = 1.061 at psi = 0
    >>> r.p[1:].round(3)
    array([[ 0.585,  0.348],
           [ 0.   ,  0.346],
           [-0.585,  0.348]])
    >>> r.set_valued
    array([False, False,  True, False])
    """
    return compute_faces_reservoir(faces_source(texture).faces(), psi, contact, progress)


def compute_axis_coefficients(texture, contact: str = "all-faces") -> dict:
    """Friction coefficients along the axes: mu_a+, mu_a-, mu_b+, mu_b- of a texture.

    Each is ``T = p . s``, the friction force per unit normal load along the sliding
    direction, for psi = 0, 180, 90 and 270 deg (sliding along ``+t_a``, ``-t_a``,
    ``+t_b``, ``-t_b``), by the closed form of :func:`asperity.compute_reservoir`.

    Parameters
    ----------
    texture : WedgeTexture, GaussianWedgeTexture, FacetSurface, HeightMap or TriangleMesh
        As for :func:`asperity.compute_reservoir`.  A surface is read in its file's frame
        (``t_a`` = +x); :func:`asperity.derive` finds a surface's principal direction.
    contact : {"all-faces", "windward"}, default "all-faces"
        Contact regime, as for :func:`asperity.compute_reservoir`.

    Returns
    -------
    dict
        ``{"mu_a_plus", "mu_a_minus", "mu_b_plus", "mu_b_minus"}``, floats,
        dimensionless; ``inf`` in a self-locking direction.

    Raises
    ------
    asperity.InputError
        A texture of another kind or an unknown contact regime.

    See Also
    --------
    asperity.compute_reservoir : Any set of sliding directions.
    asperity.derive : Every direction, with a surface's principal direction found.
    asperity.compute_H : The per-face ratio the wedge's closed form is built on.

    Notes
    -----
    For the all-faces wedge these are SPEC.md section 2's closed forms, e.g.
    ``mu_a+ = (H(mu_alpha, alpha) tan beta + H(mu_beta, -beta) tan alpha) /
    (tan alpha + tan beta)`` and ``mu_b+ = mu_b- = (mu_alpha tan beta / cos alpha +
    mu_beta tan alpha / cos beta) / (tan alpha + tan beta)``.  Sliding exactly along
    the ridges in the windward regime is set-valued; the value returned there is that of
    the level faces' average.

    Examples
    --------
    SPEC.md's check values:

    >>> mu = asperity.compute_axis_coefficients(asperity.WedgeTexture(30.0, 10.0, 0.1, 0.2))
    >>> print(", ".join(f"{k} = {v:.6f}" for k, v in mu.items()))
    mu_a_plus = 0.185697, mu_a_minus = 0.193238, mu_b_plus = 0.182587, mu_b_minus = 0.182587
    >>> mu = asperity.compute_axis_coefficients(asperity.WedgeTexture(5.0, 5.0, 0.1, 0.1))
    >>> print(f"{mu['mu_a_plus']:.6f} {mu['mu_a_minus']:.6f}")
    0.100773 0.100773

    A face too steep to climb (``mu_alpha tan alpha >= 1``) self-locks:

    >>> locking = asperity.load_texture("surfaces/self-locking.toml")
    >>> asperity.compute_axis_coefficients(locking)["mu_a_plus"]
    inf
    """
    psi = np.array([0.0, np.pi, 0.5 * np.pi, 1.5 * np.pi])
    r = compute_reservoir(texture, psi, contact)
    t = r.tangential
    return {"mu_a_plus": float(t[0]), "mu_a_minus": float(t[1]),
            "mu_b_plus": float(t[2]), "mu_b_minus": float(t[3])}
