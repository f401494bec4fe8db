"""The job of the Studies page: a study file and the files it names, run by the study
engine (:func:`asperity.study.run.run_study_file`) into the job's folder, exported as
Parquet and CSV.

A study file names other files (``study.texture``, ``study.assembly``, ``study.files``,
and an assembly's ``[friction]`` ``texture`` or ``gauge``).  On the server these may only
be plain names of the files uploaded with it (:func:`check_references`), copied beside it
into the job's ``input/`` folder: a study can never make the server read a file of its
own choosing.
"""
from __future__ import annotations

import fnmatch
import shutil

from .labels import stem
from .results import rename
from .store import UploadError, check_plain_name


def _plain_reference(where: str, value) -> str:
    if not isinstance(value, str) or not value:
        raise UploadError(f"{where} must be a file name")
    if "/" in value or "\\" in value or ".." in value or value.startswith("."):
        raise UploadError(f"{where} = {value!r}: on this page a study may only name files "
                          f"uploaded with it (plain names, no folders)")
    return value


def check_references(study_text: str, companions: dict[str, str]) -> list[str]:
    """Check that the study (TOML text) names only files among ``companions`` (plain name
    -> TOML text or None for other files); the names it uses.  One-line UploadError."""
    from ..io import parse_toml
    data = parse_toml(study_text, "the study file", UploadError)
    st = data.get("study")
    if not isinstance(st, dict):
        raise UploadError("the study file has no [study] table (see the example on the page)")
    used = []
    for key in ("texture", "assembly"):
        if isinstance(st.get(key), str):
            name = _plain_reference(f"study.{key}", st[key])
            if name not in companions:
                raise UploadError(f"the study names {name!r} (study.{key}): add it to the "
                                  f"files uploaded with the study")
            used.append(name)
    pats = st.get("files", [])
    for i, pat in enumerate(pats if isinstance(pats, list) else []):
        pat = _plain_reference(f"study.files[{i}]", pat)
        hits = [n for n in companions if fnmatch.fnmatchcase(n, pat)]
        if not hits:
            raise UploadError(f"study.files[{i}] {pat!r} matches none of the files uploaded "
                              f"with the study")
        used += hits
    asm = st.get("assembly")
    if isinstance(asm, str) and companions.get(asm) is not None:
        adata = parse_toml(companions[asm], asm, UploadError)
        fr = adata.get("friction", {})
        for key in ("texture", "gauge"):
            if isinstance(fr, dict) and isinstance(fr.get(key), str):
                name = _plain_reference(f"{asm}: friction.{key}", fr[key])
                if name not in companions:
                    raise UploadError(f"{asm} names {name!r} (friction.{key}): add it to the "
                                      f"files uploaded with the study")
                used.append(name)
    return used


def study_task(params: dict, ctx: dict, bar) -> dict:
    from ..study.run import export_folder, run_study_file
    from ..study.text import lines
    from .tasks_surface import upload_file
    folder = ctx["job_dir"]
    inp = folder / "input"
    inp.mkdir(exist_ok=True)
    texts = {}
    for f in [params["study"], *params.get("companions", [])]:
        name = check_plain_name(f["name"])
        src = upload_file(ctx, f["upload"], name)
        shutil.copyfile(src, inp / name)
        if name.lower().endswith(".toml"):
            texts[name] = (inp / name).read_text(encoding="utf-8", errors="replace")
        else:
            texts[name] = None
    study_name = params["study"]["name"]
    check_references(texts[study_name], {k: v for k, v in texts.items() if k != study_name})
    ctx["names"][str(inp) + "/"] = ""
    ctx["names"][str(folder) + "/"] = ""
    summary = run_study_file(inp / study_name, folder / "study", workers=params.get("workers", 0),
                             plot=True)
    bar(0.97, "exporting the cases")
    rows = export_folder(folder / "study", folder / "cases.parquet")
    export_folder(folder / "study", folder / "cases.csv")
    summary = rename(summary, ctx["names"])
    figures = [f if f.startswith("study/") else f"study/{f.rsplit('/', 1)[-1]}"
               for f in summary.get("figures", [])]
    files = ["cases.parquet", "cases.csv", "study/summary.json", "study/summary.md", *figures]
    name = stem(study_name)
    downloads = {f: f"{name}_{f.rsplit('/', 1)[-1]}" for f in files}
    return {"summary": summary, "text": rename("\n".join(lines(summary)), ctx["names"]),
            "figures": figures, "rows": rows, "files": files, "downloads": downloads}


TASKS = {"study": study_task}
