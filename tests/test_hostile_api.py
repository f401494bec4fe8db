"""Every public callable of ``asperity.__all__`` fed hostile arguments (issue 18, section 9).

The table :func:`api_table` holds, per public function or class, one valid call and the
kind of each of its arguments (:mod:`api_walk`); the walker replaces one argument at a
time by every bad value its kind generates (wrong types, wrong shapes, NaN, +-inf, 10**400,
out-of-range numbers, missing or malformed files) and asserts that each call ends in a
one-line InputError naming the argument, with no warning on the way -- never a bare
NumPy, IndexError or TypeError.  A function added to ``__all__`` fails
:func:`test_every_public_callable_has_a_row` until it has its row; an argument added to a
signature fails :func:`test_rows_name_every_argument` until it has its kind."""
from __future__ import annotations

import collections
import inspect
import math
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from api_walk import (BIG_INT as BIG, NAN, Kind, address, array, array_variants, callback, choice, flag, infile,
                      instance, judge, judge_variant, nan_first, number, number_variants, outcome, outfile, outfolder, text,
                      whole)
from hostile import SURF

import asperity as A
from asperity.dynamics.moreau import Force
from asperity.errors import InputError

#: public names that are not callables of the API (the version, the error classes)
NOT_CALLABLES = {"__version__", "AsperityError", "InputError"}
TEX = A.WedgeTexture(30, 10, 0.1, 0.2)
Z = 1e-6 * np.random.default_rng(7).normal(size=(12, 10))


class Row:
    """One public callable: its name, a valid call (``args``), the kind of each argument,
    and the words a message may use for an argument (default: its own name)."""

    def __init__(self, name, fn, args: dict, kinds: dict, words: dict | None = None):
        self.name, self.fn, self.args, self.kinds = name, fn, args, kinds
        self.words = words or {}

    def calls(self):
        """(argument, class, label, call) of every hostile call of this row."""
        for arg, kind in self.kinds.items():
            for cls, label, value in kind.bad():
                yield arg, kind, cls, label, value, self._call(arg, value)

    def _call(self, arg, value):
        kw = dict(self.args, **{arg: value})
        return lambda: self.fn(**kw)


def _files(folder: Path) -> dict:
    np.save(folder / "z.npy", Z)
    np.save(folder / "w.npy", 1e-6 * np.random.default_rng(3).normal(size=(20, 18)))
    gl = A.fit_derivation(A.derive(TEX, n_directions=72), "star")
    A.write_gauge(folder / "g.json", gl)
    chain = A.two_node_chain(1e6, 0.1, 1.2e-5, 5e5, 100.0, 0.2, 0.1)
    loading = A.Loading([0.0, 125.0, 0.0], [0.0, 0.0, 0.0])
    asm = A.load_assembly(SURF / "two-node-spec.toml")
    members = tuple(replace(gl, source={**gl.source, "elastic_contact": {
        "area_fraction": 0.1, "pressure_Pa": p, "max_pressure_Pa": 1e8, "E_star_Pa": 1e9,
        "boundary": "periodic", "hardness_Pa": None}}) for p in (1e6, 1e7))
    import trimesh
    trimesh.creation.box(extents=(40, 20, 10)).export(folder / "box.stl")
    (folder / "pressure.csv").write_text("x_m,y_m,p_Pa\n0,0,1e5\n0.001,0,2e5\n0,0.001,1e5\n")
    contact = A.solve_contact(-np.hypot(*np.meshgrid(np.arange(16), np.arange(16))) * 1e-6,
                              1e-6, 1e9, 1e5, boundary="free")
    return dict(contact=contact, d=A.derive(TEX, n_directions=72), npy=folder / "z.npy", gauge=folder / "g.json", gl=gl, chain=chain, members=members,
                loading=loading, asm=asm, friction=A.assembly_friction(asm),
                law=A.ellipse_law(0.2, 0.1), fs=A.load_surface(folder / "z.npy", unit="m",
                                                               pixel_size=1e-6))


def hand_made(res) -> list:
    """ContactResults made by hand around ``res``'s pressure (issue 25, item 3): NumPy's
    hostile arrays in the fields a function reads, each to refuse in one line."""
    p = res.pressure
    bad = [("type", "complex pressure", p + 1j), ("type", "boolean pressure", p > 0),
           ("shape", "1-d pressure", p[0]), ("inf", "infinite pressure", np.where(p > 0, np.inf, p)),
           ("range", "negative pressure", -p), ("huge", "4e10 pressures", np.broadcast_to(1.0, (200_000, 200_000))),
           ("type", "text pressure", np.full(p.shape, "a", dtype=object))]
    out = [(cls, label, replace(res, pressure=v)) for cls, label, v in bad]
    for label, px in (("pixel_size NaN", (NAN, 1e-6)), ("pixel_size negative", (-1e-6, 1e-6)),
                      ("pixel_size of 3", (1e-6, 1e-6, 1e-6)), ("pixel_size text", ("a", 1.0))):
        out.append(("range", label, replace(res, pixel_size=px)))
    return out


