"""The job of the Studies page: a study file and the files it names, run by the study
engine (:func:`asperity.study.run.run_study_file`) into the job's folder, exported as
Parquet and CSV.

A study file names other files (``study.texture``, ``study.assembly``, ``study.files``,
and an assembly's ``[friction]`` ``texture`` or ``gauge``).  On the server every such name
must resolve among the files uploaded with the study, whatever its form (absolute, ``..``,
``~``, a glob, a link): the study reader's own enumeration of the files a study names
(:func:`asperity.study.inputs.study_files`) runs confined to the job's ``input/`` folder,
once on the form (:func:`check_references`, on a copy of the upload's names: HTTP 400)
and again when the job reads the study: a study can never make the server read a file of
its own choosing.
"""
from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

from ..errors import InputError
from .labels import stem
from .results import rename
from .store import UploadError, check_plain_name

#: the page's words when a study names a file outside the files uploaded with it
OUTSIDE = "on this page a study may only name files uploaded with it"
MISSING = "no such file among those uploaded with the study; add it to the upload"


def confinement(root: Path):
    """The page's confinement of a study's file names to ``root``."""
    from ..study.inputs import Confine
    return Confine(Path(root), OUTSIDE, MISSING)


def check_references(study_text: str, companions: dict[str, str | None]) -> list[str]:
    """Check that the study (TOML text) names only files among ``companions`` (plain name
    -> TOML text, or None for other files), by the enumeration the job runs, on a folder
    holding the companions' names (their TOML text, other files empty); the names it uses.
    One-line UploadError naming the key."""
    from ..io import parse_toml
    from ..study.inputs import study_files
    data = parse_toml(study_text, "the study file", UploadError)
    st = data.get("study")
    if not isinstance(st, dict):
        raise UploadError("the study file has no [study] table (see the example on the page)")
    with tempfile.TemporaryDirectory(prefix="asperity-study-") as tmp:
        root = Path(tmp)
        for name, text in companions.items():
            (root / check_plain_name(name)).write_text(text or "", encoding="utf-8")
        try:
            named = study_files(st, root, st.get("kind"), confinement(root))
        except InputError as exc:
            raise UploadError(str(exc).replace(str(root) + os.sep, "")) from None
        real = os.path.realpath(root) + os.sep
        return sorted({os.path.realpath(p).removeprefix(real) for n in named.named
                       for p in n.paths})


def study_task(params: dict, ctx: dict, bar) -> dict:
    from ..study.run import export_folder, run_study_file
    from ..study.spec import load_study
    from ..study.store import StoreError
    from ..study.text import lines
    from .tasks_surface import upload_file
    folder = ctx["job_dir"]
    inp = folder / "input"
    inp.mkdir(exist_ok=True)
    for f in [params["study"], *params.get("companions", [])]:
        name = check_plain_name(f["name"])
        shutil.copyfile(upload_file(ctx, f["upload"], name), inp / name)
    ctx["names"][str(inp) + "/"] = ""
    ctx["names"][str(folder) + "/"] = ""
    study_name = params["study"]["name"]
    study = load_study(inp / study_name, confine=confinement(inp))
    from .job_progress import phase
    try:            # a job run again after a restart resumes its store: same inputs only
        with phase(bar, 0.0, 0.95):
            summary = run_study_file(study, folder / "study",
                                     workers=params.get("workers", 0), plot=True)
    except StoreError as exc:
        if exc.changed is None:
            raise
        raise StoreError(f"{exc.changed}: this result cannot be resumed; upload the study "
                         f"again for a new result") from None
    bar(0.97, "exporting the cases")
    rows = export_folder(folder / "study", folder / "cases.parquet")
    export_folder(folder / "study", folder / "cases.csv")   # as the study names its files
    summary = rename(summary, ctx["names"])
    figures = [f if f.startswith("study/") else f"study/{f.rsplit('/', 1)[-1]}"
               for f in summary.get("figures", [])]
    files = ["cases.parquet", "cases.csv", "study/summary.json", "study/summary.md", *figures]
    name = stem(study_name)
    downloads = {f: f"{name}_{f.rsplit('/', 1)[-1]}" for f in files}
    return {"summary": summary, "text": rename("\n".join(lines(summary)), ctx["names"]),
            "figures": figures, "rows": rows, "files": files, "downloads": downloads}


TASKS = {"study": study_task}
