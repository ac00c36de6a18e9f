"""The generated part of the track library: a documented sweep of requirement specs and
seeds, each turned into a validated map with :func:`roboracer_arena.generate_track`.

The sweep crosses eight venues (lap length, corridor width, hall size: ``VENUES``) with
six feature mixes and directions (``FEATURES``) and two seeds (``SEEDS``): 96 requests.
The first ``count`` acceptances are kept, every seed-0 one before any seed-1 one. Each
track goes to ``tracks/generated/<id>/`` with its map, centreline, spec and report. The
folder is built in a stage and swapped in whole, so an interrupt (SIGINT, SIGTERM) or an
error at any moment leaves the previous one as it was."""

from __future__ import annotations

import json
import tempfile
import time
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from ..distributed.executor import Executor
from ..errors import InvalidArgumentError
from ..foundation.fileio import atomic_update_dir, atomic_write_dir, atomic_write_text, check_output
from ..foundation.worker_pool import Progress, local_unless, map_ordered
from ..generate import generate_track, write_outputs
from ..generate.outcomes import Acceptance, Rejection
from ..generate.outputs import centreline_csv
from ..spec import TrackSpec
from .spec_sweep import GridSweep, SweepRequest
from .spec_sweep_report import GeneratedSweepSummary, SweepRecord, count_outcome

#: (lap length m, corridor width m, hall x m, hall y m): small to large venues.
VENUES = [
    (40.0, 1.2, 12.0, 10.0),
    (50.0, 1.5, 15.0, 12.0),
    (60.0, 1.5, 20.0, 15.0),
    (70.0, 2.0, 25.0, 20.0),
    (80.0, 1.5, 25.0, 18.0),
    (100.0, 1.5, 30.0, 20.0),
    (120.0, 2.0, 35.0, 25.0),
    (150.0, 1.8, 40.0, 30.0),
]
#: (hairpins, chicanes, sweepers, direction)
FEATURES = [
    (0, 0, 0, "counterclockwise"),
    (2, 0, 0, "clockwise"),
    (1, 1, 0, "counterclockwise"),
    (0, 1, 1, "clockwise"),
    (3, 1, 0, "counterclockwise"),
    (2, 1, 1, "clockwise"),
]
SEEDS = (0, 1)
#: Vertex spacing (m) of the committed centreline CSVs.
CSV_SPACING = 0.25


def _track_id(f: Mapping[str, Any]) -> str:
    turn = "clo" if f["direction"] == "clockwise" else "ccw"
    return (
        f"gen-l{int(f['lap_length_m']):03d}-w{int(round(f['corridor_width_m'] * 10)):02d}"
        f"-h{f['hairpins']}c{f['chicanes']}s{f['sweepers']}-{turn}-s{f['seed']}"
    )


#: The library's sweep: venues x feature mixes x seeds.
GENERATED_SWEEP = GridSweep(
    axes=(
        [{"lap_length_m": lap, "corridor_width_m": w, "hall_x_m": hx, "hall_y_m": hy} for lap, w, hx, hy in VENUES],
        [{"hairpins": h, "chicanes": c, "sweepers": s, "direction": d} for h, c, s, d in FEATURES],
        [{"seed": seed} for seed in SEEDS],
    ),
    name=_track_id,
)


def sweep() -> Iterator[SweepRequest]:
    """``(id, spec, seed)`` in sweep order."""
    return iter(GENERATED_SWEEP.requests())


