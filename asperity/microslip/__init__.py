"""Law -> consequences: cumulative microslip (ratcheting) of assemblies under load cycles.

* :mod:`.chains` -- slider chains (two-node, strip), :mod:`.closed_forms` beside them,
  :mod:`.loading` -- load cycles;
* :mod:`.quasi_static` -- exact incremental cycles and the long-life extrapolation,
  :mod:`.dynamic` -- the same chain by Moreau time-stepping (kernels in
  :mod:`._chain_kernels`, :mod:`._march_kernels`, :mod:`._dynamic_kernels`; :mod:`.pacing`
  runs them in pieces);
* :mod:`.limits` -- the physical ranges of every input, checked before any work;
* :mod:`.verdict` -- shakedown, alternating-slip, ratchet or slides-off with its numbers;
* :mod:`.assembly` -- assembly files, :mod:`.friction` -- mu+/mu- along the slip axis,
  :mod:`.risk` -- the risk analysis and risk map as a library API (``asperity risk`` and the
  report call it), :mod:`.risk_text` and :mod:`.plot` -- its text and figures.
"""
