"""Textures and surfaces whose faces carry the normal force of an elastic contact.

:func:`elastic_textures` turns what ``derive`` takes into one weighted texture per pressure
of an :class:`~asperity.surface.contact_facets.ElasticContact`:

* a HeightMap: its facets, each weighing the contact force it carries
  (:func:`asperity.surface.contact_facets.elastic_facets`, boundary ``free`` by default);
* a wedge texture (periodic by construction, boundary ``periodic`` by default): its height
  profile over one period, uniform along the ridges, is pressed onto the half-space (a
  plane-strain solve on :func:`wedge_nodes` nodes a period) and each face weighs the force
  on it: the node pressures interpolated linearly between the nodes and integrated over
  the face's exact extent (:func:`segment_forces`); the faces and their law are
  unchanged (:class:`ElasticWedge`).  A flat gap between Gaussian wedges that touches
  becomes a level face ``gap`` (mu of its profile segment).

* a TriangleMesh: its upper envelope on a height grid is pressed and each triangle weighs
  the force of the grid nodes it holds (:func:`asperity.surface.contact_facets.elastic_facets`,
  :mod:`asperity.surface.mesh_grid`; free boundary, the default grid step).

A FacetSurface has lost its heights' grid: it is refused in one line.
"""
from __future__ import annotations

import numpy as np

from ..errors import InputError
from .reservoir import Faces

#: nodes a period of a wedge texture's plane-strain solve (a power of 2): at least this
#: many, WEDGE_NODES_PER_WEDGE a wedge of a Gaussian texture and WEDGE_CONTACT_NODES x the
#: mean slope / (p / E*) at the lightest pressure (the contact of a sharp crest spans about
#: (p / E*) / mean slope of the period: some 100 nodes), at most WEDGE_MAX_NODES
WEDGE_MIN_NODES = 4096
WEDGE_NODES_PER_WEDGE = 256
WEDGE_CONTACT_NODES = 64
WEDGE_MAX_NODES = 1 << 18


class ElasticWedge:
    """A wedge texture whose faces weigh the normal force of an elastic contact.

    texture : the WedgeTexture or GaussianWedgeTexture (its attributes are this object's)
    weight  : force on each face of ``texture.faces()`` (and on the flat gaps, a third
              face, when they touch), N per m of ridge
    elastic : the contact's figures (the keys of ``asperity contact --json``)
    """

    def __init__(self, texture, weight: np.ndarray, gap: tuple[float, float] | None,
                 elastic: dict):
        self._texture = texture
        self._weight = np.asarray(weight, dtype=float)
        self._gap = gap                      # (force, mu) of the flat gaps, or None
        self.elastic = elastic

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        return getattr(self._texture, name)

    @property
    def kind(self) -> str:
        return self._texture.kind

    def faces(self) -> Faces:
        f = self._texture.faces()
        g, mu, w, names = f.gradient, f.mu, self._weight, tuple(f.names)
        if self._gap is not None:
            g = np.vstack([g, [[0.0, 0.0]]])
            mu = np.append(mu, self._gap[1])
            w = np.append(w, self._gap[0])
            names = names + ("gap",)
        return Faces(gradient=g, mu=mu, weight=w, names=names)

    def to_dict(self) -> dict:
        return self._texture.to_dict()


def wedge_nodes(texture, prof, p_over_E: float) -> int:
    """Nodes a period of the plane-strain solve of ``texture``'s profile ``prof`` at the
    lightest pressure ``p_over_E`` (p / E*)."""
    n_wedges = int(getattr(texture, "n_wedges", 1))
    slope = float(np.abs(np.diff(prof.z)).sum() / prof.period)
    want = max(WEDGE_MIN_NODES, WEDGE_NODES_PER_WEDGE * n_wedges,
               WEDGE_CONTACT_NODES * slope / p_over_E)
    return int(min(WEDGE_MAX_NODES, 1 << int(np.ceil(np.log2(want)))))


