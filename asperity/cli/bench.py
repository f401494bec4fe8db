"""``asperity bench``: speed figures of the closed form, the spring simulation and the
streamed facet reservoir."""
from __future__ import annotations

import os

from . import json_text

PARTS = ("closed-form", "springs", "facets", "microslip", "moreau", "study", "big-scan",
         "contact", "body")
#: largest --facets: the benchmark then takes 4.4 GB (peak RSS measured; estimated 7.5 GB)
MAX_FACETS_GRID = 8192


def add_parser(sub) -> None:
    p = sub.add_parser("bench", help="print speed figures",
                       description="Closed-form reservoir evaluations per second, "
                                   "spring-tip updates per second, (with --only facets or "
                                   "--facets N) facet-directions per second of the facet "
                                   "kernel against streamed NumPy and (with --only moreau) "
                                   "Moreau time steps per second of one sliding body with "
                                   "each friction law (compilation excluded); --only study: "
                                   "study cases per second of the per-case API, of the "
                                   "engine in this process and on 2 local Dask workers, "
                                   "and the seconds of a whole 1e6-case two-node study, "
                                   "with the path that solved the cases (closed form or "
                                   "exact); --only big-scan: time and peak memory of "
                                   "derive in tiles on synthetic float32 maps written to disk "
                                   "(--scan-sizes, deleted afterwards); --only contact: "
                                   "time, iterations and memory per pixel of the elastic "
                                   "contact solve against ContactMechanics and a plain "
                                   "NumPy Polonsky-Keer (periodic and free, a load curve), "
                                   "each solver in a child process, and whether the "
                                   "issue's targets are met; --only body: Moreau steps per "
                                   "second of a point mass on the ellipse and the star law "
                                   "against MuJoCo's box on a plane in the same run, "
                                   "MuJoCo's spinning disc (when sliding and spinning stop, "
                                   "v / (R omega) at the end) and the body solver's disc "
                                   "with 256 contact points (MuJoCo runs in a child process "
                                   "and is installed with pip when missing, unless "
                                   "--no-install).")
    p.add_argument("--seconds", type=float, default=1.0, help="time per measurement (s)")
    p.add_argument("--only", choices=PARTS, default=None,
                   help="run one benchmark only (default: closed-form and springs)")
    p.add_argument("--facets", type=int, default=None, metavar="N",
                   help="also run the facet benchmark on an N x N grid (2 N^2 facets; "
                        "default 2048 with --only facets; 2 to 8192, which takes about 4.4 GB "
                        "of memory)")
    p.add_argument("--directions", type=int, default=360,
                   help="sliding directions of the facet benchmark (default 360)")
    p.add_argument("--numpy-directions", type=int, default=8,
                   help="directions timed for the NumPy baseline (default 8)")
    p.add_argument("--workers", type=int, default=2,
                   help="local workers of the study benchmark (1 to 64)")
    p.add_argument("--scan-sizes", type=int, nargs="+", default=[2048, 4096, 8192],
                   metavar="N", help="--only big-scan: N x N maps (64 to 32768; 16384 "
                                     "writes 1 GB and takes minutes)")
    p.add_argument("--repeats", type=int, default=1, metavar="R",
                   help="--only big-scan / contact: runs per size or solver (1 to 20), to "
                        "see the spread (contact: the fastest is reported)")
    p.add_argument("--scan-dir", metavar="DIR", default=None,
                   help="--only big-scan: folder for the maps (default: a temporary folder)")
    p.add_argument("--contact-size", type=int, default=1024, metavar="N",
                   help="--only contact: N x N maps (64 to 4096; default 1024)")
    p.add_argument("--big", action="store_true",
                   help="--only contact: also a free 4096 x 4096 solve of asperity's solver "
                        "(memory per pixel; about 3.5 GB)")
    p.add_argument("--no-install", action="store_true",
                   help="--only body: do not pip install MuJoCo when it is missing (its "
                        "figures are then left out, saying so)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=main)


def main(args) -> int:
    from .. import bench
    from ..errors import check_int, check_range
    seconds = check_range("--seconds", args.seconds, 0.05, 600)
    # every flag in its widest range, whichever benchmark reads it (a value for a benchmark
    # not asked for was ignored: 'bench --workers -1' ran the default benchmarks)
    for flag, value, low, high in (
            ("--directions", args.directions, 1, 1_000_000),
            ("--numpy-directions", args.numpy_directions, 1, 1_000_000),
            ("--workers", args.workers, 1, 64), ("--repeats", args.repeats, 1, 20),
            ("--contact-size", args.contact_size, 64, 4096),
            *(("--scan-sizes", n, 64, 32768) for n in args.scan_sizes)):
        check_int(flag, value, low, high)
    parts = [args.only] if args.only else ["closed-form", "springs"]
    if args.facets is not None and "facets" not in parts:
        parts.append("facets")
    if "facets" in parts:                      # every request checked before any work
        n_grid = check_int("--facets", 2048 if args.facets is None else args.facets,
                           2, MAX_FACETS_GRID)
        n_dir = check_int("--directions", args.directions, 1, 1_000_000)
        n_np = check_int("--numpy-directions", args.numpy_directions, 1, 1_000_000)
        bench.check_facets_request(n_grid, n_dir, n_np)
    if "study" in parts:
        workers = check_int("--workers", args.workers, 1, 64)
    if "big-scan" in parts:
        sizes = [check_int("--scan-sizes", n, 64, 32768) for n in args.scan_sizes]
        repeats = check_int("--repeats", args.repeats, 1, 20)
        n_dir = check_int("--directions", args.directions, 8, 100_000)
        if args.scan_dir is not None and not os.path.isdir(args.scan_dir):
            from ..errors import InputError
            raise InputError(f"--scan-dir {args.scan_dir!r} is not a folder")
    if "contact" in parts:
        contact_n = check_int("--contact-size", args.contact_size, 64, 4096)
        repeats = check_int("--repeats", args.repeats, 1, 20)
    out = {}
    if "closed-form" in parts:
        out["closed_form"] = bench.bench_closed_form(seconds)
    if "springs" in parts:
        out["springs"] = bench.bench_springs(seconds)
    if "facets" in parts:
        out["facets"] = bench.bench_facets(n_grid, n_dir, n_np)
    if "moreau" in parts:
        out["moreau"] = bench.bench_moreau(seconds)
    if "microslip" in parts:
        out["microslip"] = bench.bench_microslip()
    if "study" in parts:
        from ..study.bench import bench_study
        out["study"] = bench_study(workers=workers)
    if "big-scan" in parts:
        out["big_scan"] = bench.bench_big_scan(sizes, n_dir, repeats, args.scan_dir)
    if "contact" in parts:
        out["contact"] = bench.bench_contact(contact_n, args.big, repeats)
    if "body" in parts:
        from ..dynamics.body_bench import bench_body
        out["body"] = bench_body(seconds, install=not args.no_install)
    if args.json:
        print(json_text(out))
        return 0
    for k, v in out.get("closed_form", {}).items():
        print(f"closed form, {k:9s}: {v['evaluations_per_second']:.3e} reservoir evaluations/s")
    for k, v in out.get("springs", {}).items():
        print(f"springs, {k:23s}: {v['updates_per_second']:.3e} spring-tip updates/s")
    if "facets" in out:
        print(bench.format_facets(out["facets"]))
    if "moreau" in out:
        print(bench.format_moreau(out["moreau"]))
    if "microslip" in out:
        print(bench.format_microslip(out["microslip"]))
    if "study" in out:
        from ..study.bench import format_study
        print(format_study(out["study"]))
    if "big_scan" in out:
        print(bench.format_big_scan(out["big_scan"]))
    if "contact" in out:
        print(bench.format_contact(out["contact"]))
    if "body" in out:
        from ..dynamics.body_bench import format_body
        print(format_body(out["body"]))
    return 0
