"""Any surface -> facets: measured topographies and meshes for the friction homogenisation.

* :mod:`.readers` -- one module per format family behind one ordered registry
  (:data:`~asperity.surface.readers.READERS`): meshes, NumPy arrays, text matrices, x3p,
  instrument formats through SurfaceTopography; :mod:`.topography` -- what they return;
* :mod:`.detrend` -- form removal; :mod:`.friction_map` -- local friction per pixel/triangle;
* :mod:`.facets` -- height maps and meshes triangulated into facets (:func:`load_surface`);
* :mod:`.wedge_surfaces` -- wedge textures drawn as meshes and height maps (validation).

The facets go to :mod:`asperity.friction` for the homogenisation.
"""