def api_table(folder: Path) -> list[Row]:
    f = _files(folder)
    npy, gauge = infile(folder, ".npy"), infile(folder, ".json")
    angle_deg = number(1e-6, 90.0, hi_open=True)
    mu = number(0.0, 100.0)
    pos = number(0.0, None, lo_open=True)
    psi = array(-1e3, 1e3, extra=[("NaN", "NaN", NAN), ("inf", "+inf", math.inf),  # or a number
                                  ("overflow", "10**400", BIG), ("range", "huge", 1e300)])
    contact = choice()
    small = A.SpringModel(n_springs=8, steps_per_period=2000)
    elastic = A.SpringModel(k_f=1e6, n_springs=8, steps_per_period=2000)
    scan = dict(unit=choice(none=True), pixel_size=number(1e-12, 1.0, none=True,
                                                          skip=("1-d",)),
                height_scale=number(1e-6, 1e6), detrend=choice(), mu=number(0.0, 100.0, none=True),
                friction_map=array(0.0, 100.0, ndim=2, none=True),
                rest_level=number(-1e3, 1e3, none=True), bearing_fraction=number(
                    0.0, 1.0, lo_open=True, none=True), despike=number(2.0, 1e6, none=True),
                despike_window=whole(3, 15, none=True), max_slope=number(0.0, 90.0, lo_open=True,
                                                              hi_open=True, none=True))
    scan_args = dict(path=f["npy"], unit="m", pixel_size=1e-6, height_scale=1.0,
                     detrend="slope", mu=None, friction_map=None, rest_level=None,
                     bearing_fraction=None, despike=3.0, despike_window=5, max_slope=None)
    law_mu = number(1e-6, 100.0)
    tol_default = A.assess.__kwdefaults__["tol"]
    nodes = array(0, 1, none=True, skip=("empty",))     # no node recorded: allowed
    alpha_T = number(-1e-3, 1e-3, extra=[("range", "zero", 0.0), ("range", "subnormal", 5e-324),
                                         ("range", "-1e-12", -1e-12)])
    def axis(p):
        return Kind("pair", extra=[("shape", "one item", (p,)),
                                   ("choice", "unknown parameter", ("no-such", [20.0, 30.0])),
                                   ("shape", "one value", (p, [20.0])),
                                   ("type", "values text", (p, "abc")),
                                   ("NaN", "NaN value", (p, [NAN, 20.0])),
                                   ("inf", "inf value", (p, [20.0, math.inf])),
                                   ("range", "out-of-range value", (p, [20.0, 95.0]))])
    mu_slider = number(1e-6, 1e4, inf=True)
    length = number(1e-9, 1e3)
    points = whole(1, 1_000_000, none=True)
    cop = array(-1e3, 1e3, extra=[("shape", "3 values", [0.0, 0.0, 0.0]),
                                  ("range", "off the core", [0.9, 0.0])])
    eps = array(0.0, None, ndim=None, inf=True, extra=[
        ("NaN", "NaN", NAN), ("range", "negative", -1.0), ("overflow", "10**400", BIG)])
    shape_kw = dict(contact_points=points, profile=choice(), centre_of_pressure=cop)
    shape_args = dict(contact_points=16, profile="linear", centre_of_pressure=(0.0, 0.0))
    shape_words = {"profile": ("pressure_profile",)}
    disc_fp = A.disc_footprint(1.0, contact_points=16)
    force_part = array(-1e12, 1e12, extra=[("shape", "4 values", [1.0, 2.0, 3.0, 4.0])])
    rows = [
        Row("Footprint", A.Footprint,
            dict(kind="disc", points=disc_fp.points, weights=disc_fp.weights,
                 outline=disc_fp.outline, area=1.0, radius=1.0, profile="uniform",
                 inertia_per_mass=0.5, info={}),
            dict(kind=choice(), points=array(-1e3, 1e3, ndim=2),
                 weights=array(0.0, 1.0, lo_open=True, extra=[
                     ("range", "not summing to 1", [0.5] * 16)]),
                 outline=array(ndim=2), area=number(0.0, None),
                 radius=number(1e-9, 1e3, none=True), profile=choice(),
                 inertia_per_mass=number(0.0, None), info=instance(skip=("dict",)))),
        Row("disc_footprint", A.disc_footprint, dict(radius=1.0, **shape_args),
            dict(radius=length, **shape_kw), shape_words),
        Row("ring_footprint", A.ring_footprint, dict(radius=0.1, contact_points=16),
            dict(radius=length, contact_points=whole(3, 1_000_000, none=True))),
        Row("rectangle_footprint", A.rectangle_footprint, dict(a=0.04, b=0.02, **shape_args),
            dict(a=length, b=length, **shape_kw), shape_words),
        Row("polygon_footprint", A.polygon_footprint,
            dict(vertices=[[0, 0], [1, 0], [1, 1], [0, 1]], **shape_args),
            dict(vertices=array(-1e3, 1e3, ndim=2, extra=[
                ("shape", "two points", [[0, 0], [1, 0]]),
                ("range", "zero area", [[0, 0], [1, 1], [2, 2]]),
                ("range", "crossing itself", [[0, 0], [3, 0], [0, 1], [1, 1]])]),
                 **shape_kw), shape_words),
        Row("mesh_patch", A.mesh_patch,
            dict(mesh=folder / "box.stl", unit="mm", tolerance=None, **shape_args),
            dict(mesh=infile(folder, ".stl"), unit=choice(none=True),
                 tolerance=number(0.0, 1e3, none=True), **shape_kw), shape_words),
        Row("pressure_footprint", A.pressure_footprint,
            dict(points=[[0.0, 0.0], [0.001, 0.0]], pressures=[1e5, 2e5], shape=None,
                 cell_areas=None, contact_points=None),
            dict(points=array(-1e3, 1e3, ndim=2), pressures=array(0.0, None, extra=[
                ("range", "all zero", [0.0, 0.0])]), shape=instance(none=True),
                 cell_areas=array(0.0, None, lo_open=True, none=True), contact_points=points)),
        Row("contact_footprint", A.contact_footprint,
            dict(result=f["contact"], contact_points=None),
            dict(result=instance(extra=hand_made(f["contact"])), contact_points=points)),
        Row("read_pressure", A.read_pressure, dict(path=folder / "pressure.csv"),
            dict(path=infile(folder, ".csv")), {"path": ("pressure file",)}),
        Row("read_body", A.read_body, dict(path=SURF / "body-plate.toml"),
            dict(path=infile(folder, ".toml")), {"path": ("body file",)}),
        Row("disc_f_m", A.disc_f_m, dict(eps=0.5), dict(eps=eps)),
        Row("ring_f_m", A.ring_f_m, dict(eps=0.5), dict(eps=eps)),
        Row("spin_drift_force", A.spin_drift_force, dict(law=f["law"], n=64),
            dict(law=instance(), n=whole(8, 10**7))),
        Row("disc_reference", A.disc_reference,
            dict(v0=1.0, omega0=10.0, mu=0.3, g=9.81, R=0.05, kind="disc", rtol=1e-8),
            dict(v0=number(0.0, 1e4), omega0=number(0.0, 1e6), mu=number(1e-6, 100.0),
                 g=number(1e-6, 1e4), R=number(1e-9, 1e3), kind=choice(),
                 rtol=number(1e-14, 1e-3))),
        Row("slide_body", A.slide_body,
            dict(law=f["law"], body=A.disc_footprint(0.05, contact_points=16), u0=0.2,
                 angle_deg=30.0, omega0=5.0, mass=None, inertia=None, g=9.81, dt=1e-3,
                 t_end=None, force=None, texture_angle_deg=0.0, settings=None),
            dict(law=instance(), body=instance(extra=[
                ("range", "a point", A.Footprint("point", np.zeros((1, 2)), np.ones(1),
                                                 np.zeros((1, 2)), 0.0))]),
                 u0=number(0.0, 1e4), angle_deg=number(-360.0, 360.0),
                 omega0=number(-1e6, 1e6), mass=number(1e-9, 1e9, none=True),
                 inertia=number(1e-15, 1e12, none=True), g=number(1e-6, 1e4),
                 dt=number(1e-9, 1.0), t_end=number(0.0, 1e9, none=True),
                 force=instance(none=True, extra=[
                     ("range", "a load without t_end", Force(constant=(1.0, 0.0, 0.0)))]),
                 texture_angle_deg=number(-360.0, 360.0), settings=instance(none=True))),
        Row("crawl", A.crawl,
            dict(law=None, mu_f=0.1, mu_b=0.15, mu_t=0.2, rule="componentwise", gait=None,
                 amplitude=None, waves=None, length=None, period=None, points=8,
                 periods=None, quasi_static=True, g=9.81, steps_per_period=16,
                 texture_on="body", texture_angle_deg=0.0, weights=None, mass=1.0,
                 settings=A.CrawlSettings()),
            dict(law=instance(none=True), mu_f=number(1e-6, 100.0, none=True),
                 mu_b=number(1e-6, 100.0, none=True), mu_t=number(1e-6, 100.0, none=True),
                 rule=choice(), gait=instance(none=True), amplitude=number(0.0, 100.0, none=True),
                 waves=number(0.0, 20.0, lo_open=True, none=True),
                 length=number(0.0, 1e6, lo_open=True, none=True),
                 period=number(0.0, 1e6, lo_open=True, none=True), points=whole(3, 100_000),
                 periods=whole(1, 100_000, none=True), quasi_static=flag(),
                 g=number(1e-6, 1e4), steps_per_period=whole(8, 10_000_000),
                 texture_on=choice(), texture_angle_deg=number(-360.0, 360.0),
                 weights=array(0.0, None, lo_open=True, none=True), mass=number(1e-9, 1e9),
                 settings=instance())),
        Row("coefficient_law", A.coefficient_law,
            dict(mu_f=0.1, mu_b=0.15, mu_t=0.2, rule="componentwise"),
            dict(mu_f=number(1e-6, 100.0), mu_b=number(1e-6, 100.0), mu_t=number(1e-6, 100.0),
                 rule=choice())),
        Row("CrawlSettings", A.CrawlSettings, dict(tol=1e-12, max_iterations=200),
            dict(tol=number(1e-15, 1e-3), max_iterations=whole(1, 1_000_000))),
        Row("Force", A.Force,
            dict(constant=(1.0, 0.0, 0.0), amplitude=(0.0, 0.5, 0.01), period=1.0,
                 waveform="sine"),
            dict(constant=force_part, amplitude=force_part, period=number(1e-9, 1e9),
                 waveform=choice())),
        Row("WedgeTexture", A.WedgeTexture,
            dict(alpha_deg=30, beta_deg=10, mu_alpha=0.1, mu_beta=0.2, height=1e-6),
            dict(alpha_deg=angle_deg, beta_deg=angle_deg, mu_alpha=mu, mu_beta=mu,
                 height=number(1e-10, 100.0)), {"alpha_deg": ("alpha",), "beta_deg": ("beta",)}),
        Row("GaussianWedgeTexture", A.GaussianWedgeTexture,
            dict(alpha_deg=30, beta_deg=10, mu_alpha=0.1, mu_beta=0.2, height_mean=1e-6,
                 height_std=2e-7, n_wedges=20, seed=0, mean_gap=None),
            dict(alpha_deg=angle_deg, beta_deg=angle_deg, mu_alpha=mu, mu_beta=mu,
                 height_mean=number(1e-10, 100.0), height_std=number(0.0, 3e-6),
                 n_wedges=whole(1, 1_000_000), seed=whole(0, 2**32 - 1),
                 mean_gap=number(0.0, 100.0, none=True)),
            {"alpha_deg": ("alpha",), "beta_deg": ("beta",)}),
        Row("load_texture", A.load_texture, dict(path=SURF / "wedge-asymmetric.toml"),
            dict(path=infile(folder, ".toml")), {"path": ("texture file",)}),
        Row("compute_H", A.compute_H, dict(x=0.1, y=0.2),
            dict(x=array(0.0, 100.0, ndim=None), y=array(-math.pi / 2, math.pi / 2,
                                                       lo_open=True, hi_open=True, ndim=None)),
            {"x": ("x (local friction)",), "y": ("y (slope angle)",)}),
        Row("compute_reservoir", A.compute_reservoir,
            dict(texture=TEX, psi=[0.0, 1.0], contact="all-faces", progress=None),
            dict(texture=instance(), psi=psi, contact=contact, progress=callback())),
        Row("compute_axis_coefficients", A.compute_axis_coefficients,
            dict(texture=TEX, contact="all-faces"), dict(texture=instance(), contact=contact)),
        Row("SpringModel", A.SpringModel,
            dict(k_n=1e3, k_f=math.inf, density=1e10, preload=0.0, n_springs=8,
                 steps_per_period=2000),
            dict(k_n=number(1e-6, 1e12), k_f=number(1e-6, 1e12, inf=True),
                 density=number(1.0, 1e20), preload=number(-1e6, 1e6),
                 n_springs=whole(1, 1_000_000), steps_per_period=whole(2, 10**8))),
        Row("simulate_sliding", A.simulate_sliding,
            dict(texture=TEX, psi=0.0, model=small, contact="all-faces"),
            dict(texture=instance(), psi=number(-1e3, 1e3), model=instance(), contact=contact)),
        Row("simulate_reservoir", A.simulate_reservoir,
            dict(texture=TEX, psi=[0.0], model=small, contact="all-faces"),
            dict(texture=instance(), psi=psi, model=instance(), contact=contact)),
        Row("simulate_loading_curve", A.simulate_loading_curve,
            dict(texture=TEX, psi=0.0, model=elastic, distance=None, n_steps=200,
                 contact="all-faces"),
            dict(texture=instance(), psi=number(-1e3, 1e3), model=instance(),
                 distance=number(0.0, 1.0, lo_open=True, none=True),
                 n_steps=whole(2, 10**8), contact=contact)),
        Row("load_surface", A.load_surface, scan_args, dict(path=npy, **scan),
            {"path": ("surface file",), "friction_map": ("friction map",)}),
        Row("FacetSurface", A.FacetSurface,
            dict(gx=f["fs"].gx, gy=f["fs"].gy, mu=0.1, weight=f["fs"].weight, info={},
                 preview=None, extent=None, quality=None, elastic=None),
            dict(gx=array(), gy=array(), mu=number(0.0, 100.0), weight=array(0.0),
                 info=instance(skip=("dict",)), preview=array(ndim=2, none=True,
                                                              skip=("NaN inside",)),
                 extent=array(0.0, None, lo_open=True, none=True),
                 quality=instance(none=True, skip=("dict",)),
                 elastic=instance(none=True, skip=("dict",)))),
        Row("read_surface", A.read_surface,
            dict(path=f["npy"], unit="m", pixel_size=1e-6, height_scale=1.0, point_bytes=0.0),
            dict(path=npy, unit=scan["unit"], pixel_size=scan["pixel_size"],
                 height_scale=scan["height_scale"], point_bytes=number(0.0, 1e6)),
            {"path": ("surface file",)}),
        Row("compute_facet_reservoir", A.compute_facet_reservoir,
            dict(gx=f["fs"].gx, gy=f["fs"].gy, mu=0.1, weight=f["fs"].weight, psi=[0.0, 1.0],
                 contact="all-faces", progress=None, batch=None),
            dict(gx=array(), gy=array(), mu=number(0.0, 100.0), weight=array(0.0),
                 psi=psi, contact=contact, progress=callback(),
                 batch=whole(1, None, none=True))),
        Row("derive", A.derive,
            dict(texture=TEX, contact="all-faces", method="closed-form", n_directions=8,
                 model=None, progress=None, elastic=None),
            dict(texture=instance(), contact=contact, method=choice(),
                 n_directions=whole(8, 100_000), model=instance(none=True),
                 progress=callback(), elastic=instance(none=True)),
            {"n_directions": ("directions",)}),
        Row("ElasticContact", A.ElasticContact,
            dict(E_star=1e9, pressure=1e6, boundary=None, hardness=None, tol=1e-8,
                 max_iterations=None),
            dict(E_star=pos, pressure=array(0.0, None, lo_open=True, extra=[
                ("NaN", "NaN", NAN), ("inf", "+inf", math.inf), ("overflow", "10**400", BIG),
                ("range", "zero", 0.0), ("range", "negative", -1.0),
                ("shape", "101 values", [1e6] * 101)]),
                 boundary=choice(none=True), hardness=number(1e6, None, lo_open=True, none=True),
                 tol=number(1e-15, 0.1), max_iterations=whole(1, 10**7, none=True))),
        Row("effective_modulus", A.effective_modulus,
            dict(E1=210e9, nu1=0.3, E2=70e9, nu2=0.33),
            dict(E1=pos, nu1=number(-1.0, 0.5, lo_open=True),
                 E2=number(0.0, None, lo_open=True, none=True),
                 nu2=number(-1.0, 0.5, lo_open=True, none=True))),
        Row("solve_contact", A.solve_contact,
            dict(heights=Z, pixel_size=1e-6, E_star=1e9, pressure=1e6, boundary="periodic",
                 hardness=None, tol=1e-8, max_iterations=None, initial=None, progress=None,
                 workers=None),
            dict(heights=array(ndim=2), pixel_size=pos, E_star=number(1.0, 1e13), pressure=pos,
                 boundary=choice(), hardness=number(1e6, None, lo_open=True, none=True),
                 tol=number(1e-15, 0.1), max_iterations=whole(1, 10**7, none=True),
                 initial=array(ndim=2, none=True), progress=callback(),
                 workers=whole(1, 4096, none=True))),
        Row("solve_load_curve", A.solve_load_curve,
            dict(heights=Z, pixel_size=1e-6, E_star=1e11, pressures=[1e8, 2e8],
                 boundary="free", hardness=None, tol=1e-8, max_iterations=None, progress=None,
                 workers=None),
            dict(heights=array(ndim=2, skip=("NaN inside",)),
                 pixel_size=number(0.0, None, lo_open=True, skip=("1-d", "huge")),
                 E_star=number(1.0, 1e13), pressures=array(0.0, None, lo_open=True),
                 boundary=choice(), hardness=number(2e8, None, lo_open=True, none=True),
                 tol=number(1e-15, 0.1), max_iterations=whole(1, 10**7, none=True),
                 progress=callback(), workers=whole(1, 4096, none=True)),
            {"pressures": ("pressure / E_star",), "pixel_size": ("pixel_size dx",)}),
        Row("load_elastic", A.load_elastic,
            dict({k: v for k, v in scan_args.items() if "_level" not in k
                  and k != "bearing_fraction"}, elastic=A.ElasticContact(1e9, 1e6),
                 observe=None, grid_step=None),
            dict(path=npy, elastic=instance(), observe=callback(),
                 grid_step=number(0.0, None, lo_open=True, none=True),
                 **{k: v for k, v in scan.items() if k not in ("rest_level",
                                                               "bearing_fraction")}),
            {"path": ("surface file",), "friction_map": ("friction map",)}),
        Row("derive_family", A.derive_family,
            dict(texture=TEX, elastic=A.ElasticContact(1e9, [1e6, 1e7]), contact="all-faces",
                 n_directions=8, progress=None),
            dict(texture=instance(), elastic=instance(), contact=contact,
                 n_directions=whole(8, 100_000), progress=callback()),
            {"n_directions": ("directions",)}),
        Row("derive_scan", A.derive_scan,
            dict(scan_args, contact="all-faces", n_directions=8, tile_lines=None, client=None,
                 other_contact=None, source=None),
            dict(path=npy, **scan, contact=contact, n_directions=whole(8, 100_000),
                 tile_lines=whole(1, None, none=True), client=instance(none=True),
                 other_contact=choice(none=True), source=instance(none=True)),
            {"path": ("surface file",), "n_directions": ("directions",),
             "friction_map": ("friction map",)}),
        Row("derive_windows", A.derive_windows,
            dict({k: v for k, v in scan_args.items() if "_level" not in k
                  and k != "bearing_fraction"}, path=folder / "w.npy",
                 elastic=A.ElasticContact(1e9, 1e6), window=16, windows=2, placement="grid",
                 seed=0, contact="all-faces", n_directions=8, client=None, source=None),
            dict(path=npy, elastic=instance(), window=whole(16, 18), windows=whole(1, 10_000),
                 placement=choice(), seed=whole(0, 2 ** 63 - 1), contact=contact,
                 n_directions=whole(8, 100_000), client=instance(none=True),
                 source=instance(none=True),
                 **{k: v for k, v in scan.items() if k not in ("rest_level",
                                                               "bearing_fraction")}),
            {"path": ("surface file",), "friction_map": ("friction map",),
             "n_directions": ("directions",), "placement": ("window_placement",),
             "seed": ("window_seed",)}),
        Row("fit_derivation", A.fit_derivation, dict(d=f["d"], kind="star", holdout=True),
            dict(d=instance(), kind=choice(), holdout=flag()), {"d": ("derivation",)}),
        Row("WalkerLeineLaw", A.WalkerLeineLaw, dict(C=f["gl"].law.C, D=f["gl"].law.D),
            dict(C=instance(), D=instance())),
        Row("TruncatedEllipse", A.TruncatedEllipse,
            dict(mu_a_plus=0.2, mu_a_minus=0.3, mu_b_plus=0.1, mu_b_minus=0.15, theta=0.0),
            dict(mu_a_plus=law_mu, mu_a_minus=law_mu, mu_b_plus=law_mu, mu_b_minus=law_mu,
                 theta=number(-4 * math.pi, 4 * math.pi))),
        Row("read_gauge", A.read_gauge, dict(path=f["gauge"]), dict(path=gauge),
            {"path": ("gauge file",)}),
        Row("GaugeFamily", A.GaugeFamily, dict(pressures=(1e6, 1e7), members=f["members"]),
            dict(pressures=array(0.0, None, lo_open=True, extra=[
                ("NaN", "NaN", NAN), ("inf", "+inf", math.inf), ("overflow", "10**400", BIG),
                ("range", "zero", 0.0), ("range", "decreasing", [1e7, 1e6]),
                ("shape", "one value", [1e6])]),
                 members=instance()), {"pressures": ("pressure",), "members": ("member",)}),
        Row("write_gauge", A.write_gauge, dict(path=folder / "out.json", gl=f["gl"]),
            dict(path=outfile(folder), gl=instance()), {"gl": ("gauge law",)}),
        Row("PlanarLaw", A.PlanarLaw, dict(name="star", law=f["gl"].law, description="d"),
            dict(name=choice(), law=instance(), description=text())),
        Row("coulomb_law", A.coulomb_law, dict(mu=0.2), dict(mu=law_mu)),
        Row("ellipse_law", A.ellipse_law, dict(mu1=0.2, mu2=0.1), dict(mu1=law_mu, mu2=law_mu)),
        Row("truncated_ellipse_law", A.truncated_ellipse_law,
            dict(mu_a_plus=0.2, mu_a_minus=0.3, mu_b_plus=0.1, mu_b_minus=0.15, theta=0.0),
            dict(mu_a_plus=law_mu, mu_a_minus=law_mu, mu_b_plus=law_mu, mu_b_minus=law_mu,
                 theta=number(-4 * math.pi, 4 * math.pi))),
        Row("collinear_law", A.collinear_law, dict(C=None, mu1=0.2, mu2=0.1),
            dict(C=instance(none=True), mu1=law_mu, mu2=law_mu)),
        Row("componentwise_law", A.componentwise_law, dict(mu_f=0.2, mu_b=0.3, mu_t=0.4),
            dict(mu_f=law_mu, mu_b=law_mu, mu_t=law_mu)),
        Row("star_law", A.star_law, dict(mu1=0.2, mu2=0.1, directions=360),
            dict(mu1=law_mu, mu2=law_mu, directions=whole(8, 100_000))),
        Row("windward_star_law", A.windward_star_law,
            dict(alpha_deg=30.0, beta_deg=30.0, mu_alpha=0.3, mu_beta=0.3, directions=360),
            dict(alpha_deg=angle_deg, beta_deg=angle_deg, mu_alpha=mu, mu_beta=mu,
                 directions=whole(8, 100_000)), {"alpha_deg": ("alpha",), "beta_deg": ("beta",)}),
        Row("law_from_gauge", A.law_from_gauge, dict(gauge=f["gauge"], kind=None),
            dict(gauge=infile(folder, ".json"), kind=choice(none=True)),
            {"gauge": ("gauge file",)}),
        Row("slide", A.slide,
            dict(law=f["law"], u0=1.0, angle_deg=30.0, mass=1.0, g=9.81, dt=1e-3, t_end=None,
                 record_every=1, settings=A.slide.__kwdefaults__["settings"]),
            dict(law=instance(), u0=number(0.0, 1e4), angle_deg=number(-360.0, 360.0),
                 mass=number(1e-9, 1e9), g=number(1e-6, 1e4), dt=number(1e-9, 1.0),
                 t_end=number(0.0, 1e9, none=True), record_every=whole(1, None),
                 settings=instance()), {"angle_deg": ("angle",)}),
        Row("simulate_body", A.simulate_body,
            dict(points=[[0.01, 0.0], [-0.01, 0.0], [0.0, 0.01], [0.0, -0.01]],
                 weights=[0.25, 0.25, 0.25, 0.25], law=f["law"], mass=1.0, inertia=1e-4,
                 u0=[0.2, 0.0, 1.0], q0=[0.0, 0.0, 0.0], dt=1e-3, t_end=None, force=None,
                 g=9.81, texture_angle_deg=0.0,
                 settings=A.simulate_body.__kwdefaults__["settings"], record_every=1,
                 until_rest=False),
            dict(points=array(-1e3, 1e3, ndim=2), weights=array(0.0, 1.0, lo_open=True),
                 law=instance(), mass=number(1e-9, 1e9), inertia=number(1e-15, 1e12),
                 u0=array(-1e4, 1e4, extra=[("shape", "2 values", [0.1, 0.2])]),
                 q0=array(-1e9, 1e9, extra=[("shape", "2 values", [0.1, 0.2])]),
                 dt=number(1e-9, 1.0), t_end=number(0.0, 1e9, none=True),
                 force=instance(none=True), g=number(1e-6, 1e4),
                 texture_angle_deg=number(-360.0, 360.0), settings=instance(),
                 record_every=whole(1, None), until_rest=flag())),
        Row("ratchet_drift_square", A.ratchet_drift_square,
            dict(F0=1.5, mass=1.0, period=1.0, mu_plus=0.2, mu_minus=0.1, g=9.81),
            dict(F0=number(0.0, 1e12), mass=number(1e-9, 1e9), period=number(1e-9, 1e9),
                 mu_plus=number(1e-6, 100.0), mu_minus=number(1e-6, 100.0),
                 g=number(1e-6, 1e4))),
        Row("deflection_deg", A.deflection_deg, dict(u0_angle_deg=30.0, rest=[1.0, 0.5]),
            dict(u0_angle_deg=number(-3600.0, 3600.0), rest=array(skip=("2-d",),
                 extra=[("shape", "3 values", [1.0, 2.0, 3.0])]))),
        Row("simulate_microslip", A.simulate_microslip,
            dict(chain=f["chain"], loading=f["loading"], cycles=5, record_nodes=None,
                 until_stable=True, min_cycles=2, tol=tol_default),
            dict(chain=instance(), loading=instance(), cycles=whole(1, 10**8),
                 record_nodes=nodes, until_stable=flag(),
                 min_cycles=whole(1, 10**8), tol=instance())),
        Row("long_life", A.long_life,
            dict(chain=f["chain"], loading=f["loading"], cycles=1e6, max_marched=50,
                 record_nodes=None, tol=tol_default),
            dict(chain=instance(), loading=instance(), cycles=number(1.0, 1e15),
                 max_marched=whole(2, 10**6), record_nodes=nodes,
                 tol=instance())),
        Row("assess", A.assess,
            dict(chain=f["chain"], loading=f["loading"], cycles=1e6, tolerance=None,
                 dT_c_closed_form=None, max_marched=50, tol=tol_default),
            dict(chain=instance(), loading=instance(), cycles=number(1.0, 1e15),
                 tolerance=number(1e-9, 1e3, none=True),
                 dT_c_closed_form=number(0.0, None, lo_open=True, none=True, inf=True),
                 max_marched=whole(2, 10**6), tol=instance())),
        Row("two_node_chain", A.two_node_chain,
            dict(k=1e6, l0=0.1, alpha_T=1.2e-5, k_t=5e5, N=100.0, mu_plus=0.2, mu_minus=0.1),
            dict(k=number(1e-3, 1e15), l0=number(1e-6, 1e3), alpha_T=alpha_T,
                 k_t=number(1e-3, 1e15), N=number(1e-6, 1e9), mu_plus=mu_slider,
                 mu_minus=mu_slider)),
        Row("strip_chain", A.strip_chain,
            dict(h=1e-3, E=2e11, p=1e6, l=0.05, k_t=1e12, alpha_T=1.2e-5, n=11, mu_plus=0.2,
                 mu_minus=0.1),
            dict(h=number(1e-7, 10.0), E=number(1e4, 1e13), p=number(1e-3, 1e10),
                 l=number(1e-6, 1e3), k_t=number(1e3, 1e20), alpha_T=alpha_T,
                 n=whole(2, 10**6), mu_plus=mu_slider, mu_minus=mu_slider)),
        Row("Loading", A.Loading, dict(dT=[0.0, 125.0, 0.0], F=[0.0, 0.0, 0.0], substeps=1),
            dict(dT=array(-5000.0, 5000.0), F=array(-1e12, 1e12, skip=("1-d",)),
                 substeps=whole(1, 100_000)), {"dT": ("history",), "F": ("force_history",)}),
        Row("load_assembly", A.load_assembly, dict(path=SURF / "two-node-spec.toml"),
            dict(path=infile(folder, ".toml")), {"path": ("assembly file",)}),
        Row("assembly_friction", A.assembly_friction,
            dict(asm=f["asm"], texture=None, texture_name="", contact=None,
                 slip_axis_deg=None, textured=None),
            dict(asm=instance(), texture=instance(none=True), texture_name=text(),
                 contact=choice(none=True), slip_axis_deg=number(-3600.0, 3600.0, none=True),
                 textured=choice(none=True))),
        Row("assess_assembly", A.assess_assembly,
            dict(asm=f["asm"], friction=f["friction"], cycles=None, tolerance=None,
                 max_marched=50, dynamic_steps=None),
            dict(asm=instance(), friction=instance(), cycles=number(1.0, 1e15, none=True),
                 tolerance=number(1e-9, 1e3, none=True), max_marched=whole(2, 10**6),
                 dynamic_steps=whole(100, 10**7, none=True))),
        Row("risk_map", A.risk_map,
            dict(asm=f["asm"], x=("alpha", [20.0, 30.0]), y=("beta", [10.0, 20.0]),
                 texture=TEX, contact=None, slip_axis_deg=None, textured=None, cycles=None,
                 max_marched=50, workers=0, scheduler=None, folder=None),
            dict(asm=instance(), x=axis("alpha"), y=axis("beta"), texture=instance(none=True),
                 contact=choice(none=True), slip_axis_deg=number(-3600.0, 3600.0, none=True),
                 textured=choice(none=True), cycles=number(1.0, 1e15, none=True),
                 max_marched=whole(2, 10**6), workers=whole(0, 4096, none=True),
                 scheduler=address(), folder=outfolder(folder)),
            {"x": ("map parameter", "risk map"), "y": ("map parameter", "risk map")}),
    ]
    return rows


