"""The files a study names (issue 18, sections 1 and 6), at the library level: confined to
a folder (as the web page's study jobs are), every key that names a file and every form of
name -- absolute, ``..``, ``~``, a glob, a symbolic link or linked folder pointing out -- is
refused in one line naming the key, before any outside file is opened or listed (an audit
hook watches the process); the command line, unconfined, reads exactly the files the one
enumeration finds.  The web page's own tests are in test_web_security.py, the fingerprint
of the inputs' content in test_study_fingerprint.py."""
from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

import pytest

from asperity.errors import InputError
from asperity.study.inputs import Confine, study_files
from asperity.study.spec import load_study

ROOT = Path(__file__).resolve().parents[1]
SURF = ROOT / "surfaces"
WHY = "may only name files of its folder"

# ----------------------------------------------------------------------------- audit

_SEEN: list[tuple[str, str]] = []
_WATCH: list[str] = []


def _hook(event, args):
    if _WATCH and event in ("open", "os.listdir", "os.scandir") and args and \
            isinstance(args[0], (str, bytes, os.PathLike)):
        p = os.fsdecode(args[0]) if not isinstance(args[0], os.PathLike) else os.fspath(args[0])
        if any(os.path.realpath(p).startswith(w) for w in _WATCH):
            _SEEN.append((event, p))


sys.addaudithook(_hook)                 # idle unless a test watches a folder


class watched:
    """Record every open or listing of a file under ``folder`` while inside."""

    def __init__(self, folder: Path):
        self.folder = os.path.realpath(folder)

    def __enter__(self):
        _SEEN.clear()
        _WATCH.append(self.folder)
        return _SEEN

    def __exit__(self, *exc):
        _WATCH.remove(self.folder)


# ----------------------------------------------------------------------------- fixtures

@pytest.fixture
def job(tmp_path, monkeypatch):
    """(input folder, outside folder): the input holds a texture, an assembly, a scan and
    links pointing out; the outside folder holds files of every kind, and is $HOME."""
    inp, out = tmp_path / "job" / "input", tmp_path / "outside"
    inp.mkdir(parents=True)
    out.mkdir()
    for src, name in ((SURF / "wedge-asymmetric.toml", "wedge.toml"),
                      (SURF / "bushing-strip.toml", "asm.toml"),
                      (SURF / "wedge-30-10.stl", "scan.stl")):
        shutil.copyfile(src, inp / name)
        shutil.copyfile(src, out / name)
    shutil.copyfile(inp / "wedge.toml", inp / "wedge-asymmetric.toml")   # asm.toml names it
    (inp / "link.toml").symlink_to(out / "wedge.toml")
    (inp / "linked").symlink_to(out, target_is_directory=True)
    monkeypatch.setenv("HOME", str(out))
    return inp, out


def forms(out: Path, name: str) -> dict[str, str]:
    """Every form of a name that resolves to outside file ``out/name``."""
    return {"absolute": str(out / name), "dotdot": f"../../outside/{name}",
            "tilde": f"~/{name}", "link": "link.toml", "linked-folder": f"linked/{name}",
            "glob": "../../outside/*", "absolute-glob": str(out / "*"),
            "tilde-glob": "~/*", "glob-in-linked-folder": "linked/*",
            "dotdot-after-glob": "*/../../../outside/*"}


def _q(v: str) -> str:
    return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'


def study(inp: Path, key: str, value: str) -> Path:
    """A study (and assembly) in ``inp`` whose file name at ``key`` is ``value``."""
    grid = '[parameters]\n"loading.dT_max" = { values = [80.0] }\n'
    before, after = (SURF / "bushing-strip.toml").read_text().split("[friction]")
    asm = before + after[after.index("[loading]"):]          # no [friction] of its own
    if key == "study.files":
        body = f'[study]\nkind = "files"\nstages = ["derive"]\nfiles = {_q(value)}\n'
    elif key.startswith("study.files["):
        body = (f'[study]\nkind = "files"\nstages = ["derive"]\n'
                f'files = ["wedge.toml", {_q(value)}]\n')
    elif key == "study.texture":
        body = f'[study]\nkind = "grid"\nassembly = "asm.toml"\ntexture = {_q(value)}\n' + grid
    elif key == "study.assembly":
        body = f'[study]\nkind = "grid"\nassembly = {_q(value)}\n' + grid
    else:                                        # a name in the assembly's [friction]
        k = key.rsplit(".", 1)[1]
        (inp / "named.toml").write_text(asm + f"[friction]\n{k} = {_q(value)}\n")
        body = '[study]\nkind = "grid"\nassembly = "named.toml"\n' + grid
    p = inp / "s.toml"
    p.write_text(body)
    return p


