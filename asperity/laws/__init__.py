"""Friction -> law: gauge functions fitted to directional friction, and their files.

* :mod:`.geometry` -- plane helpers and tolerances; :mod:`.sets` -- disc, truncated ellipse,
  star-shaped polygon; :mod:`.convex_set` -- D from its support function;
* :mod:`.walker_leine` -- the law (C, D); :mod:`.fitting` -- fits of the truncated ellipse and
  the star law to a derivation (:class:`~asperity.laws.fitting.GaugeLaw`);
* :mod:`.gauge_file`, :mod:`.gauge_schema` -- versioned JSON gauge files and their checks;
  :mod:`.family` -- law families over the nominal pressure (version 2) and the law at a
  pressure, :mod:`.family_report` -- their summary, text, plot and exports;
  :mod:`.export` -- CSV polar table and Abaqus block; :mod:`.plot` -- figures;
* :mod:`.planar` -- the laws as the solvers use them, with their proximal maps (kernels in
  :mod:`._set_kernels`, :mod:`._warm_kernels` and :mod:`._law_kernels`).
"""