@pytest.fixture(scope="module")
def table(tmp_path_factory):
    return {row.name: row for row in api_table(tmp_path_factory.mktemp("api"))}


#: the public callables, from the package itself: a name added to ``__all__`` is walked
PUBLIC = sorted(set(A.__all__) - NOT_CALLABLES)


def walk(row: Row) -> tuple[collections.Counter, list[str]]:
    """(hostile calls per class, what went wrong) of one row."""
    counts, failures = collections.Counter(), []
    for arg, kind, cls, label, value, call in row.calls():
        counts[cls] += 1
        why = judge(call, kind, (arg, *row.words.get(arg, ())), value)
        if why:
            failures.append(f"{row.name}({arg}={label}): {why}")
    return counts, failures


@pytest.mark.parametrize("name", PUBLIC)
def test_every_argument_refuses_hostile_values_in_one_line(table, name):
    """Each hostile value of each argument: a one-line InputError naming the argument, no
    warning, never a bare NumPy/IndexError/TypeError -- and the row's own call is valid, so
    each refusal is the mutated argument's."""
    assert name in table, f"{name} is public but has no row in api_table: add one"
    row = table[name]
    params = [p for p in inspect.signature(row.fn).parameters.values()
              if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    assert set(row.kinds) == {p.name for p in params} == set(row.args), \
        f"{name}: the row must give every argument a valid value and a kind"
    row.fn(**row.args)
    thin = [arg for arg, kind in row.kinds.items() if len(kind.bad()) < 5]
    assert not thin, f"{name}: fewer than 5 hostile values for {thin}"
    counts, failures = walk(row)
    assert not failures, "\n".join(failures)


def walk_arrays(row: Row) -> tuple[collections.Counter, list[str]]:
    """(NumPy variants per class, what went wrong) of the array arguments of one row."""
    counts, failures = collections.Counter(), []
    for arg, kind in row.kinds.items():
        if kind.what == "array":
            plain, variants = array_variants(kind, row.args[arg])
        elif kind.what in ("number", "int"):
            plain, variants = number_variants(kind, row.args[arg])
        else:
            continue
        if not variants:
            continue
        arr, memo = np.atleast_1d(plain), {}
        others = {"same": plain, "nan": nan_first(arr), "scalar": float(arr.flat[0])}

        def expected(how, arg=arg, others=others, memo=memo):
            if how not in memo:                 # each reference call once per argument
                memo[how] = outcome(row._call(arg, others[how]))
            return memo[how]

        for cls, label, value, how in variants:
            counts[cls] += 1
            why = judge_variant(row._call(arg, value), expected, kind,
                                (arg, *row.words.get(arg, ())), how)
            if why:
                failures.append(f"{row.name}({arg}={label}): {why}")
    return counts, failures


@pytest.mark.parametrize("name", PUBLIC)
def test_numpy_arrays_of_every_flavour(table, name):
    """Issue 25, item 3: each array argument given as NumPy arrays a caller may hold
    (:func:`api_walk.array_variants`): complex, boolean or object arrays, a 0-d or empty
    array and a broadcast view of 4e10 values refused in one line naming the argument;
    a masked array's masked values taken as undefined (as NaN) or refused; a strided
    view, big-endian, read-only, Fortran-ordered or integer array giving exactly what the
    plain float64 array of the same values gives."""
    _, failures = walk_arrays(table[name])
    assert not failures, "\n".join(failures)


def test_the_walk_covers_every_class(table):
    """The counts the issue asks for (per class of bad input), for the report."""
    total, n_args, numpy = collections.Counter(), 0, collections.Counter()
    for row in table.values():
        total.update(collections.Counter(cls for _, _, cls, *_ in row.calls()))
        n_args += len(row.kinds)
        for arg, kind in row.kinds.items():
            if kind.what == "array":
                numpy.update(v[0] for v in array_variants(kind, row.args[arg])[1])
            elif kind.what in ("number", "int"):
                numpy.update(v[0] for v in number_variants(kind, row.args[arg])[1])
    line = (f"API: {len(table)} callables, {n_args} arguments, {sum(total.values())} hostile "
            f"calls: " + ", ".join(f"{k} {v}" for k, v in total.most_common()) +
            f"; NumPy arrays and scalars: {sum(numpy.values())}: " +
            ", ".join(f"{k} {v}" for k, v in numpy.most_common()))
    print(line)
    assert set(total) == {"type", "shape", "NaN", "inf", "overflow", "range", "file", "choice",
                          "huge"}
    assert set(numpy) == {"type", "shape", "NaN", "huge", "layout"}
    assert len(table) == len(PUBLIC) and n_args >= 4 * len(table)


def _refused(call, *words):
    """The call's one-line InputError (its message holds ``words``), no warning on the way."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(InputError) as exc:
            call()
    msg = str(exc.value)
    assert "\n" not in msg and all(w in msg for w in words), msg
    return msg


def test_the_issue_examples(tmp_path):
    """Issue 18, section 9, one by one."""
    _refused(lambda: A.compute_reservoir(TEX, psi="abc"), "psi must be a number or a 1-d array")
    _refused(lambda: A.compute_reservoir(TEX, np.zeros((2, 2))), "psi", "shape (2, 2)")
    np.save(tmp_path / "z.npy", Z)
    _refused(lambda: A.load_surface(tmp_path / "z.npy", unit="um", pixel_size=np.eye(2)),
             "pixel_size must be a number or a pair (dx, dy), got shape (2, 2)")
    fs = A.load_surface(tmp_path / "z.npy", unit="m", pixel_size=1e-6)
    _refused(lambda: A.FacetSurface(fs.gx, fs.gy[:-1], 0.1, fs.weight, {}),
             "gy must have the shape of gx")


def test_the_issue_25_examples():
    """Issue 25, item 3, one by one: heights times 1e300 (a raw OverflowError), a masked
    array (its masked pixels taken as heights), complex heights (accepted), a 200000^2
    request (a raw MemoryError)."""
    from asperity.errors import ResourceError
    _refused(lambda: A.solve_contact(Z * 1e300, 1e-6, 1e9, 1e6), "heights must lie within")
    mask = np.zeros(Z.shape, dtype=bool)
    mask[3:5, 2:7] = True
    masked = A.solve_contact(np.ma.masked_array(Z, mask=mask), 1e-6, 1e9, 1e6)
    nan = A.solve_contact(np.where(mask, np.nan, Z), 1e-6, 1e9, 1e6)
    assert np.isnan(masked.pressure[mask]).all()
    assert np.array_equal(masked.pressure, nan.pressure, equal_nan=True)
    _refused(lambda: A.solve_contact(Z + 0j, 1e-6, 1e9, 1e6), "heights must be real numbers")
    for view in (np.broadcast_to(0.0, (200_000, 200_000)),
                 np.broadcast_to(np.int8(0), (200_000, 200_000))):
        msg = _refused(lambda v=view: A.solve_contact(v, 1e-6, 1e9, 1e6),
                       "contact solve of heights of 200000 x 200000 pixels needs about")
        with pytest.raises(ResourceError):
            A.solve_contact(view, 1e-6, 1e9, 1e6)
        assert "memory" in msg


@pytest.mark.parametrize("inline", [False, True])
def test_x3p_whose_increment_overflows_is_one_line_without_warnings(tmp_path, inline):
    """Raw heights times the file's Increment (plus Offset) beyond the float range: the
    whole-file reader, load_surface and the tiled (streamed) derivation refuse the file in
    one TextureFileError line naming the axis, and no RuntimeWarning is printed first."""
    from x3p_files import x3p_bytes

    from asperity.errors import TextureFileError
    raw = np.full((6, 5), 3.0e4)
    p = tmp_path / "overflow.x3p"
    p.write_bytes(x3p_bytes(raw, code="I", zinc=1e305, zoff=0.0, inline=inline))
    calls = [lambda: A.read_surface(p), lambda: A.load_surface(p),
             lambda: A.derive_scan(p, n_directions=8, tile_lines=2)]
    for call in calls:
        msg = _refused(call, "CZ Increment 1e+305", "beyond the float range")
        assert msg.startswith(str(p))
    with pytest.raises(TextureFileError):
        calls[0]()