KEYS = ["study.files", "study.files[1]", "study.texture", "study.assembly",
        "named.toml: friction.gauge", "named.toml: friction.texture"]
FORMS = list(forms(Path("/x"), "x"))


# ----------------------------------------------------------------------------- confined

@pytest.mark.parametrize("form", FORMS)
@pytest.mark.parametrize("key", KEYS)
def test_every_key_and_form_that_leaves_the_folder_is_refused_naming_the_key(job, key, form):
    inp, out = job
    name = {"study.assembly": "asm.toml", "study.files": "scan.stl"}.get(key, "wedge.toml")
    value = forms(out, name)[form]
    path = study(inp, key, value)
    with watched(out) as seen, pytest.raises(InputError) as e:
        load_study(path, confine=Confine(inp, WHY))
    msg = str(e.value)
    assert "\n" not in msg and f"{key} = {value!r}: {WHY}" in msg, msg
    assert seen == [], f"{key} = {value!r} opened or listed {seen}"


@pytest.mark.parametrize("files", ['"lin*.toml"', '["wedge.toml", "*.toml"]', '"*"'])
def test_a_pattern_inside_the_folder_that_matches_a_link_pointing_out_is_refused(job, files):
    inp, out = job
    (inp / "s.toml").write_text(f'[study]\nkind = "files"\nstages = ["derive"]\n'
                                f'files = {files}\n')
    with watched(out) as seen, pytest.raises(InputError) as e:
        load_study(inp / "s.toml", confine=Confine(inp, WHY))
    assert "study.files" in str(e.value) and WHY in str(e.value), str(e.value)
    assert seen == [], seen


def test_names_inside_the_folder_are_taken_and_each_file_is_read_from_there(job):
    inp, _ = job
    (inp / "sub").mkdir()
    shutil.copyfile(inp / "wedge.toml", inp / "sub" / "w2.toml")
    body = ('[study]\nkind = "files"\nstages = ["derive"]\n'
            'files = ["wedge.toml", "sub/../sub/*.toml", "./scan.stl"]\nunit = "um"\n')
    (inp / "s.toml").write_text(body)
    s = load_study(inp / "s.toml", confine=Confine(inp, WHY))
    assert [Path(f).resolve() for f in s.files] == [inp / "wedge.toml", inp / "sub" / "w2.toml",
                                                   inp / "scan.stl"]
    # a name that stays inside but names no file is refused without a word on outside files
    for key, value in (("study.files", "nothing*.toml"), ("study.texture", "nothing.toml")):
        with pytest.raises(InputError) as e:
            load_study(study(inp, key, value), confine=Confine(inp, WHY, "not uploaded"))
        assert f"{key} = {value!r}: not uploaded" in str(e.value)


def test_a_link_inside_the_folder_to_a_file_inside_is_allowed(job):
    inp, _ = job
    (inp / "alias.toml").symlink_to(inp / "wedge.toml")
    s = load_study(study(inp, "study.texture", "alias.toml"), confine=Confine(inp, WHY))
    assert s.spec["texture"]["alpha_deg"] == 30.0


# ----------------------------------------------------------------------------- command line

def test_the_command_line_reads_any_file_by_the_same_enumeration(job):
    """Unconfined (a local user may name any file): the same forms are read, and the
    files the reader takes are the ones study_files enumerates."""
    inp, out = job
    for form in ("absolute-glob", "tilde-glob", "dotdot", "glob-in-linked-folder"):
        value = forms(out, "scan.stl")[form]
        s = load_study(study(inp, "study.files", value))
        named = study_files({"files": value}, inp, "files")
        assert list(s.files) == list(named.scans) and s.files, form
        assert {os.path.realpath(f) for f in s.files} <= {str(p.resolve()) for p in out.iterdir()}
    s = load_study(study(inp, "named.toml: friction.gauge", "~/g.json"))
    assert s.spec["assembly"]["friction"]["gauge"] == "~/g.json"
    from asperity.microslip.assembly import assembly_from_dict
    from asperity.microslip.friction import resolve_friction
    asm = assembly_from_dict(s.spec["assembly"], s.spec["assembly_path"])
    with pytest.raises(InputError) as e:        # the worker looks where the study looked
        resolve_friction(asm)
    assert str(out / "g.json") in str(e.value)


def test_string_and_list_files_name_the_same_cases(job):
    inp, out = job
    one = load_study(study(inp, "study.files", str(out / "*.toml")))
    (inp / "s.toml").write_text(f'[study]\nkind = "files"\nstages = ["derive"]\n'
                                f'files = [{_q(str(out / "*.toml"))}]\n')
    assert load_study(inp / "s.toml").files == one.files and len(one.files) == 2
