"""``roboracer-arena raceline MAP|ID``: the raceline of a track (ROS map YAML or catalog
id) inside its corridor less half the car's width and a safety margin, with its speed
profile under vehicle limits, written as TUM's CSV, ForzaETH's ``global_waypoints.json``
and a picture of the preview with the raceline coloured by speed.

Limits: the car's own by default (measured from the simulator: ``--measure-limits FILE``
measures and writes them again), a preset (``--limits f1tenth-racetracks``,
``--limits forzaeth``) or a JSON/YAML file with ``v_max``, ``ggv`` rows (v, ax_max,
ay_max) and ``ax_max_machines`` rows (v, ax); ``--v-max``, ``--ax-max``, ``--ay-max``,
``--ax-machines`` replace single numbers.

Exit codes: 0 written, 2 bad input (one line naming the file and the field)."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..errors import InvalidArgumentError
from ..foundation.fileio import check_output
from ..foundation.paths import writable_tracks_dir
from ..library.raceline_index import index_path
from ._common import add_json_flag, print_json

#: Accepted range of each numeric flag (inclusive).
RANGES: dict[str, tuple[float, float]] = {
    "margin": (0.0, 2.0),
    "v_max": (0.1, 100.0),
    "ax_max": (0.1, 100.0),
    "ay_max": (0.1, 100.0),
    "ax_machines": (0.1, 100.0),
    "step": (0.02, 2.0),
    "vehicle_width": (0.05, 2.0),
}


def register(sub) -> None:
    p = sub.add_parser(
        "raceline",
        help="minimum-curvature raceline and speed profile of a track (TUM CSV, ForzaETH JSON, picture)",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("map", metavar="MAP|ID", nargs="?", help="ROS map YAML or a catalog id")
    p.add_argument(
        "--out", type=Path, metavar="DIR", help="write raceline.csv, global_waypoints.json and raceline.png to DIR"
    )
    p.add_argument("--csv", type=Path, metavar="FILE.csv", help="write TUM's raceline CSV to FILE")
    p.add_argument("--forza", type=Path, metavar="FILE.json", help="write ForzaETH's global_waypoints.json to FILE")
    p.add_argument("--png", type=Path, metavar="FILE.png", help="write the preview with the raceline coloured by speed")
    p.add_argument("--mode", choices=("mincurv", "mintime"), default="mincurv", help="line to plan (default mincurv)")
    p.add_argument(
        "--limits",
        metavar="PRESET|FILE",
        help="vehicle limits: car (default, measured), f1tenth-racetracks, forzaeth, or a JSON/YAML file",
    )
    p.add_argument("--v-max", type=float, help="top speed (m/s), replacing the limits'")
    p.add_argument("--ax-max", type=float, help="longitudinal tyre limit (m/s^2) at every speed")
    p.add_argument("--ay-max", type=float, help="lateral tyre limit (m/s^2) at every speed")
    p.add_argument("--ax-machines", type=float, help="drivetrain acceleration limit (m/s^2) at every speed")
    p.add_argument(
        "--margin", type=float, default=None, help="safety margin beyond half the car's width (m, default 0.10)"
    )
    p.add_argument("--vehicle-width", type=float, default=None, help="car width (m, default the simulator car's)")
    p.add_argument("--step", type=float, default=0.2, help="spacing of the raceline points (m, default 0.2)")
    p.add_argument(
        "--measure-limits",
        type=Path,
        metavar="FILE.json",
        help="drive the simulator's car to measure its limits (ggv, motor curve, v_max) and write them to FILE",
    )
    p.add_argument(
        "--catalog",
        metavar="SELECTION",
        help="library job: plan and race every catalog track of SELECTION (all, circuits, recorded, generated, "
        "or ids) into tracks/racelines.json; staged per track, a rerun skips what is recorded",
    )
    p.add_argument("--redo", action="store_true", help="with --catalog: plan again tracks already recorded")
    p.add_argument(
        "--tracks",
        type=Path,
        metavar="DIR",
        help="with --catalog: the tracks directory whose racelines.json is written (default: the package's "
        "tracks/ in a source checkout; required for an installed package)",
    )
    add_json_flag(p)
    p.set_defaults(func=run, output_dirs=("out",))


def run(args: argparse.Namespace) -> int:
    # Here, not at the top: every command's parser is built at start-up, and these load
    # scipy and the env stack (measure), and PIL and pxr (the picture).
    from ..raceline.export import raceline_csv_text, raceline_forza_text, write_outputs
    from ..raceline.limits import limits_json, resolve_limits
    from ..raceline.measure import measure_limits
    from ..raceline.plan import DEFAULT_MARGIN, plan_raceline
    from ..raceline.source import resolve_track
    from ..render.formats import image_format
    from ..render.raceline_view import raceline_picture

    for dest, (lo, hi) in RANGES.items():
        v = getattr(args, dest)
        if v is not None and not lo <= v <= hi:
            raise InvalidArgumentError(f"--{dest.replace('_', '-')} must be in [{lo:g}, {hi:g}], got {v}")

    if args.measure_limits is not None:
        check_output(args.measure_limits)
        lim = measure_limits()
        write_outputs([(args.measure_limits, limits_json(lim))])
        if args.json:
            print_json(lim.to_json_dict())
        else:
            print(f"wrote {args.measure_limits}: v_max {lim.v_max:.2f} m/s, {len(lim.ggv)} ggv rows")
        if args.map is None:
            return 0
    if args.catalog is not None:
        return _catalog_job(args)
    if args.map is None:
        raise InvalidArgumentError("give a map YAML or a catalog id (or only --measure-limits FILE)")
    outputs = _outputs(args)
    if "png" in outputs:
        image_format(outputs["png"])  # a wrong extension is bad input, before any work
    lim = resolve_limits(args.limits).with_overrides(
        v_max=args.v_max, ax_max=args.ax_max, ay_max=args.ay_max, ax_machines=args.ax_machines
    )
    track, map_path = resolve_track(args.map)
    for out in outputs.values():
        check_output(out, inputs=[map_path])
    line = plan_raceline(
        track,
        lim,
        mode=args.mode,
        margin=DEFAULT_MARGIN if args.margin is None else args.margin,
        vehicle_width=args.vehicle_width,
        step=args.step,
    )
    files: list[tuple[Path, str | bytes]] = []
    if "csv" in outputs:
        files.append((outputs["csv"], raceline_csv_text(line)))
    if "forza" in outputs:
        files.append((outputs["forza"], raceline_forza_text(line, track)))
    if "png" in outputs:
        title = (
            f"{track.name}: {args.mode} raceline, {line.length:.1f} m, planned lap {line.lap_time:.2f} s ({lim.name})"
        )
        files.append((outputs["png"], raceline_picture(map_path, track, line.xy, line.vx, title, outputs["png"])))
    written = write_outputs(files) if files else []
    summary = {**line.summary(), "outputs": [str(p) for p in written]}
    if args.json:
        print_json(summary)
    else:
        print(
            f"{track.name}: {args.mode} raceline {line.length:.1f} m, planned lap {line.lap_time:.2f} s "
            f"with limits {lim.name} (v {line.vx.min():.2f}-{line.vx.max():.2f} m/s, "
            f"wall clearance >= {line.min_clearance:.3f} m) in {line.timings['total']:.2f} s"
        )
        for p in written:
            print(f"  wrote {p}")
    return 0


def _catalog_job(args: argparse.Namespace) -> int:
    from ..catalog.catalog_file import load_catalog
    from ..library.racelines import build_racelines

    path = index_path(writable_tracks_dir(args.tracks, "--tracks"))  # never into an installed package
    ids = [e.id for e in load_catalog().select_many(args.catalog.split(","))]
    done = [0]

    def report(rec) -> None:
        done[0] += 1
        d = rec.driver
        drive = (
            f"driver plan {d.planned_s:.2f} s, driven {d.driven_s if d.driven_s is not None else '-'}"
            f"{'' if d.clean else ' CONTACT'}"
            if d
            else ""
        )
        what = rec.error or f"{rec.length_m:.1f} m, planned lap {rec.lap_time_s:.2f} s; {drive}"
        if not args.json:
            print(f"[{done[0]}/{len(ids)}] {rec.id}: {what}", flush=True)

    index = build_racelines(ids, path=path, redo=args.redo, progress=report)
    recs = [r for r in index.records if r.id in set(ids)]
    clean = sum(1 for r in recs if r.driver and r.driver.clean)
    within = sum(1 for r in recs if r.driver and r.driver.within_5pct)
    summary = {
        "tracks": len(recs),
        "planned": sum(r.error is None for r in recs),
        "driver_clean": clean,
        "driver_within_5pct": within,
    }
    if args.json:
        print_json(summary)
    else:
        print(
            f"{summary['planned']}/{len(recs)} tracks planned; the racing driver lapped {clean} cleanly, "
            f"{within} within 5 % of its plan"
        )
    return 0


def _outputs(args: argparse.Namespace) -> dict[str, Path]:
    outs: dict[str, Path] = {}
    if args.out is not None:
        outs = {
            "csv": args.out / "raceline.csv",
            "forza": args.out / "global_waypoints.json",
            "png": args.out / "raceline.png",
        }
    for key in ("csv", "forza", "png"):
        if getattr(args, key) is not None:
            outs[key] = getattr(args, key)
    return outs
