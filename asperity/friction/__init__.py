"""Directional friction: faces -> the reservoir p(psi) for every sliding direction.

The one room both :mod:`asperity.texture` and :mod:`asperity.surface` depend on:

* :mod:`.reservoir` -- :class:`Faces` (the input), :class:`Reservoir` (the result), the
  contact regimes and tolerances;
* :mod:`.faces` -- the closed-form homogenisation over plane faces (NumPy reference), and
  :mod:`.facet_reservoir` -- the same for millions of facets (numba kernels in
  :mod:`._facet_kernels`);
* :mod:`.diagnostics` -- self-locking, admissibility, associativity;
* :mod:`.derive` -- the computation behind ``asperity derive`` (principal direction,
  anisotropy, axis coefficients, JSON and text), :mod:`.sources` -- texture or surface file,
  :mod:`.plot` -- its figures.
"""
