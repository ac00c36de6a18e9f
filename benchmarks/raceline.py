"""``python -m benchmarks raceline`` (or ``python -m benchmarks.raceline``; ``all`` runs three maps): our
minimum-curvature racelines against the ones f1tenth_racetracks publishes.

On each of the f1tenth_racetracks maps that ship a ``*_raceline.csv`` (TUM's optimiser,
v_max 8 m/s, 10 m/s^2 lateral), with the same limits (the ``f1tenth-racetracks`` preset,
whose longitudinal envelope ``--fit-preset`` reads from their files):

* **published**: their lap time, from their ``s_m`` and ``vx_mps``;
* **their line, our profile**: our speed profile on their line's geometry, so the lines
  compare without the profiles' differences;
* **ours**: our line on our corridor (the catalog map's walls less half the car's width
  and the margin) with our profile; the target is ``ours <= published + 1 %``;
* **seconds**: the time to plan it (one core).

``--drive`` adds the laps in our physics with the car's own limits: the planned lap with
the full measured limits, the racing driver's plan (the limits derated for it,
:mod:`roboracer_arena.raceline.driver`) and its driven flying lap, and the reference
pure-pursuit centreline lap (``drivers.drive_laps``, reference settings).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from roboracer_arena.bench.output import BenchModel, add_bench_parser, write_json
from roboracer_arena.catalog.catalog_file import load_catalog
from roboracer_arena.foundation.paths import sources_dir
from roboracer_arena.raceline import plan_raceline, preset, read_tum_csv, speed_profile
from roboracer_arena.raceline.geometry import closed_path
from roboracer_arena.raceline.limits import VehicleLimits, limits_json
from roboracer_arena.raceline.source import resolve_track

TARGET_RATIO = 1.01
PRESET_FILE = Path(__file__).resolve().parent.parent / "python/roboracer_arena/raceline/presets/f1tenth-racetracks.json"


class RacelineRow(BenchModel):
    """One reference map (lap times in s, lengths in m)."""

    id: str
    published_s: float
    published_length_m: float
    their_line_our_profile_s: float
    ours_s: float
    ours_length_m: float
    ratio: float
    seconds: float
    min_wall_clearance_m: float
    car_planned_s: float | None = None
    driver_planned_s: float | None = None
    driven_s: float | None = None
    driven_clean: bool | None = None
    centreline_pp_s: float | None = None


class RacelineResult(BenchModel):
    """``bench raceline``: the rows, the worst ratio and how many meet the target."""

    limits: str
    margin_m: float
    target_ratio: float
    rows: list[RacelineRow]
    worst_ratio: float
    within_target: int
    median_seconds: float
    seconds_per_500m_max: float


def reference_files(sources: Path | None = None) -> list[tuple[str, Path]]:
    """``(catalog id, published raceline CSV)`` for every catalog map from f1tenth_racetracks that has one."""
    base = sources_dir(sources, "bench raceline")
    out = []
    for e in load_catalog().select_many("all"):
        path = e.source.path if e.source else ""
        if path.startswith("f1tenth-racetracks/"):
            folder = base / Path(path).parent
            found = sorted(folder.glob("*_raceline.csv"))
            if found:
                out.append((e.id, found[0]))
    return out


def fit_f1tenth_limits(files: list[Path]) -> VehicleLimits:
    """The limits their files show: v_max and the lateral peak, braking as the largest
    deceleration on the straights, the motor curve as the largest acceleration per 0.25 m/s
    on the straights (|ay| < 0.5 m/s^2), held flat below the slowest speed seen."""
    rows = []
    for f in files:
        t = read_tum_csv(f)
        rows.append(np.column_stack([t.vx[:-1], np.abs(t.kappa[:-1]) * t.vx[:-1] ** 2, t.ax[:-1]]))
    v, ay, ax = np.vstack(rows).T
    straight = ay < 0.5
    brake = float(-ax[straight & (ax < 0)].min())
    machines = []
    for lo in np.arange(0.0, float(v.max()), 0.25):
        m = straight & (ax > 0) & (v >= lo) & (v < lo + 0.25)
        if m.sum() >= 3:
            machines.append((round(float(lo + 0.125), 3), round(float(ax[m].max()), 3)))
    machines.insert(0, (0.0, machines[0][1]))
    return VehicleLimits(
        name="f1tenth-racetracks",
        v_max=round(float(v.max()), 3),
        ggv=[(0.0, round(brake, 3), round(float(ay.max()), 3))],
        ax_max_machines=machines,
        dyn_model_exp=1.0,
        source=(
            f"fitted by benchmarks/raceline.py --fit-preset from the {len(files)} f1tenth_racetracks "
            "*_raceline.csv files: v_max and peak lateral acceleration; braking = largest deceleration, "
            "motor curve = largest acceleration per 0.25 m/s, both where |ay| < 0.5 m/s^2"
        ),
    )


def run(
    ids: list[str] | None = None, margin: float = 0.10, drive: bool = False, sources: Path | None = None
) -> RacelineResult:
    lim = preset("f1tenth-racetracks")
    rows = []
    for tid, csv in reference_files(sources):
        if ids and tid not in ids:
            continue
        pub = read_tum_csv(csv)
        theirs = closed_path(np.column_stack([pub.x[:-1], pub.y[:-1]]), 0.2)
        their_prof = speed_profile(theirs.kappa, theirs.ds, lim)
        track, _ = resolve_track(tid)
        t0 = time.process_time()
        ours = plan_raceline(track, lim, margin=margin)
        secs = time.process_time() - t0
        row = dict(
            id=tid,
            published_s=round(pub.lap_time, 3),
            published_length_m=round(pub.length, 2),
            their_line_our_profile_s=round(their_prof.lap_time, 3),
            ours_s=round(ours.lap_time, 3),
            ours_length_m=round(ours.length, 2),
            ratio=round(ours.lap_time / pub.lap_time, 4),
            seconds=round(secs, 3),
            min_wall_clearance_m=round(ours.min_clearance, 3),
        )
        if drive:
            row.update(_drive(tid, track))
        rows.append(RacelineRow(**row))
        _print_row(rows[-1])
    ratios = [r.ratio for r in rows]
    per500 = [r.seconds * 500.0 / r.ours_length_m for r in rows]
    return RacelineResult(
        limits=lim.name,
        margin_m=margin,
        target_ratio=TARGET_RATIO,
        rows=rows,
        worst_ratio=max(ratios) if ratios else 0.0,
        within_target=sum(r <= TARGET_RATIO for r in ratios),
        median_seconds=float(np.median([r.seconds for r in rows])) if rows else 0.0,
        seconds_per_500m_max=round(max(per500), 3) if per500 else 0.0,
    )


def _drive(tid: str, track) -> dict:
    """The racing driver on its line (the car's limits derated, :mod:`raceline.driver`):
    its plan and its flying lap (the second from a standing start), the plan with the
    car's full limits, and the reference pure pursuit's centreline lap."""
    from roboracer_arena.drivers import drive_laps
    from roboracer_arena.raceline.driver import drive_raceline, plan_for_driver

    full = plan_raceline(track, preset("car"))
    line = plan_for_driver(track)
    r = drive_raceline(tid, line, 2)
    pp = drive_laps(tid, 1)
    return {
        "car_planned_s": round(full.lap_time, 3),
        "driver_planned_s": round(line.lap_time, 3),
        "driven_s": r.lap_times[-1] if r.completed and r.lap_times else None,
        "driven_clean": bool(r.completed),
        "centreline_pp_s": pp.lap_times[0] if pp.lap_times and pp.completed else None,
    }


HEADER = f"{'track':28s} {'published':>9s} {'their/our':>9s} {'ours':>8s} {'ratio':>7s} {'plan s':>7s} {'clear':>6s}"


def _print_row(r: RacelineRow) -> None:
    line = (
        f"{r.id:28s} {r.published_s:9.2f} {r.their_line_our_profile_s:9.2f} {r.ours_s:8.2f} "
        f"{r.ratio:7.4f} {r.seconds:7.2f} {r.min_wall_clearance_m:6.3f}"
    )
    if r.driver_planned_s is not None:
        d = f"{r.driven_s:.2f}" if r.driven_s is not None else "-"
        c = f"{r.centreline_pp_s:.2f}" if r.centreline_pp_s is not None else "-"
        line += (
            f" | car plan {r.car_planned_s:6.2f} driver plan {r.driver_planned_s:6.2f} driven {d:>6s} "
            f"{'clean' if r.driven_clean else 'CONTACT'} centreline pp {c:>6s}"
        )
    print(line, flush=True)


def markdown(res: RacelineResult) -> str:
    """The tables for BENCHMARKS.md."""
    out = [
        "| track | published (s) | their line, our profile (s) | ours (s) | ours / published | plan time (s) |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for r in res.rows:
        out.append(
            f"| {r.id} | {r.published_s:.2f} | {r.their_line_our_profile_s:.2f} | {r.ours_s:.2f} | "
            f"{r.ratio:.4f} | {r.seconds:.2f} |"
        )
    if any(r.driver_planned_s is not None for r in res.rows):
        out += [
            "",
            "| track | planned, car limits (s) | racing driver: plan (s) | driven flying lap (s) | clean "
            "| pure pursuit, centreline (s) |",
            "|---|---:|---:|---:|---|---:|",
        ]
        for r in res.rows:
            d = f"{r.driven_s:.2f}" if r.driven_s is not None else "-"
            c = f"{r.centreline_pp_s:.2f}" if r.centreline_pp_s is not None else "-"
            out.append(
                f"| {r.id} | {r.car_planned_s:.2f} | {r.driver_planned_s:.2f} | {d} | "
                f"{'yes' if r.driven_clean else 'no'} | {c} |"
            )
    return "\n".join(out)


def register(kinds) -> None:
    p = add_bench_parser(kinds, "raceline", "our racelines against f1tenth_racetracks' published ones", __doc__)
    _add_args(p)


def _add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("--ids", nargs="*", help="catalog ids to run (default: every reference map)")
    p.add_argument("--margin", type=float, default=0.10, help="safety margin beyond half the car's width (m)")
    p.add_argument("--drive", action="store_true", help="also drive the racing driver and the centreline pure pursuit")
    p.add_argument(
        "--driver-scale", type=float, default=0.8, help="share of the car's measured limits the driver plans with"
    )
    p.add_argument(
        "--fit-preset", action="store_true", help="refit the f1tenth-racetracks preset from their files first"
    )
    p.add_argument("--markdown", action="store_true", help="print the table as Markdown too")
    p.add_argument("--sources", type=Path, help="the track-sources folder")
    p.set_defaults(func=_main)


def _main(args: argparse.Namespace) -> int:
    if args.fit_preset:
        from roboracer_arena.foundation.fileio import atomic_write_text

        lim = fit_f1tenth_limits([f for _, f in reference_files(args.sources)])
        atomic_write_text(PRESET_FILE, limits_json(lim))
        print(f"wrote {PRESET_FILE}")
    print(HEADER)
    res = run(args.ids, args.margin, args.drive, args.sources)
    print(
        f"{res.within_target}/{len(res.rows)} within {100 * (TARGET_RATIO - 1):.0f} % of the published lap time; "
        f"worst ratio {res.worst_ratio:.4f}; median plan time {res.median_seconds:.2f} s; "
        f"at most {res.seconds_per_500m_max:.2f} s per 500 m"
    )
    if args.markdown:
        print(markdown(res))
    write_json(args.json, res)
    return 0


def run_quick() -> RacelineResult:
    return run(["racetracks-spielberg", "racetracks-monza", "racetracks-oschersleben"])


if __name__ == "__main__":
    import sys

    parser = argparse.ArgumentParser(prog="python -m benchmarks.raceline", description=__doc__)
    parser.add_argument("--json", metavar="FILE", type=Path, help="write the results to FILE as JSON")
    _add_args(parser)
    sys.exit(_main(parser.parse_args()))
