"""Hostile outputs (issue 11, class 1): every output path and format is checked before any
work, the outputs of a command are committed together only when all succeeded, a failed
or interrupted run leaves existing files byte-identical, modes follow the umask or the
replaced file, symbolic links are written through, ``-`` is standard output."""
from __future__ import annotations

import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest
from hostile import SURF, assert_refused, cli, package_env, read_only

WEDGE = str(SURF / "wedge-asymmetric.toml")
TWO_NODE = str(SURF / "two-node-spec.toml")

#: commands with their output flags; each runs in a second or less
COMMANDS = {
    "derive": (["derive", WEDGE], ["--plot"]),
    "fit": (["fit", WEDGE, "--directions", "72"], ["-o", "--plot"]),
    "risk": (["risk", TWO_NODE], ["--plot"]),
    "slide": (["slide", "--mu1", "0.3", "--u0", "1", "--angle", "30"], ["--csv", "--plot"]),
}


@pytest.fixture(scope="module")
def gauge(tmp_path_factory):
    g = tmp_path_factory.mktemp("gauge") / "g.json"
    assert cli("fit", WEDGE, "--directions", "72", "-o", g)[0] == 0
    return g


def law_command(gauge):
    return ["law", str(gauge)], ["--csv", "--abaqus", "--plot"]


def existing(tmp_path: Path, name: str, content=b"precious\n") -> Path:
    p = tmp_path / name
    p.write_bytes(content)
    return p


def all_commands(gauge):
    return {**COMMANDS, "law": law_command(gauge)}


def out_value(flag: str, path: Path) -> list[str]:
    return [flag, str(path)]


def _each_command_output(gauge):
    for name, (base, flags) in all_commands(gauge).items():
        for flag in flags:
            yield name, base, flag


# ----------------------------------------------------------------------------- before any work

@pytest.mark.parametrize("name", ["derive", "fit", "law", "slide", "risk"])
def test_unsupported_plot_format_refused_before_any_file_is_touched(name, gauge, tmp_path):
    base, flags = all_commands(gauge)[name]
    keep = {f: existing(tmp_path, f"keep{i}.txt") for i, f in enumerate(flags) if f != "--plot"}
    argv = list(base) + ["--plot", str(tmp_path / "out.xyz")]
    for f, p in keep.items():
        argv += [f, str(p)]
    assert_refused(cli(*argv), contains=["--plot", "unsupported figure format '.xyz'"])
    for p in keep.values():
        assert p.read_bytes() == b"precious\n"
    assert not (tmp_path / "out.xyz").exists()
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".part")]


def bad_paths(tmp_path: Path) -> dict:
    (tmp_path / "a_folder").mkdir()
    (tmp_path / "file.txt").write_text("x")
    return {"missing folder": (tmp_path / "no" / "such" / "out.png", "does not exist"),
            "a folder": (tmp_path / "a_folder", "is a folder"),
            "under a file": (tmp_path / "file.txt" / "out.png", "does not exist"),
            "empty name": ("", "empty file name")}


@pytest.mark.parametrize("case", ["missing folder", "a folder", "under a file", "empty name"])
def test_unusable_output_paths_are_one_line(case, gauge, tmp_path):
    path, msg = bad_paths(tmp_path)[case]
    n = 0
    for name, base, flag in _each_command_output(gauge):
        result = cli(*base, flag, path)
        assert_refused(result, contains=[flag, msg])
        n += 1
    assert n == 9                                   # every output flag of every command


def test_read_only_folder_is_refused_and_keeps_its_file(gauge, tmp_path):
    """Refused before the work when the permission bits say so, else when the temporary
    file cannot be made: one line either way, and the old file stays."""
    folder = tmp_path / "ro"
    folder.mkdir()
    keep = existing(folder, "g.json")
    with read_only(folder):
        for argv in (["fit", WEDGE, "--directions", "72", "-o", keep],
                     ["law", gauge, "--csv", folder / "t.csv"],
                     ["derive", WEDGE, "--plot", folder / "p.png"],
                     ["report", "--out", folder / "rep"]):
            status, out, err = cli(*argv)
            assert status == 1 and "Traceback" not in err and err.count("\n") == 1, err
            assert any(m in err for m in ("not writable", "not permitted", "ermission denied"))
    assert keep.read_bytes() == b"precious\n"
    assert sorted(p.name for p in folder.iterdir()) == ["g.json"]


