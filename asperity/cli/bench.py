"""``asperity bench``: speed figures of the closed form, the spring simulation and the
streamed facet reservoir."""
from __future__ import annotations

from . import json_text

PARTS = ("closed-form", "springs", "facets", "microslip", "moreau", "study")
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
                                   "study cases per second, a serial loop against 2 local "
                                   "Dask workers.")
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
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=main)


def main(args) -> int:
    from .. import bench
    from ..errors import check_range
    seconds = check_range("--seconds", args.seconds, 0.05, 600)
    parts = [args.only] if args.only else ["closed-form", "springs"]
    if args.facets is not None and "facets" not in parts:
        parts.append("facets")
    if "facets" in parts:                      # every request checked before any work
        n_grid = int(check_range("--facets", 2048 if args.facets is None else args.facets,
                                 2, MAX_FACETS_GRID))
        n_dir = int(check_range("--directions", args.directions, 1, 1_000_000))
        n_np = int(check_range("--numpy-directions", args.numpy_directions, 1, 1_000_000))
        bench.check_facets_request(n_grid, n_dir, n_np)
    if "study" in parts:
        workers = int(check_range("--workers", args.workers, 1, 64))
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
    return 0
