"""``python -m benchmarks library``: build every circuit at 1:10 into a temporary
directory and report the wall time (all cores, threads), the centreline-length error
of each raster against its scaled input, and the per-stage cost, beside the paper's
figures (44 circuits in 43.72 s; length error mean 0.253 %, max 0.924 %).

The time covers reading the sources, smoothing, narrowing, rasterising, measuring the
raster (the accuracy check) and writing every map; pool start-up is included."""

from __future__ import annotations

import argparse
import os
import tempfile
from pathlib import Path

from roboracer_arena.bench.output import BenchModel, add_bench_parser, write_json
from roboracer_arena.circuits.report import CircuitRaster

PAPER: dict[str, int | float] = {"circuits": 44, "seconds": 43.72, "mean_error_pct": 0.253, "max_error_pct": 0.924}
TARGET_SECONDS = 10.0


class CircuitRow(BenchModel):
    """One circuit of the build (for one that failed only ``id`` and ``source`` are known)."""

    id: str
    source: str
    lap_length_m: float | None
    length_error: float | None
    width_mean_m: float | None
    width_min_m: float | None
    narrowed_fraction: float | None
    grade_separated: bool | None
    raster: CircuitRaster | None
    seconds: float | None


class CpuMedians(BenchModel):
    """Median CPU seconds per circuit, and of its smoothing, narrowing and rasterising."""

    median: float
    raster_median: float


class LibraryResult(BenchModel):
    """``bench library``: counts, wall time, length errors (%), per-circuit cost and rows."""

    circuits: int
    built: int
    one_corridor: int
    jobs: int
    seconds: float
    mean_error_pct: float
    max_error_pct: float
    measured_circuits: int
    grade_separated: list[str]
    cpu_seconds_per_circuit: CpuMedians
    per_circuit: list[CircuitRow]
    paper: dict[str, int | float]


def register(kinds) -> None:
    p = add_bench_parser(kinds, "library", "circuit library build time and raster accuracy", __doc__)
    p.add_argument("--sources", type=Path, default=None, help="track-sources directory")
    p.add_argument("--jobs", type=int, default=None, help="threads (default: all cores)")
    p.add_argument("--resolution", type=float, default=0.05, help="m per cell (default 0.05)")
    p.set_defaults(func=_run_cli)


def run(sources: Path | None = None, jobs: int | None = None, resolution: float = 0.05) -> LibraryResult:
    from roboracer_arena.circuits import CircuitConfig, build_all

    with tempfile.TemporaryDirectory(prefix="rra-bench-library-") as tmp:
        s = build_all(sources, tmp, CircuitConfig(resolution=resolution), jobs=jobs or os.cpu_count() or 1)
    built = s.reports()
    res = LibraryResult(
        circuits=s.circuits,
        built=s.built,
        one_corridor=s.one_corridor,
        jobs=s.jobs,
        seconds=s.seconds,
        mean_error_pct=100 * (s.mean_length_error or 0),
        max_error_pct=100 * (s.max_length_error or 0),
        measured_circuits=sum(r.length_error is not None for r in built),
        grade_separated=s.grade_separated,
        cpu_seconds_per_circuit=CpuMedians(
            median=sorted(r.seconds for r in built)[len(s.results) // 2],
            raster_median=sorted(r.seconds_raster for r in built)[len(s.results) // 2],
        ),
        per_circuit=[
            CircuitRow.model_validate({k: getattr(r, k, None) for k in CircuitRow.model_fields}) for r in s.results
        ],
        paper=PAPER,
    )
    cpu = res.cpu_seconds_per_circuit
    print(f"{'':<28}{'ours':>12}{'paper':>12}")
    print(f"{'circuits built':<28}{res.built:>12}{PAPER['circuits']:>12}")
    print(
        f"{'wall time (s)':<28}{res.seconds:>12.2f}{PAPER['seconds']:>12.2f}   ({res.jobs} threads; target ≤ {TARGET_SECONDS:g} s)"
    )
    print(f"{'length error mean (%)':<28}{res.mean_error_pct:>12.3f}{PAPER['mean_error_pct']:>12.3f}")
    print(f"{'length error max (%)':<28}{res.max_error_pct:>12.3f}{PAPER['max_error_pct']:>12.3f}")
    print(
        f"{'per circuit, median (s)':<28}{cpu.median:>12.2f}"
        f"   (of which smoothing + narrowing + rasterising {cpu.raster_median:.2f} s)"
    )
    return res


def run_quick() -> LibraryResult:
    return run()


def _run_cli(args: argparse.Namespace) -> int:
    res = run(args.sources, args.jobs, args.resolution)
    write_json(args.json, res)
    return 0
