"""Law -> motion: Moreau time-stepping of bodies sliding on a friction law (SPEC.md 4).

* :mod:`.moreau` -- bodies, the solver and ``slide`` (kernels in
  :mod:`._moreau_kernels`);
* :mod:`.force` -- the external load of a body (``asperity.Force``);
* :mod:`.references` -- closed forms and ODE reference paths beside it.
"""