def test_two_outputs_on_one_file_and_output_on_an_input_are_refused(gauge, tmp_path):
    p = tmp_path / "same.csv"
    assert_refused(cli("law", gauge, "--csv", p, "--abaqus", p),
                   contains=["--csv and --abaqus name the same output"])
    before = gauge.read_bytes()
    assert_refused(cli("law", gauge, "--csv", gauge), contains="also an input")
    assert gauge.read_bytes() == before
    assert_refused(cli("slide", "--mu1", "0.3", "--u0", "1", "--angle", "0", "--csv", "-",
                       "--plot", "-"), contains="name the same output")


# ----------------------------------------------------------------------------- committing

def test_full_device_is_one_line_and_nothing_else_is_committed(tmp_path):
    keep = existing(tmp_path, "g.json")
    result = cli("fit", WEDGE, "--directions", "72", "-o", keep, "--plot", "/dev/full")
    status, out, err = result
    assert status == 1 and "Traceback" not in err
    assert err.count("\n") == 1 and "No space left on device" in err and "/dev/full" in err
    assert keep.read_bytes() == b"precious\n", "an output was committed although another failed"
    assert "written to" not in out


def test_a_write_that_fails_midway_leaves_the_old_file(tmp_path):
    """A file-size limit makes the write of a large output fail as a full disk would."""
    keep = existing(tmp_path, "g.json", b"old gauge\n")

    def small_files():
        import resource
        import signal
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (20_000, 20_000))
    status, out, err = cli("fit", WEDGE, "--directions", "720", "-o", keep,
                           preexec_fn=small_files)
    assert status == 1 and "Traceback" not in err and err.count("\n") == 1, err
    assert "cannot write" in err and "g.json" in err
    assert keep.read_bytes() == b"old gauge\n"
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".part")]


def test_modes_follow_the_umask_or_the_replaced_file(tmp_path):
    def umask(m):
        return lambda: os.umask(m)
    fresh = tmp_path / "fresh.json"
    assert cli("fit", WEDGE, "--directions", "72", "-o", fresh, preexec_fn=umask(0o027))[0] == 0
    assert stat.S_IMODE(fresh.stat().st_mode) == 0o640
    kept = existing(tmp_path, "kept.json")
    os.chmod(kept, 0o604)
    assert cli("fit", WEDGE, "--directions", "72", "-o", kept, preexec_fn=umask(0o077))[0] == 0
    assert stat.S_IMODE(kept.stat().st_mode) == 0o604
    assert kept.read_bytes().startswith(b"{")


def test_writing_through_a_symlink_writes_its_target(tmp_path):
    target = existing(tmp_path, "target.json")
    link = tmp_path / "link.json"
    link.symlink_to(target)
    assert cli("fit", WEDGE, "--directions", "72", "-o", link)[0] == 0
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert target.read_text().startswith("{") and '"asperity-gauge"' in target.read_text()


def test_dash_and_dev_stdout_write_to_standard_output(tmp_path):
    status, out, err = cli("fit", WEDGE, "--directions", "72", "-o", "-")
    assert status == 0 and out.startswith("{") and '"format": "asperity-gauge"' in out
    assert "gauge file written to standard output" in err and "fitted points" in err
    status, out2, _ = cli("fit", WEDGE, "--directions", "72", "-o", "/dev/stdout")
    assert status == 0 and '"format": "asperity-gauge"' in out2
    status, out, err = cli("slide", "--mu1", "0.3", "--u0", "1", "--angle", "0", "--csv", "-")
    assert status == 0 and out.startswith("t_s,x_m,y_m,vx_m_s,vy_m_s\n") and "rest at" in err


def test_report_out_onto_a_file_or_a_read_only_folder(tmp_path):
    f = existing(tmp_path, "REPORT.md")
    assert_refused(cli("report", "--out", f), contains="is a file, not a folder")
    assert_refused(cli("report", "--out", f / "sub"), contains="cannot be made")
    assert f.read_bytes() == b"precious\n"


# ----------------------------------------------------------------------------- pipes

def test_output_piped_into_head_ends_quietly():
    p = subprocess.Popen([sys.executable, "-m", "asperity", "derive", WEDGE, "--directions",
                          "20000", "--json"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         env=package_env())
    first = p.stdout.readline()
    p.stdout.close()                              # `| head -1` has read its line and left
    err = p.stderr.read().decode()
    assert p.wait(timeout=60) == 0
    assert first.startswith(b"{") and err == ""
