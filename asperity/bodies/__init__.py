"""Planar rigid bodies on a support (issue 20): footprints and their pressure
(:mod:`.footprint`), body files (:mod:`.body_file`), and the closed forms and reference ODEs
of a sliding and spinning disc or ring (:mod:`.closed_forms`).  The body solver is
:mod:`asperity.dynamics.body`; it takes a footprint's points and weights."""
