"""SIGTERM handled as Ctrl-C is, Ctrl-C sent to a whole process group (as a terminal
sends it, Dask workers included), and progress lines when stderr is not a terminal.

Real child processes with their stderr on a pipe, each signalled once its long work has
printed its first progress line (an event, not a guessed delay): waiting for that line
also checks that every long loop (derive, contact windows, slide of a point mass and of a
body, the dynamic strip of risk, a study) reports through asperity.progress.  No timing
is asserted; benchmarks/bench_interrupts.py measures how soon each command stops."""
from __future__ import annotations

import io
import re
import signal
from pathlib import Path

import pytest
from hostile import Running
from test_study_engine import SLOW

from asperity import progress

ROOT = Path(__file__).resolve().parents[1]
SURF = ROOT / "surfaces"
STUDY = SLOW.replace("samples = N", "samples = 3000")   # ~3 ms a case: long enough


def long_runs(tmp: Path) -> dict:
    """name -> (argv, the output file it must not leave): each runs for minutes."""
    study = tmp / "s.toml"
    study.write_text(STUDY.replace("SURF", str(SURF)))
    return {
        "derive": (["derive", SURF / "wedge-asymmetric.toml", "--method", "springs",
                    "--directions", "4000", "--plot", tmp / "r.png"], tmp / "r.png"),
        "contact windows": (["contact", SURF / "scan-ridges.txt", "--elastic", "1e9",
                             "--pressure", "1e6", "--window", "32", "--windows", "10000",
                             "--plot", tmp / "c.png"], tmp / "c.png"),
        "slide": (["slide", "--law", "star", "--mu1", "0.3", "--mu2", "0.2", "--u0", "1",
                   "--angle", "30", "--t-end", "4000", "--dt", "1e-5", "--csv",
                   tmp / "p.csv"], tmp / "p.csv"),
        "slide --body": (["slide", "--mu1", "0.3", "--u0", "1", "--angle", "0", "--body",
                          "disc", "--radius", "0.05", "--contact-points", "256", "--t-end",
                          "1000", "--dt", "1e-4", "--force", "3", "0", "--csv",
                          tmp / "b.csv"], tmp / "b.csv"),       # pushed past friction
        "risk": (["risk", SURF / "wedge-asymmetric.toml", SURF / "bushing-strip.toml",
                  "--dynamic", "10000000", "--plot", tmp / "k.png"], tmp / "k.png"),
        "study": (["study", study, "-o", tmp / "out", "--workers", "0", "--batch-size", "5",
                   "--export", tmp / "x.csv"], tmp / "x.csv"),
    }


def _clean_stop(err: str, status: int, code: int, word: str, command: str):
    assert status == code, (status, err)
    assert "Traceback" not in err and "leaked" not in err and "Error" not in err, err
    assert err.count("\n") == 1 and err.startswith(f"asperity {command}: {word}"), err


@pytest.mark.parametrize("name", ["derive", "contact windows", "slide", "slide --body", "risk",
                                  "study"])
def test_sigterm_stops_a_long_command_as_ctrl_c_does(tmp_path, name):
    argv, output = long_runs(tmp_path)[name]
    before = sorted(p.name for p in tmp_path.iterdir())
    run = Running(*argv, cwd=tmp_path)
    run.wait_progress(above=0.0 if name == "study" else None)   # study: a case stored
    run.send(signal.SIGTERM)
    status, err, lines = run.finish()
    _clean_stop(err, status, 143, "terminated by SIGTERM", argv[0])
    assert lines, "the long loop reports progress"
    assert not output.exists()
    left = sorted(p.name for p in tmp_path.iterdir())
    if name == "study":                        # the store stays, to resume; nothing else
        assert "cases stored in" in err and left == sorted([*before, "out"]), left
    else:
        assert left == before, left            # no partial or temporary file


@pytest.mark.slow
@pytest.mark.parametrize("sig,code,word", [(signal.SIGINT, 130, "interrupted"),
                                           (signal.SIGTERM, 143, "terminated by SIGTERM")])
def test_a_signal_to_the_whole_group_during_windows_on_two_workers(tmp_path, sig, code, word):
    """A terminal's Ctrl-C reaches the Dask workers too: they leave the stopping to the
    command (no asyncio.CancelledError traceback, no 'lost scattered data' log), and no
    process of the group outlives it; SIGTERM to the group likewise."""
    argv, output = long_runs(tmp_path)["contact windows"]
    run = Running(*argv, "--workers", "2", cwd=tmp_path, group=True)
    run.wait_progress()
    run.send(sig)
    status, err, _ = run.finish()
    _clean_stop(err, status, code, word, "contact")
    assert "CancelledError" not in err and "distributed" not in err, err
    assert not output.exists()
    assert run.group_gone(), "a worker outlived the command"


@pytest.mark.slow
def test_sigterm_to_a_study_on_a_local_cluster_closes_it(tmp_path):
    """SIGTERM to the command alone: its cluster is closed as on Ctrl-C (the workers and
    the multiprocessing semaphores are released: no resource-tracker warning)."""
    argv, output = long_runs(tmp_path)["study"]
    argv = [a if a != "0" else "2" for a in argv]                # --workers 2
    run = Running(*argv, cwd=tmp_path, group=True)
    run.wait_progress(above=0.0)
    run.send(signal.SIGTERM, whole_group=False)
    status, err, _ = run.finish()
    _clean_stop(err, status, 143, "terminated by SIGTERM", "study")
    assert "run the same command again to resume" in err and not output.exists()
    assert run.group_gone(), "a worker outlived the command"


