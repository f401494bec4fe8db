"""``asperity study``: many cases at once -- tolerance Monte Carlo, sensitivity, grids and
scan libraries -- on a Dask cluster, into a resumable store, with a summary."""
from __future__ import annotations

import argparse
import os

from ..errors import InputError
from . import add_cluster_arguments, emit, whole_flag


def add_parser(sub) -> None:
    p = sub.add_parser(
        "study", help="run a study (Monte Carlo, Sobol, grid, scan library) on a Dask cluster",
        description="Run the cases of a study file (see the documentation: the creep-risk tutorial and the file formats) -- derive, fit "
                    "and/or the risk verdict for every sample of the parameters or every "
                    "file of a scan library -- in batches on an embedded local Dask cluster "
                    "(one worker per core) or an existing one (--scheduler), into a SQLite "
                    "store in DIR, and print the summary: counts per verdict, probability of "
                    "ratchet with its 95 % interval, quantiles of the drift and of the cycles "
                    "to tolerance, Sobol indices or rank correlations, a ranked table for "
                    "scan libraries.  Running the same command again resumes (only missing "
                    "cases run); `asperity study DIR` prints the summary of a finished or "
                    "interrupted study.",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("target", metavar="STUDY.toml|DIR",
                   help="a study file to run (or resume), or a study folder to summarise")
    p.add_argument("-o", "--output", metavar="DIR", default=None,
                   help="study folder (store, summary.md, figures); default: "
                        "STUDY-study in the current folder")
    add_cluster_arguments(p, "local worker processes (default: one per core; 0 runs in this "
                             "process, without a cluster)",
                          "run on an existing Dask cluster instead of a local one (default: "
                          "$ASPERITY_SCHEDULER if set)")
    p.add_argument("--batch-size", metavar="N", default=None,
                   help="cases per task (default: sized to about 1 s of work per task)")
    p.add_argument("--retry-failed", action="store_true",
                   help="run the stored failed cases again (e.g. after fixing a scan)")
    p.add_argument("--restart", action="store_true",
                   help="discard the cases stored in DIR and start over (needed when the "
                        "study file or a file it names changed since DIR was started)")
    p.add_argument("--export", metavar="FILE.parquet|FILE.csv", default=None,
                   help="also write one row per case (case_id, inputs, status, outputs)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.add_argument("--plot", action="store_true",
                   help="draw the figures into DIR: drift distribution, verdict over the two "
                        "most influential parameters, Sobol indices, ranking")
    p.set_defaults(func=main, outputs=[("--export", "export", False)], inputs=["target"])


def run(args) -> dict:
    """Python API of the command: the summary (the JSON object printed with --json)."""
    from ..study.run import export_folder, run_study_file, summarise_folder
    target = args.target
    if args.export is not None and os.path.splitext(str(args.export))[1].lower() not in (
            ".parquet", ".csv"):
        raise InputError(f"--export writes .parquet or .csv, got {os.path.basename(args.export)!r}")
    workers = whole_flag("--workers", args.workers, 0, 4096)
    batch = whole_flag("--batch-size", args.batch_size, 1, 1_000_000)
    if os.path.isdir(target):
        _check_study_folder(target)
        if args.output is not None or args.scheduler or workers is not None or batch \
                or args.retry_failed or args.restart:
            raise InputError(f"{target} is a study folder: it is summarised, not run; give "
                             f"the study file to run or resume it")
        summary = summarise_folder(target, plot=args.plot)
        folder = target
    else:
        if not str(target).lower().endswith(".toml"):
            raise InputError(f"{target!r}: give a study file (.toml) or a study folder")
        summary = run_study_file(target, args.output, scheduler=args.scheduler,
                                 workers=workers, batch_size=batch,
                                 retry_failed=args.retry_failed, plot=args.plot,
                                 restart=args.restart)
        folder = os.path.dirname(summary["store"])
    if args.export:
        summary["export"] = {"path": args.export, "rows": export_folder(folder, args.export)}
    return summary


def _check_study_folder(target: str) -> None:
    """A folder given as the target must be a study folder: say what it is otherwise."""
    from ..study.store import DB_NAME
    if os.path.isfile(os.path.join(target, DB_NAME)):
        return
    try:
        empty = not os.listdir(target)
    except OSError as exc:
        raise InputError(f"{target}: a folder that cannot be read ({exc.strerror})") from None
    if str(target).rstrip("/").lower().endswith(".toml"):
        what = "a folder named like a study file, not a study file"
    elif empty:
        what = "an empty folder, not a study folder"
    else:
        what = f"a folder that holds no study ({DB_NAME} missing)"
    raise InputError(f"{target}: {what}; give a study file (.toml) to run, or the folder of "
                     f"a study run before (-o) to summarise it")


def main(args) -> int:
    from ..study.text import lines
    summary = run(args)
    text = "\n".join(lines(summary))
    if "run" in summary:
        r = summary["run"]
        text = (f"ran {r['ran']} cases in {r['seconds']:.1f} s ({r['where']})\n" + text)
        if args.restart:
            text = (f"--restart: discarded the {r['discarded']} cases stored in "
                    f"{os.path.dirname(summary['store'])}\n" + text)
    written = [("summary", os.path.join(os.path.dirname(summary["store"]), "summary.md"))]
    written += [("figure", f) for f in summary.get("figures", [])]
    if "export" in summary:
        written.append((f"{summary['export']['rows']} rows", summary["export"]["path"]))
    shown = argparse.Namespace(**{**vars(args), "plot": None})   # figures listed above
    emit(shown, summary, text, tuple(written))
    return 0