def segment_forces(p: np.ndarray, dx: float, x0: np.ndarray, x1: np.ndarray) -> np.ndarray:
    """Integral over [x0, x1] (0 <= x0 <= x1 <= n dx) of the node values ``p`` (nodes
    i dx, periodic: node n is node 0) interpolated linearly between the nodes."""
    n = p.size
    q = np.append(p, p[0])
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (q[:-1] + q[1:]) * dx)])

    def F(x):
        s = np.clip(x / dx, 0.0, n)
        i = np.minimum(np.floor(s).astype(np.int64), n - 1)
        t = s - i
        return cum[i] + dx * (q[i] * t + 0.5 * (q[i + 1] - q[i]) * t * t)

    return F(np.asarray(x1, dtype=float)) - F(np.asarray(x0, dtype=float))


def wedge_heightmap(texture, p_over_E: float):
    """(HeightMap, profile, node spacing): ``texture``'s profile over one period on
    :func:`wedge_nodes` nodes (axis 0, across the ridges), uniform along the ridges (two
    columns: a periodic solve of it is the plane-strain solve of the profile)."""
    from ..surface.topography import HeightMap
    prof = texture.profile()
    n = wedge_nodes(texture, prof, p_over_E)
    dx = prof.period / n
    z = prof.height(np.arange(n) * dx)
    hm = HeightMap(np.repeat(z[:, None], 2, axis=1), dx, dx, source=f"{texture.kind} profile")
    return hm, prof, dx


def wedge_contact(texture, elastic, observe=None) -> list[ElasticWedge]:
    """``texture`` weighted by the contact force at each pressure of ``elastic``
    (``observe``: see :func:`asperity.surface.contact_facets.contact_solutions`)."""
    from ..surface.contact_facets import contact_solutions
    hm, prof, dx = wedge_heightmap(texture, min(elastic.pressures) / elastic.E_star)
    boundary = elastic.boundary_or("periodic")
    if boundary != "periodic":
        raise InputError("boundary of a wedge texture must be periodic (the texture repeats "
                         "by construction), got free")
    nfaces = texture.faces().gradient.shape[0]
    out = []
    for res in contact_solutions(hm, elastic, boundary, False, observe):
        force = segment_forces(res.pressure[:, 0], dx, prof.x[:-1], prof.x[1:])
        w = np.array([force[prof.face == k].sum() for k in range(nfaces)])
        flat = prof.face < 0
        gap = None
        if flat.any() and force[flat].sum() > 0:
            gap = (float(force[flat].sum()), float(prof.mu[flat][0]))
        if not (w > 0).any() and gap is None:
            raise InputError("no face of the texture carries load")
        out.append(ElasticWedge(texture, w, gap, res.to_dict()))
    return out


def elastic_textures(texture, elastic, observe=None) -> list:
    """One texture per pressure of ``elastic`` whose faces weigh the contact force (see
    the module's docstring); InputError for what has no height grid.  ``observe(result)``
    sees each pressure's ContactResult (a wedge's: its profile, 2 columns)."""
    from ..surface.contact_facets import check_elastic, elastic_facets
    from ..surface.topography import HeightMap, TriangleMesh
    elastic = check_elastic(elastic)
    if isinstance(texture, (HeightMap, TriangleMesh)):
        return list(elastic_facets(texture, elastic, observe=observe))
    if callable(getattr(texture, "profile", None)) and getattr(texture, "kind", "") in (
            "wedge", "gaussian-wedge"):
        return wedge_contact(texture, elastic, observe)
    what = "a surface's facets (they have lost the height grid: give the HeightMap, or " \
           "load_elastic(path, ...))" if getattr(texture, "kind", "") == "surface" else \
        f"{type(texture).__name__}"
    raise InputError(f"texture must be a height map, a mesh or a wedge texture for elastic "
                     f"contact, "
                     f"got {what}")