def generate_files(task: tuple[str, TrackSpec, int]) -> tuple[SweepRecord, dict[str, bytes]]:
    """Worker side of one request ``(id, spec, seed)``: run :func:`generate_track` and return
    its record and, for an acceptance, its files (name -> bytes: map, centreline, spec,
    report). Files go back to the caller, which alone writes them (no shared disk needed,
    and a retried task cannot leave a partial directory)."""
    tid, spec, seed = task
    out = generate_track(spec, seed)
    rec: dict[str, Any] = {
        "id": tid,
        "seed": seed,
        "outcome": out.kind,
        "seconds": round(out.seconds, 3),
        "spec": json.loads(spec.model_dump_json()),
    }
    files: dict[str, bytes] = {}
    if isinstance(out, Acceptance):
        with tempfile.TemporaryDirectory(prefix="rra-gen-") as tmp:
            paths = write_outputs(out, tmp, stem="map")
            # The committed centreline is thinned to ~CSV_SPACING m (the map is the reference).
            line = np.asarray(out.centreline, float)
            step = np.median(np.hypot(*np.diff(line, axis=0).T))
            every = max(1, int(round(CSV_SPACING / step))) if step > 0 else 1
            atomic_write_text(paths["centreline_csv"], centreline_csv(line[::every], spec.corridor_width_m))
            files = {p.name: p.read_bytes() for p in paths.values()}
        rec["candidates_tried"] = out.candidates_tried
    elif isinstance(out, Rejection):
        rec["violations"] = out.violations
    return SweepRecord(**rec), files


def build_generated(
    outdir: str | Path,
    count: int = 60,
    jobs: int = 1,
    progress: Progress | None = None,
    executor: Executor | None = None,
) -> GeneratedSweepSummary:
    """Run the whole sweep on ``executor`` (default a local pool of ``jobs`` processes),
    keep the first ``count`` acceptances, write ``outdir/sweep.json`` with every outcome,
    and return it. The folder is staged and swapped in whole (:func:`staged_generated`):
    an interrupt or an error leaves the previous ``outdir`` as it was."""
    with staged_generated(outdir) as stage:
        return generate_into(stage, count, jobs, progress, executor)


@contextmanager
def staged_generated(outdir: str | Path, also: Callable[[], object] | None = None) -> Iterator[Path]:
    """A stage for the generated folder ``outdir``, swapped in with ``also`` when the block
    succeeds (:func:`~roboracer_arena.foundation.fileio.atomic_update_dir`): what ``outdir`` has that
    is not this sweep's (other folders and files) is kept; this sweep's tracks are all
    written afresh, so one it no longer keeps (or no longer tries) is gone."""
    check_output(outdir, directory=True)
    with atomic_update_dir(outdir, {tid for tid, _, _ in sweep()} | {"sweep.json"}, also) as stage:
        yield stage


def generate_into(
    stage: Path,
    count: int = 60,
    jobs: int = 1,
    progress: Progress | None = None,
    executor: Executor | None = None,
    max_requests: int | None = None,
) -> GeneratedSweepSummary:
    """The body of :func:`build_generated`, writing into the (staged) folder ``stage``;
    ``max_requests``: try only the sweep's first ones (default all)."""
    t0 = time.perf_counter()
    tasks = list(sweep())
    if max_requests is not None:
        if max_requests < 1:
            raise InvalidArgumentError(f"--max-requests must be >= 1, got {max_requests}")
        tasks = tasks[:max_requests]
    with local_unless(executor, jobs) as ex:
        results = map_ordered(ex, generate_files, tasks, progress)
    # Every seed-0 acceptance first (one per spec: the widest spread), then seed 1.
    accepted = sorted((r for r, _ in results if r.outcome == "accepted"), key=lambda r: r.seed)
    kept = {r.id for r in accepted[:count]}
    for rec, files in results:  # a dropped acceptance leaves no directory (the stage has none)
        if rec.id in kept:
            atomic_write_dir(stage / rec.id, files)
    recs = [r.with_fields(kept=r.id in kept) for r, _ in results]
    summary = GeneratedSweepSummary(
        sweep={"venues": VENUES, "features": FEATURES, "seeds": list(SEEDS)},
        specs_tried=len(recs),
        accepted=len(accepted),
        rejected=count_outcome(recs, "rejected"),
        failed=count_outcome(recs, "failed"),
        kept=len(kept),
        seconds=round(time.perf_counter() - t0, 2),
        records=recs,
    )
    atomic_write_text(stage / "sweep.json", json.dumps(summary.to_json_dict(), indent=2) + "\n")
    return summary
