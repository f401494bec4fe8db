"""Wedge textures: the first stage, texture -> friction, for textures given by parameters.

* :mod:`.wedges` -- the periodic sawtooth and the Gaussian-height wedge texture, their faces
  and profiles, texture files (TOML);
* :mod:`.closed_form` -- H(x, y) and the wedge's mu_a+, mu_a-, mu_b (SPEC.md sections 1-2);
* :mod:`.springs`, :mod:`.spring_model` -- the spring-on-wedge simulation (kernels in
  :mod:`._spring_kernels` and :mod:`._tip_kernels`).

A texture's faces go to :mod:`asperity.friction` for the homogenisation.
"""
