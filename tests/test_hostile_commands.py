"""Hostile input to the newest commands (issue 25, item 4): ``asperity contact`` (maps,
meshes, wedge textures, windows), ``slide --body`` (disc, ring, rectangle, body files),
``derive/fit/risk --elastic``, ``law --pressure`` on law families.  Extreme values,
garbled files, options combined: one line naming the flag (or the file and its key) with
the README's status, or a result -- never a traceback, an internal error or a NaN.

Each case is one a walk of some 900 command lines found failing or unclear (an internal
error, a library name instead of the flag, two ranges for one flag, a message that hides
the value, a run that printed nothing useful), plus the plain refusals next to it."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from cli_run import run
from hostile import assert_finite_output, assert_refused, cli

ROOT = Path(__file__).resolve().parents[1]
SURF = ROOT / "surfaces"
SCAN = SURF / "scan-ridges.txt"
WEDGE_FLAGS = ["--alpha", "30", "--beta", "10", "--mu-alpha", "0.1", "--mu-beta", "0.2"]
E = ["--elastic", "1e9", "--pressure", "1e6"]
BODY = ["--mu1", "0.3", "--u0", "0.5", "--angle", "30", "--dt", "1e-3"]
DISC = ["--body", "disc", "--radius", "0.05", "--contact-points", "64"]


def outcome(capsys, *argv):
    """(status, stdout, stderr) through the real parser, in this process."""
    try:
        return run(capsys, *argv)
    except SystemExit as exc:
        out, err = capsys.readouterr()
        return exc.code, out, err


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("hostile")
    rng = np.random.default_rng(0)
    base = rng.normal(size=(32, 32)) * 1e-6
    np.save(d / "complex.npy", base.astype(complex))
    np.save(d / "bool.npy", base > 0)
    np.save(d / "3d.npy", np.zeros((4, 4, 4)))
    np.save(d / "allnan.npy", np.full((8, 8), np.nan))
    inf = base.copy()
    inf[3, 3] = np.inf
    np.save(d / "inf.npy", inf)
    (d / "garbage.npy").write_bytes(rng.bytes(500))
    (d / "bad.toml").write_text("this is [not toml")
    (d / "neg.toml").write_text('[body]\nshape = "disc"\nradius = -1.0\nmass = 1.0\n')
    (d / "flat.toml").write_text('[body]\nshape = "polygon"\nvertices = [[0,0],[1,0],[2,0]]\n'
                                 'mass = 1.0\n')
    code, _, err = cli("fit", SCAN, *E[:2], "--pressure", "1e5", "1e6", "1e7", "--directions",
                       "72", "-o", d / "family.json")
    assert code == 0, err
    code, _, err = cli("fit", SURF / "wedge-asymmetric.toml", "--directions", "72", "-o",
                       d / "one.json")
    assert code == 0, err
    return d


CONTACT = [
    # one range for --elastic, whichever way it is exceeded, and the materials named
    ([SCAN, "--elastic", "0", "--pressure", "1e6"], "--elastic must be in [1, 1e+13] Pa, got 0"),
    ([SCAN, "--elastic", "5e-324", "--pressure", "1e6"], "--elastic must be in [1, 1e+13] Pa"),
    ([SCAN, "--elastic", "-1e9", "--pressure", "1e6"], "--elastic must be in [1, 1e+13] Pa"),
    ([SCAN, "--materials", "1e308", "0.3", "--pressure", "1e6"],
     "--materials gives E* = 1.099e+308 Pa, outside [1, 1e+13] Pa"),
    ([SCAN, "--materials", "1e9", "0.6", "--pressure", "1e6"], "--materials nu1 must be in"),
    ([SCAN, "--materials", "1e9", "0.3", "1e9", "--pressure", "1e6"],
     "--materials takes E1 NU1 or E1 NU1 E2 NU2"),
    # a pressure whose ratio to E* underflows: refused before a wedge's profile divides by it
    ([*WEDGE_FLAGS, "--elastic", "1e9", "--pressure", "5e-324"],
     "--pressure / --elastic must be in [1e-12, 10], got 0"),
    ([SCAN, "--elastic", "1e9", "--pressure", "1e12"],
     "--pressure / --elastic must be in [1e-12, 10], got 1000"),
    ([SCAN, *E, "--hardness", "1e6"], "--hardness must be in (1e+06, inf) Pa"),
    ([SCAN, *E, "--tol", "0"], "--tol must be in [1e-15, 0.1], got 0"),
    ([SCAN, *E, "--max-iterations", "1e8"], "--max-iterations must be a whole number in [1,"),
    # a mesh's grid step so small that the node count overflowed (an internal error)
    ([SURF / "wedge-30-10.stl", "--unit", "um", *E, "--grid-step", "5e-324"],
     ["the height grid of wedge-30-10.stl", "give a coarser grid_step (--grid-step)"]),
    ([SURF / "wedge-30-10.stl", "--unit", "um", *E, "--boundary", "periodic"],
     "--boundary of a mesh must be free"),
    # the library's words for the flags, after a file's name
    ([SCAN, *E, "--pixel-size", "0"], "--pixel-size is given in --unit; pass --unit too"),
    # windows
    ([SCAN, *E, "--window", "65"], "--window 65 pixels is larger than the scan"),
    ([SCAN, *E, "--window", "15"], "--window must be a whole number in [16,"),
    ([SCAN, *E, "--window", "32", "--windows", "0"], "--windows must be a whole number in [1,"),
    ([SCAN, *E, "--window", "32", "--window-seed", "3"], "--window-seed applies to"),
    ([SCAN, *E, "--window", "32", "--save-pressure", "p.npy"], "not with --save-pressure"),
    ([SURF / "wedge-asymmetric.toml", *E, "--window", "32"], "--window applies to height-map"),
    ([SCAN, *E, "--workers", "2"], "--workers runs windows (--window W)"),
]


@pytest.mark.parametrize("argv,msg", CONTACT)
def test_contact_refuses_in_one_line(capsys, tmp_path, monkeypatch, argv, msg):
    monkeypatch.chdir(tmp_path)
    code, out, err = outcome(capsys, "contact", *argv)
    assert code == 1 and out == "" and err.count("\n") == 1, err
    assert err.startswith("asperity contact: error: ")
    for m in [msg] if isinstance(msg, str) else msg:
        assert m in err, err
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("name,msg", [
    ("complex.npy", "must hold real numbers"), ("bool.npy", "holds booleans"),
    ("3d.npy", "must be a 2-D array"), ("allnan.npy", "every pixel is undefined"),
    ("inf.npy", "infinite values"), ("garbage.npy", "not a surface file"),
    ("nope.npy", "does not exist")])
def test_contact_refuses_a_file_it_cannot_use(files, capsys, name, msg):
    code, out, err = outcome(capsys, "contact", files / name, "--unit", "m", "--pixel-size",
                             "1e-6", *E)
    assert code == 1 and out == "" and err.count("\n") == 1, err
    assert name in err and msg in err, err


def test_an_abbreviated_or_foreign_flag_is_unknown_to_the_command(capsys):
    """contact has no --mu: argparse's prefix matching said 'ambiguous option: --mu could
    match --mu-alpha, --mu-beta'; a flag is now spelled in full, and the command's own
    parser names itself."""
    for argv, flag in ((["contact", SCAN, *E, "--mu", "0.1"], "--mu 0.1"),
                       (["contact", SCAN, *E, "--hard", "2e6"], "--hard 2e6")):
        code, out, err = outcome(capsys, *argv)
        assert code == 2 and out == "" and err.count("\n") == 1, err
        assert err.startswith("asperity contact: error: unrecognized arguments: " + flag), err
        assert "(see asperity contact --help)" in err


BODIES = [
    (["--radius", "1e-9", "--omega0", "10"],
     "the body's inertia (its size and --mass) must be in [1e-15, 1e+12] kg m^2, got 5e-19"),
    (["--centre-of-pressure", "0.01", "0"],
     "--centre-of-pressure applies to --pressure-profile linear only"),
    (["--t-end", "1", "--force-amplitude", "1", "--waveform", "sine"],
     "--force-amplitude takes AX AY or AX AY AT (2 or 3 numbers), got 1"),
    (["--t-end", "1", "--force", "1e308", "0"], "--force must be in [-1e+12, 1e+12] N"),
    (["--force", "-1e-1", "0"], "--force, --torque and --force-amplitude need --t-end"),
    (["--omega0", "-1e7"], "--omega0 must be in [-1e+06, 1e+06] rad/s, got -1e+07"),
    (["--contact-points", "2.5"], "--contact-points must be a whole number in [1, 1000000]"),
    (["--max-iterations", "2.5"], "--max-iterations must be a whole number in [1, 1000000]"),
    # one point: the run's horizon divided by its friction torque (an internal error)
    (["--contact-points", "1"], "body's contact points (--contact-points, or a body file"),
    (["--omega0", "1e6", "--dt", "1e-4"], "--t-end must be given: this body may need"),
    (["--texture-angle", "1e5"], "--texture-angle must be in [-360, 360] deg"),
]


@pytest.mark.parametrize("extra,msg", BODIES)
def test_slide_body_refuses_in_one_line(capsys, extra, msg):
    code, out, err = outcome(capsys, "slide", *BODY, *DISC[:4], *extra)
    assert code == 1 and out == "" and err.count("\n") == 1, err
    assert err.startswith("asperity slide: error: ") and msg in err, err


def test_a_body_file_whose_pressure_points_sit_at_one_spot_is_refused(tmp_path, capsys):
    """A pressure file of one point, or of points at one place: refused in one line (the
    run's horizon divided by the nil friction torque: an internal error), with or without
    --t-end and --omega0."""
    for name, rows in (("one", ["0,0,1000"]), ("spot", ["0.01,0.01,1"] * 3),
                       ("femto", ["0,0,1", "1e-15,0,1"])):
        (tmp_path / f"{name}.csv").write_text("x_m,y_m,p_Pa\n" + "\n".join(rows) + "\n")
        (tmp_path / f"{name}.toml").write_text(
            f'[body]\nshape = "disc"\nradius = 0.05\nmass = 1.0\npressure_file = "{name}.csv"\n')
        for extra in ([], ["--omega0", "10"], ["--t-end", "0.1"]):
            code, out, err = outcome(capsys, "slide", *BODY, "--body", tmp_path / f"{name}.toml",
                                     *extra)
            assert code == 1 and out == "" and err.count("\n") == 1, err
            assert "must not all lie at one spot" in err, err


def test_slide_body_refuses_a_footprint_at_one_spot_before_its_horizon():
    from asperity import InputError, slide_body
    from asperity.bodies.pressure import from_pressure
    from asperity.laws.planar import coulomb_law
    for pts in ([[0.0, 0.0]], [[0.01, 0.02]] * 3):
        fp = from_pressure(np.array(pts), np.ones(len(pts)))
        for t_end in (None, 0.1):
            with pytest.raises(InputError, match="one spot") as e:
                slide_body(coulomb_law(0.3), fp, 1.0, 30.0, 10.0, dt=1e-3, t_end=t_end,
                           inertia=1e-3)
            assert "\n" not in str(e.value)


def test_a_whole_number_is_read_exactly_and_refused_with_its_range(capsys):
    """--window-seed 9223372036854775807 (its largest value) went through a float and was
    refused as 9223372036854775808; --max-iterations 2.5 said 'a whole number' without the
    range."""
    code, out, err = outcome(capsys, "contact", SCAN, *E, "--window", "32", "--windows", "1",
                             "--window-placement", "random", "--window-seed",
                             str(2 ** 63 - 1), "--json")
    assert code == 0, err
    import json
    assert json.loads(out)["windows"]["seed"] == 2 ** 63 - 1
    for argv in (["fit", SURF / "wedge-asymmetric.toml", "--directions", "7.5"],
                 ["law", SURF / "wedge-asymmetric.toml", "--csv-directions", "nan"],
                 ["bench", "--repeats", "1e400"]):
        code, out, err = outcome(capsys, *argv)
        assert code == 1 and out == "" and err.count("\n") == 1, err
        assert "must be a whole number in [" in err, err


@pytest.mark.parametrize("name,msg", [("bad.toml", "not valid TOML"),
                                      ("neg.toml", "body.radius must be in [1e-09, 1000] m"),
                                      ("flat.toml", "body.vertices: the polygon has zero area"),
                                      ("nope.toml", "does not exist")])
def test_slide_refuses_a_body_file_it_cannot_use(files, capsys, name, msg):
    code, out, err = outcome(capsys, "slide", *BODY, "--body", files / name)
    assert code == 1 and out == "" and err.count("\n") == 1 and msg in err, err


def test_a_body_launched_slower_than_the_solver_resolves_is_refused(capsys):
    """--u0 5e-324 (first an internal error, then a run to the horizon printing "still
    moving" beside "sliding stopped at 0 s"): the kernels' slip norm underflows below
    ~1e-154 m/s and takes the body for sticking while it keeps its speed, so a launch
    slower than 1e-100 m/s (or rad/s) other than 0 is refused, in the CLI and the API;
    1e-99 comes to rest in one step."""
    import asperity as a
    for flag, value, unit in (("--u0", "5e-324", "m/s"), ("--u0", "1e-200", "m/s"),
                              ("--omega0", "-1e-300", "rad/s")):
        argv = [*BODY, *DISC, flag, value]
        code, out, err = outcome(capsys, "slide", *argv)
        assert code == 1 and out == "" and err.count("\n") == 1, err
        assert f"{flag} must be 0 or at least 1e-100 {unit} in size, got " in err, err
    code, out, err = outcome(capsys, "slide", "--mu1", "0.3", "--u0", "1e-99", "--angle", "90",
                             "--dt", "1e-3", *DISC)
    assert code == 0 and err == "", err
    assert "rest at" in out and "(1 step of 0.001 s)" in out, out
    assert_finite_output(out)
    fp, law = a.disc_footprint(0.05, contact_points=64), a.coulomb_law(0.3)
    for kw, msg in (({"u0": 5e-324}, "u0 must be 0 or at least 1e-100 m/s"),
                    ({"u0": 1.0, "omega0": 1e-101}, "omega0 must be 0 or at least 1e-100")):
        with pytest.raises(a.InputError, match=msg):
            a.slide_body(law, fp, angle_deg=0.0, **kw)
    with pytest.raises(a.InputError, match=r"u0 \(vx, vy\) must be 0 or at least 1e-100"):
        a.simulate_body(fp.points, fp.weights, law, mass=1.0, inertia=1e-3, dt=1e-3,
                        u0=(1e-300, 1e-300, 0.0))
    r = a.simulate_body(fp.points, fp.weights, law, mass=1.0, inertia=1e-3, dt=1e-3,
                        u0=(0.0, 1e-99, 0.0))
    assert r.stop_time == 1e-3 and not np.any(r.u_final), r


def test_a_spinning_body_says_when_its_spin_stopped(capsys):
    code, out, _ = outcome(capsys, "slide", *BODY, *DISC, "--omega0", "5")
    assert code == 0 and "spin stopped at" in out and "spinning at" not in out, out


def test_law_families_refuse_outside_their_pressures_showing_the_value(files, capsys):
    code, _, err = outcome(capsys, "law", files / "family.json", "--pressure", "99999.99")
    assert code == 1 and err.count("\n") == 1, err
    assert "--pressure 99999.99 Pa is outside the law family's pressures [100000, 1e+07]" in err
    code, _, err = outcome(capsys, "law", files / "family.json", "--pressure", "1e4")
    assert code == 1 and "--pressure 10000 Pa is outside" in err, err
    code, _, err = outcome(capsys, "law", files / "one.json", "--pressure", "1e6")
    assert code == 1 and "--pressure applies to a law family" in err, err
    code, _, err = outcome(capsys, "slide", files / "family.json", "--pressure", "1e308",
                           "--u0", "0.5", "--angle", "30", *DISC)
    assert code == 1 and "--pressure 1e+308 Pa is outside" in err, err
    code, out, err = outcome(capsys, "law", files / "family.json", "--pressure", "1e5",
                             "--psi", "-1e1")
    assert code == 0 and out.startswith("psi = -10 deg"), err


@pytest.mark.parametrize("command", ["derive", "fit"])
def test_a_family_needs_increasing_pressures_in_derive_as_in_fit(capsys, command):
    """derive took --pressure 1e7 1e6 (and 100 copies of one pressure) as a 'law family'
    that fit refuses."""
    for ps in (["1e7", "1e6"], ["1e6", "1e6"]):
        code, out, err = outcome(capsys, command, SCAN, "--elastic", "1e9", "--pressure", *ps)
        assert code == 1 and out == "" and err.count("\n") == 1, err
        assert "--pressure values of a law family must be strictly increasing" in err, err


@pytest.mark.parametrize("argv,msg", [
    (["derive", SURF / "wedge-asymmetric.toml", "--elastic", "5e-324", "--pressure", "1e6"],
     "--elastic must be in [1, 1e+13] Pa"),
    (["fit", SCAN, "--elastic", "1e9", "--pressure", "1e6", "5e-324"],
     "--pressure / --elastic must be in [1e-12, 10], got 0"),
    (["risk", SURF / "wedge-asymmetric.toml", SURF / "two-node-spec.toml", *E, "--boundary",
      "free"], "--boundary of a wedge texture must be periodic"),
    (["risk", SURF / "wedge-asymmetric.toml", SURF / "two-node-spec.toml", "--elastic", "1e9",
      "--pressure", "1e6", "2e6"], "give one --pressure"),
    (["risk", SURF / "wedge-asymmetric.toml", SURF / "two-node-spec.toml", "--elastic", "1e9"],
     "add assembly.contact_area"),
])
def test_elastic_flags_of_derive_fit_and_risk(capsys, argv, msg):
    code, out, err = outcome(capsys, *argv)
    assert code == 1 and out == "" and err.count("\n") == 1 and msg in err, err


def test_the_real_commands_agree(files):
    """A few of the above through ``python -m asperity``, stderr and status as a user
    sees them."""
    assert_refused(cli("contact", *WEDGE_FLAGS, "--elastic", "1e9", "--pressure", "5e-324"),
                   contains="--pressure / --elastic must be in [1e-12, 10], got 0")
    assert_refused(cli("contact", SURF / "wedge-30-10.stl", "--unit", "um", *E, "--grid-step",
                       "5e-324"), contains="--grid-step")
    assert_refused(cli("contact", SCAN, *E, "--mu", "0.1"), code=2,
                   contains="unrecognized arguments: --mu 0.1")
    assert_refused(cli("law", files / "family.json", "--pressure", "-1e-1"),
                   contains="--pressure must be in (0, inf) Pa, got -0.1")


def test_a_window_position_is_solved_once_and_the_text_says_so(capsys):
    """--window 64 --windows 10000 on the 64 x 64 scan solved 10000 identical windows (five
    minutes for one solve's answer); a grid of 30 windows of 60 pixels repeated positions of
    the 25 the scan holds.  Each position is solved once, its figures those of one window."""
    import json
    code, out, err = outcome(capsys, "contact", SCAN, *E, "--window", "64", "--windows",
                             "10000", "--json")
    assert code == 0, err
    s = json.loads(out)
    wi = s["windows"]
    assert (wi["asked"], wi["positions"], wi["solved"], wi["used"]) == (10000, 1, 1, 1), wi
    code, one, err = outcome(capsys, "contact", SCAN, *E, "--window", "64", "--windows", "1",
                             "--json")
    assert code == 0, err
    assert s["area_fraction"] == json.loads(one)["area_fraction"]
    assert s["area_fraction"]["n"] == 1 and s["area_fraction"]["sd"] is None
    code, out, err = outcome(capsys, "contact", SCAN, *E, "--window", "64", "--windows", "5",
                             "--window-placement", "random")
    assert code == 0, err
    assert "5 windows asked, 1 solved: the scan holds 1 distinct position of a window of 64 " \
           "pixels" in out and "ESTIMATE from 1 window of" in out, out
    for placement in ("grid", "random"):
        code, out, err = outcome(capsys, "contact", SCAN, *E, "--window", "60", "--windows",
                                 "30", "--window-placement", placement, "--json")
        assert code == 0, err
        wi = json.loads(out)["windows"]
        origins = [tuple(w["origin_px"]) for w in json.loads(out)["per_window"]]
        assert wi["positions"] == 25 and wi["solved"] == len(origins) <= 25, wi
        assert len(set(origins)) == len(origins), origins
        if placement == "grid":
            assert len(origins) == 25, origins
    # strata narrower than a pixel: two of the 20 random draws fell on one position
    code, out, err = outcome(capsys, "contact", SCAN, *E, "--window", "60", "--windows", "20",
                             "--window-placement", "random", "--window-seed", "5")
    assert code == 0, err
    assert "20 windows asked, 19 solved: the others fell on a position already solved" in out


_SYNC_RACE = """
import os, signal, sys, threading, time
from distributed.utils import LoopRunner, sync
if sys.argv[1] == "quiet":
    from asperity.study.clusters import quiet_interrupted_sync
    quiet_interrupted_sync()
runner = LoopRunner(asynchronous=False)
runner.start()
gate, busy = threading.Event(), threading.Event()
runner.loop.add_callback(lambda: (busy.set(), gate.wait(10)))   # the loop thread is busy
busy.wait(10)
def ctrl_c():                     # Ctrl-C while sync() waits, before its coroutine started
    time.sleep(0.2)
    os.kill(os.getpid(), signal.SIGINT)
    time.sleep(0.3)
    gate.set()
threading.Thread(target=ctrl_c).start()
async def work():
    return 1
try:
    sync(runner.loop, work)
except KeyboardInterrupt:
    print("interrupted")
time.sleep(1.0)
runner.stop()
"""


def test_ctrl_c_before_a_dask_call_started_prints_no_traceback():
    """Ctrl-C during 'contact --window ... --workers 2' printed tornado's 'Exception in
    callback ... NameError: cannot access free variable 'future'' (distributed's sync()
    interrupted before its coroutine ran): the race reproduced exactly, and silenced by
    the filter every cluster connection installs."""
    import subprocess
    import sys

    from hostile import package_env
    runs = {}
    for mode in ("plain", "quiet"):
        p = subprocess.run([sys.executable, "-c", _SYNC_RACE, mode], capture_output=True,
                           text=True, timeout=60, env=package_env(), check=False)
        assert p.stdout == "interrupted\n", (mode, p.stdout, p.stderr)
        runs[mode] = p.stderr
    assert "NameError" in runs["plain"] and "Traceback" in runs["plain"], runs["plain"]
    assert runs["quiet"] == "", runs["quiet"]


def test_the_text_counts_the_steps_to_the_rest_and_one_iteration(capsys):
    """'rest ... after 0.1699 s (10000 steps of 0.0001 s)' under --t-end 1 (the steps run,
    not those to the rest: 0.1699 s is 1699 of them); 'in 1 iterations'."""
    for extra in ([], DISC):
        code, out, err = outcome(capsys, "slide", *BODY, *extra, "--t-end", "2")
        assert code == 0, err
        line = next(x for x in out.splitlines() if x.startswith("rest at"))
        t = float(line.split(" after ")[1].split(" s (")[0])
        k = int(line.split(" s (")[1].split(" step")[0])
        assert k == round(t / 1e-3) < 2000 and "; run to 2 s)" in line, line
    code, out, _ = outcome(capsys, "slide", *BODY)
    assert "run to" not in out, out
    code, out, err = outcome(capsys, "contact", *WEDGE_FLAGS, *E,
                             "--max-iterations", "1")
    assert code == 3 and out == "" and " in 1 iteration (residual" in err, err


def test_a_local_cluster_starts_with_ctrl_c_held_from_its_workers():
    """Ctrl-C (to the process group, as a terminal sends it) while 'contact --window ...
    --workers 2' started its cluster printed the workers' KeyboardInterrupt tracebacks as
    they imported dask, and atexit's 'AssertionError: Status.init' of the half-started
    cluster.  While it starts SIGINT is ignored (the processes started then inherit that)
    and SIGTERM is held, then raised as the command's Terminated."""
    import os
    import signal
    import subprocess
    import sys

    from asperity.cli.interrupts import Terminated, terminate_as_interrupt
    from asperity.study.clusters import _held_signals
    before = signal.getsignal(signal.SIGINT)
    with terminate_as_interrupt():
        hold = _held_signals()
        with hold:
            code = "import signal; print(int(signal.getsignal(signal.SIGINT)))"
            child = subprocess.run([sys.executable, "-c", code],
                                   capture_output=True, text=True, timeout=60, check=True)
            os.kill(os.getpid(), signal.SIGTERM)
            for _ in range(1000):             # the handler runs between two bytecodes
                if hold.got:
                    break
        assert int(child.stdout) == signal.SIG_IGN, child
        assert hold.got == signal.SIGTERM
        with pytest.raises(Terminated):
            hold.replay()
    assert signal.getsignal(signal.SIGINT) is before


def test_unit_replaces_a_stated_height_unit_as_its_help_says(capsys):
    """--help said '--unit ... overrides nothing a file states' while it replaces the
    stated height unit of a text matrix ('# Value units: m' read as um: a near-flat map, in
    full contact at p/E* = 0.001) and keeps its '# Width:'."""
    import json
    fractions = {}
    for unit in ([], ["--unit", "um"]):
        code, out, err = outcome(capsys, "contact", SCAN, *E, *unit, "--json")
        assert code == 0, err
        s = json.loads(out)
        fractions[bool(unit)] = s["area_fraction"]
    assert fractions[False] < 0.1 and fractions[True] == 1.0, fractions
    code, out, _ = outcome(capsys, "contact", "--help")
    assert "overrides nothing" not in out and "--unit replaces it" in " ".join(out.split())


@pytest.mark.parametrize("command", ["derive", "fit", "law", "risk", "serve", "slide",
                                     "contact"])
def test_help_never_says_default_none(capsys, command):
    """derive --help said '(default: None)' 34 times, and '(None: 8)' for --windows."""
    code, out, _ = outcome(capsys, command, "--help")
    text = " ".join(out.split())
    assert code == 0 and "default: None" not in text and "(None:" not in text, text
    assert "(default: False)" not in text, text
    if command in ("derive", "contact"):
        assert "number of windows, 1 to 10000 (default 8)" in text, text


def test_a_refused_value_shows_the_digits_that_tell_it_from_its_bounds(capsys):
    """'--elastic 1.0000001e13' was refused as 'got 1e+13' beside the bound 1e+13; the
    fix then printed '--pressure 1e300' as 'got 1.0000000000000001e+291' (p/E*)."""
    for argv, msg in (
            (["--elastic", "1.0000001e13", "--pressure", "1e6"],
             "--elastic must be in [1, 1e+13] Pa, got 1.0000001e+13"),
            (["--elastic", "1e9", "--pressure", "1e300"],
             "--pressure / --elastic must be in [1e-12, 10], got 1e+291\n"),
            (["--elastic", "1e9", "--pressure", "1e6", "--tol", "0.10000001"],
             "--tol must be in [1e-15, 0.1], got 0.10000001\n")):
        code, out, err = outcome(capsys, "contact", *WEDGE_FLAGS, *argv)
        assert code == 1 and out == "" and msg in err, err
    # a value at an open bound reads as the bound ('got 1000000', 'got 0.0' for a while)
    for argv, msg in ((["--pressure", "1e6", "--hardness", "1e6"], "mean pressure), got 1e+06\n"),
                      (["--pressure", "0"], "--pressure must be in (0, inf) Pa, got 0\n")):
        code, out, err = outcome(capsys, "contact", *WEDGE_FLAGS, "--elastic", "1e9", *argv)
        assert code == 1 and out == "" and msg in err, err


def test_an_assembly_file_with_its_article(tmp_path, capsys):
    """'not UTF-8 text (byte 1); a assembly file must be UTF-8'."""
    bad = tmp_path / "bad.toml"
    bad.write_bytes(b"\x00\xff\xfe[assembly]")
    code, out, err = outcome(capsys, "risk", SURF / "wedge-asymmetric.toml", bad)
    assert code == 1 and out == "" and "; an assembly file must be UTF-8" in err, err


def test_body_refusals_name_what_the_user_wrote(tmp_path, capsys):
    """A body file's 'size = [nan, 0.1]' was refused as 'body.a must be ...'; the CLI's
    renaming of 'profile' made 'a pressure --pressure-profile that does not carry ...'."""
    f = tmp_path / "nan.toml"
    f.write_text('[body]\nshape = "rectangle"\nsize = [nan, 0.1]\nmass = 1.0\n')
    code, out, err = outcome(capsys, "slide", *BODY, "--body", f)
    assert code == 1 and out == "" and "body.size[0] must be in [1e-09, 1000] m, got NaN" in err
    code, out, err = outcome(capsys, "slide", *BODY, *DISC, "--pressure-profile", "linear",
                             "--centre-of-pressure", "0.05", "0")
    assert code == 1 and out == "" and err.count("\n") == 1, err
    assert "--centre-of-pressure (0.05, 0) m: a pressure distribution that does not carry " \
           "the load" in err and "pressure --pressure" not in err, err


def test_risk_says_where_a_gauge_file_goes(files, capsys):
    """'risk law.json assembly.toml' said 'unknown surface file format (suffix .json)'
    though its help speaks of a gauge file holding a law family."""
    code, out, err = outcome(capsys, "risk", files / "family.json", SURF / "bushing-strip.toml")
    assert code == 1 and out == "" and err.count("\n") == 1, err
    assert 'a gauge file goes in the assembly file ([friction] gauge = "law.json")' in err


def test_a_contact_footprint_of_one_pixel_is_refused_for_what_it_is():
    """contact_footprint of a contact on one pixel is one point: slide_body refused it as
    'inertia must be in [1e-30, 1e+12] kg m^2, got 0' (its inertia computed first)."""
    import asperity as a
    h = np.zeros((4, 4))
    h[1, 1] = 1e-6
    fp = a.contact_footprint(a.solve_contact(h, 1e-6, 1e9, 1e3))
    assert fp.points.shape == (1, 2)
    with pytest.raises(a.InputError, match="points must not all lie at one spot"):
        a.slide_body(a.coulomb_law(0.3), fp, 1.0, 0.0, omega0=5.0)


def test_window_notes_count_in_words(tmp_path, capsys):
    """'window: none of the 1 windows ... has enough', '1 windows found a place so', and
    'N of <asked> windows skipped' counted against the windows asked, not those solved."""
    h = np.where(np.arange(32)[:, None] < 16, np.nan, np.random.default_rng(1).normal(
        size=(32, 32)) * 1e-6)
    np.save(tmp_path / "half.npy", h)
    base = ["contact", tmp_path / "half.npy", "--unit", "m", "--pixel-size", "1e-6", *E,
            "--window", "16"]
    code, out, err = outcome(capsys, *base, "--windows", "1")
    assert code == 1 and out == "" and err.count("\n") == 1, err
    assert "--window: the window of 16 x 16 pixels has not enough defined pixels" in err, err
    code, out, err = outcome(capsys, *base, "--windows", "1", "--window-placement", "random",
                             "--window-seed", "3")
    assert code == 0 and "1 window found a place so" in out, out
    code, out, err = outcome(capsys, *base, "--windows", "100")     # 289 positions: 100
    assert code == 0 and "of 100 windows skipped" in out, out
    code, out, err = outcome(capsys, *base, "--windows", "9000")    # 289 solved
    assert code == 0 and "of 289 windows skipped" in out, out


def test_derive_windows_names_its_own_arguments():
    """derive_windows(placement=..., seed=...) was refused as 'window_placement must ...',
    'window_seed must ...' (names it does not have)."""
    import asperity as a
    el = a.ElasticContact(1e9, 1e6)
    for kw, msg in (({"placement": "Random"}, "placement must be one of grid, random"),
                    ({"placement": "random", "seed": 2 ** 64}, "seed must be a whole number"),
                    ({"windows": 2.5}, "windows must be a whole number in [1, 10000]")):
        with pytest.raises(a.InputError) as exc:
            a.derive_windows(SCAN, el, window=32, **kw)
        assert str(exc.value).startswith(msg), exc.value


def test_window_progress_is_not_numbered_as_a_pass(monkeypatch):
    """'asperity contact: pass 1: windows 7.0 % after 5 s': windows take one pass (a scan's
    tiles take several), so their progress is 'windows ...'."""
    import asperity as a
    from asperity.friction import tiled
    labels = []
    monkeypatch.setattr(tiled, "report", lambda f, label: labels.append(label))
    a.derive_windows(SCAN, a.ElasticContact(1e9, 1e6), window=32, windows=2)
    assert labels and set(labels) == {"windows"}, labels
