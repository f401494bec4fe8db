"""Law families (version-2 gauge files) inside the generated FRIC: the law at PRESS as
``asperity law --pressure`` takes it (a member at its pressure, ``GaugeFamily.at`` between),
clamped outside the members' pressures with a count in STATEV(2), and DDTDDP holding the
change of the law with the pressure (against central differences)."""
from __future__ import annotations

import math
from dataclasses import replace
from functools import cache

import numpy as np
import pytest
from fe_builds import library, needs_gfortran
from law_families import contact, four_members

from asperity.fe.fortran_harness import call_fric

pytestmark = needs_gfortran
K = 1e10


@cache
def families():
    """The four-member star family of the family tests, and a two-member truncated-ellipse
    family of different asymmetry (its semi-axes are interpolated: the routine's blend needs
    levels between the members)."""
    from asperity.friction.derive import derive
    from asperity.laws.family import GaugeFamily
    from asperity.laws.fitting import fit_derivation
    from asperity.texture.wedges import WedgeTexture
    ell = [fit_derivation(derive(WedgeTexture(a, b, 0.3, 0.05), "windward", "closed-form", 72),
                          "truncated-ellipse") for a, b in ((10, 40), (35, 15))]
    src = ell[0].source
    two = GaugeFamily((1e6, 1e8), tuple(replace(g, source={**src, "elastic_contact":
                                                           contact(p)})
                                        for g, p in zip(ell, (1e6, 1e8))))
    return {"star": four_members(), "ellipse": two}


@cache
def lib(name):
    from asperity.fe.abaqus_fric import routine_source
    return library(routine_source(families()[name], "fric", header=[f"family {name}"]))


def slide(name, press, phi, statev=(0.0, 0.0, 0.0)):
    """Steady sliding along phi from the law's own force at press: (tau, statev)."""
    u = np.array([math.cos(phi), math.sin(phi)])
    fam = families()[name]
    p = min(max(press, fam.pressures[0]), fam.pressures[-1])
    tau0 = press * fam.at(p).force(np.array([phi])).p[0]
    out = call_fric(lib(name), lm=0, tau=tau0, statev=np.asarray(statev, float),
                    dgam=1e-4 * u, press=press, props=np.array([K, 0.0, 1.0]))
    return out, tau0


@pytest.mark.parametrize("name", ["star", "ellipse"])
def test_members_and_between_them_as_law_pressure_takes_them(name):
    fam = families()[name]
    lo, hi = fam.pressures[0], fam.pressures[-1]
    pressures = list(fam.pressures) + [math.sqrt(lo * hi), lo * (hi / lo) ** 0.23,
                                       lo * (hi / lo) ** 0.81]
    for press in pressures:
        for phi in np.radians(np.arange(0.0, 360.0, 7.5) + 0.3):
            out, tau0 = slide(name, press, phi)
            assert np.abs(out.tau - tau0).max() < 1e-4 * press, (press, math.degrees(phi))
            assert out.statev[1] == 0.0


@pytest.mark.parametrize("name", ["star", "ellipse"])
def test_outside_the_members_the_law_is_clamped_and_counted(name):
    fam = families()[name]
    for press, end in ((0.3 * fam.pressures[0], 0), (4.0 * fam.pressures[-1], -1)):
        member = fam.members[end]
        for phi in np.radians([10.0, 100.0, 200.0]):
            out, _ = slide(name, press, phi, statev=(0.0, 5.0, 0.0))
            ref = press * member.force(np.array([phi])).p[0]
            assert np.abs(out.tau - ref).max() < 1e-4 * press
            assert out.statev[1] == 6.0                  # one more clamped increment


