"""``roboracer-arena circuits``: build every real circuit (TUM racetrack database + the
bacinger GeoJSON circuits TUM does not cover) at 1:10 as ROS maps, in parallel, and
report the centreline-length accuracy of each raster against its scaled input.

Writes ``OUT/<id>/map.{png,yaml}``, ``centreline.csv`` and ``circuit.json`` per circuit,
and ``OUT/index.json``. Exit 2 if some circuit fails to build or has no single corridor."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..circuits import CircuitConfig, build_all
from ..circuits.report import CircuitFailure
from ..errors import InvalidArgumentError
from ..foundation.paths import writable_tracks_dir
from ..foundation.worker_pool import tqdm_progress
from . import EXIT_BAD_INPUT, EXIT_OK
from ._common import add_json_flag, print_json


def register(sub) -> None:
    p = sub.add_parser(
        "circuits",
        help="build the real circuits at 1:10 as ROS maps",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument(
        "--sources",
        type=Path,
        default=None,
        metavar="DIR",
        help="track-sources directory (default: $ROBORACER_ARENA_SOURCES, or ../shared/track-sources "
        "beside a source checkout)",
    )
    p.add_argument(
        "-o",
        "--out",
        type=Path,
        default=None,
        metavar="DIR",
        help="output directory (default: the package's tracks/circuits in a source checkout; "
        "required for an installed package)",
    )
    p.add_argument(
        "--resolution", type=float, default=0.05, metavar="M", help="map resolution in m/cell (default 0.05)"
    )
    p.add_argument("--jobs", type=int, default=None, metavar="N", help="worker threads (default: all cores)")
    p.add_argument("--only", nargs="+", metavar="ID", help="build only these circuit ids")
    add_json_flag(p)
    p.set_defaults(func=run, output_dirs=("out",))


def run(args: argparse.Namespace) -> int:
    if not (args.resolution > 0):
        raise InvalidArgumentError(f"--resolution must be > 0, got {args.resolution}")
    cfg = CircuitConfig(resolution=args.resolution)
    if args.out is None:
        args.out = writable_tracks_dir(None, "-o/--out") / "circuits"

    progress = tqdm_progress("circuits", "circuit")
    s = build_all(args.sources, args.out, cfg, jobs=args.jobs, only=args.only, progress=progress)
    ok = s.built == s.circuits and s.one_corridor == s.circuits
    if args.json:
        print_json(s)
        return EXIT_OK if ok else EXIT_BAD_INPUT
    print(f"{'id':<26}{'src':<9}{'lap m':>9}{'err %':>8}{'w mean':>8}{'w min':>7}{'narrow':>8}{'raster':>12}  notes")
    for r in s.results:
        if isinstance(r, CircuitFailure):
            print(f"{r.id:<26}{r.source:<9}  FAILED: {r.error}")
            continue
        err = "n/a" if r.length_error is None else f"{100 * r.length_error:.3f}"
        notes = []
        if r.grade_separated:
            notes.append("grade-separated crossing")
        if not r.one_corridor:
            notes.append("NOT one corridor")
        if r.unresolved_fraction > 0:
            notes.append(f"unresolved {100 * r.unresolved_fraction:.1f} %")
        raster = f"{r.raster.width_px}x{r.raster.height_px}"
        print(
            f"{r.id:<26}{r.source:<9}{r.lap_length_m:>9.1f}{err:>8}{r.width_mean_m:>8.2f}"
            f"{r.width_min_m:>7.2f}{100 * r.narrowed_fraction:>7.1f}%{raster:>12}  {'; '.join(notes)}"
        )
    me, mx = s.mean_length_error, s.max_length_error
    print(
        f"\n{s.built}/{s.circuits} built, {s.one_corridor} with one closed corridor; "
        f"length error mean {100 * (me or 0):.3f} %, max {100 * (mx or 0):.3f} % (paper 0.253 %, 0.924 %); "
        f"{s.seconds:.2f} s with {s.jobs} thread(s) (paper 43.72 s for 44)"
    )
    print(f"{len(s.skipped_as_covered)} bacinger circuits skipped as covered by TUM; wrote {args.out}/index.json")
    return EXIT_OK if ok else EXIT_BAD_INPUT