# --------------------------------------------------------------------- progress lines

LINE = re.compile(r"^asperity slide: Moreau steps (\d+\.\d) % after \d+ s"
                  r"(, about [\d.]+ (s|min|h) left)?$")


def test_progress_lines_on_a_pipe_then_quiet(tmp_path):
    """stderr on a pipe: plain lines at the pace asked, fractions that only grow; with
    --quiet none (errors still show)."""
    argv = ["slide", "--law", "star", "--mu1", "0.3", "--mu2", "0.2", "--u0", "1", "--angle",
            "30", "--t-end", "4000", "--dt", "1e-5"]
    run = Running(*argv, cwd=tmp_path, every=0.5)
    run.wait_progress()
    while sum(bool(LINE.match(x.rstrip("\n"))) for x in run.err) < 3 and run.p.poll() is None:
        run.progress.clear()
        run.progress.wait(60)
    run.send(signal.SIGINT)
    status, err, lines = run.finish()
    assert status == 130 and err.count("\n") == 1, err
    assert len(lines) >= 3 and all(LINE.match(x.rstrip("\n")) for x in lines), lines
    fractions = [float(LINE.match(x.rstrip("\n")).group(1)) for x in lines]
    assert fractions == sorted(fractions) and fractions[-1] < 100, fractions
    quiet = Running(*argv[:-4], "--t-end", "20", "--dt", "1e-5", "--quiet", cwd=tmp_path,
                    every=0.01)
    status, err, lines = quiet.finish()
    assert status == 0 and err == "" and lines == [], err
    refused = Running(*argv, "--dt", "-1e-5", "--quiet", cwd=tmp_path, every=0.01)
    status, err, _ = refused.finish()
    assert status == 1 and err.startswith("asperity slide: error: --dt must be"), err


class Clock:
    def __init__(self):
        self.t = 100.0

    def __call__(self):
        return self.t


def test_progress_lines_are_rate_limited_with_the_time_left(monkeypatch):
    clock = Clock()
    monkeypatch.setattr(progress.time, "perf_counter", clock)
    monkeypatch.setenv(progress.LINE_ENV, "5")
    out = io.StringIO()                           # not a terminal
    with progress.progress_bar("asperity contact", stream=out) as bar:
        progress.report(0.0, "windows")
        for k in range(1, 41):                    # 1 % a quarter of a second: 10 s in all
            clock.t += 0.25
            progress.report(k / 100)
        assert bar.on is False
        with progress.progress_bar("facets"):     # a phase opened inside: the same lines
            clock.t += 5.0
            progress.report(0.5)
        with progress.silenced():
            clock.t += 60.0
            progress.report(0.9, "nothing")
    lines = out.getvalue().splitlines()
    assert lines == ["asperity contact: windows 20.0 % after 5 s, about 20 s left",
                     "asperity contact: windows 40.0 % after 10 s, about 15 s left",
                     "asperity contact: facets 50.0 % after 15 s"], lines


@pytest.mark.parametrize("every,quiet", [("0", False), ("nan", False), ("5", True),
                                         ("abc", False)])
def test_no_lines_when_asked(monkeypatch, every, quiet):
    """$ASPERITY_PROGRESS_EVERY 0 (or not a number of seconds: nan) or --quiet: no lines;
    text that is no number: the default pace."""
    clock = Clock()
    monkeypatch.setattr(progress.time, "perf_counter", clock)
    monkeypatch.setenv(progress.LINE_ENV, every)
    out = io.StringIO()
    with progress.progress_bar("asperity derive", stream=out, quiet=quiet):
        for k in range(100):
            clock.t += 1.0
            progress.report(k / 100, "facets")
    if every == "abc":                  # reports at 101 ... 200 s, lines from 105 s on
        assert out.getvalue().count("\n") == 20
    else:
        assert out.getvalue() == ""


def test_a_terminal_gets_the_bar_not_lines(monkeypatch):
    class Tty(io.StringIO):
        def isatty(self):
            return True
    clock = Clock()
    monkeypatch.setattr(progress.time, "perf_counter", clock)
    out = Tty()
    with progress.progress_bar("asperity slide", stream=out):
        clock.t += 10
        progress.report(0.5, "Moreau steps")
        with progress.progress_bar("inner", quiet=True):   # quiet applies to the outer only
            progress.report(0.75)
    text = out.getvalue()
    assert "\n" not in text and "\r" in text and "75.0 %" in text and "inner" in text
    out = Tty()
    with progress.progress_bar("asperity slide", stream=out, quiet=True):
        clock.t += 10
        progress.report(0.5)
    assert out.getvalue() == ""


def test_a_study_stopped_before_its_first_case_says_nothing_was_written(tmp_path,
                                                                       monkeypatch):
    """The store of a study stopped before any case is removed: the line must not send
    the user to resume from a folder that is gone."""
    from asperity.study import engine
    from asperity.study.run import run_study_file

    def stopped(*args, **kwargs):
        raise engine.StudyInterrupted("0 of 3000 cases stored in out; run the same command "
                                      "again to resume")
    monkeypatch.setattr(engine, "run_study", stopped)
    study = tmp_path / "s.toml"
    study.write_text(STUDY.replace("SURF", str(SURF)))
    with pytest.raises(engine.StudyInterrupted, match="before its first case was stored; "
                                                      "nothing written"):
        run_study_file(study, tmp_path / "out", workers=0)
    assert not (tmp_path / "out").exists()