@pytest.mark.parametrize("name", ["star", "ellipse"])
@pytest.mark.parametrize("side", [1.0, -1.0])
def test_nfdir_1_takes_the_law_at_the_pressure_and_its_change(name, side):
    fam = families()[name]
    lo, hi = fam.pressures[0], fam.pressures[-1]
    for w in (0.0, 0.3, 0.77, 1.0, 1.6):
        press = lo * (hi / lo) ** w
        ref = fam.at(min(press, hi))
        th = math.radians(30.0) + (math.pi if side < 0 else 0.0)
        s = np.array([math.cos(-th), math.sin(-th)])
        for sign, psi in ((1.0, -th), (-1.0, math.pi - th)):
            def tau(pp, sign=sign, press=press):
                return call_fric(lib(name), lm=0, tau=[0.0], statev=np.zeros(3),
                                 dgam=[3.0 * sign * press / K], press=pp,
                                 props=np.array([K, 30.0, side]),
                                 nfdir=1)
            out = tau(press)
            assert out.tau[0] == pytest.approx(press * ref.force(np.array([psi])).p[0] @ s,
                                               abs=1e-4 * press)
            assert out.statev[1] == (1.0 if w > 1 else 0.0)
            if w in (0.0, 1.0):          # a member's pressure: the law's slope changes there
                continue
            h = 1e-6 * press
            num = (tau(press + h).tau[0] - tau(press - h).tau[0]) / (2 * h)
            assert out.ddtddp[0] == pytest.approx(num, abs=1e-5), w


@pytest.mark.parametrize("name", ["star", "ellipse"])
def test_ddtddp_holds_the_change_of_the_law_with_pressure(name):
    fam = families()[name]
    rng = np.random.default_rng(2)
    lo, hi = fam.pressures[0], fam.pressures[-1]
    for _ in range(12):
        press = lo * (hi / lo) ** rng.uniform(0.02, 0.98)
        phi = rng.uniform(0, 2 * math.pi)
        tau0 = 0.8 * press * fam.at(press).force(np.array([phi])).p[0]
        dg = 1e-4 * np.array([math.cos(phi), math.sin(phi)])

        def tau(pp, tau0=tau0, dg=dg):
            return call_fric(lib(name), lm=0, tau=tau0, statev=np.zeros(3), dgam=dg,
                             press=pp, props=np.array([K, 0.0, 1.0])).tau
        out = call_fric(lib(name), lm=0, tau=tau0, statev=np.zeros(3), dgam=dg, press=press,
                        props=np.array([K, 0.0, 1.0]))
        h = 1e-6 * press
        num = (tau(press + h) - tau(press - h)) / (2 * h)
        assert np.abs(out.ddtddp - num).max() < 1e-5, (out.ddtddp, num)


@pytest.mark.parametrize("name", ["star", "ellipse"])
def test_the_routines_law_is_exactly_the_blended_table(name):
    """ASPFRC and ASPRAD at any pressure against the family table blended at it, to
    rounding (the boundary's search on blended polar angles may land one interval off:
    the neighbours are tried)."""
    import ctypes as C

    from asperity.fe.table import family_table
    ft = family_table(families()[name])
    lo, hi = ft.pressures[0], ft.pressures[-1]
    rng = np.random.default_rng(12)
    r, n, px, py = C.c_double(), C.c_int(), C.c_double(), C.c_double()
    for _ in range(150):
        press = lo * (hi / lo) ** rng.uniform(-0.05, 1.05)
        tab = ft.level(press)
        for x in rng.uniform(-math.pi, 3 * math.pi, 20):
            lib(name).aspfrc_(C.byref(C.c_double(press)), C.byref(C.c_double(x)),
                              C.byref(px), C.byref(py), C.byref(n))
            assert np.abs([px.value, py.value] - tab.force([x])[0]).max() < 1e-12
            assert n.value == int(press < lo or press > hi)
            lib(name).asprad_(C.byref(C.c_double(press)), C.byref(C.c_double(x)),
                              C.byref(r), C.byref(n))
            assert abs(r.value - tab.radial([x])[0]) < 1e-12, (press, x)
