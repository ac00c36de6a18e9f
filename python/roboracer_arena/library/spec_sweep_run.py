"""``tracks generate``: build a library of N generated tracks from a sweep file on an
executor (local processes or Ray tasks), deterministically.

Requests run in waves of consecutive ``k`` (:mod:`.sweep`); the library is the first
``count`` acceptances in ``k`` order, so it does not depend on the number of workers or
the wave sizes. Workers return files; only this process writes. The whole library is
staged in a hidden sibling of ``outdir`` and swapped in by rename when it is complete
(:func:`~roboracer_arena.foundation.fileio.atomic_dir`): an interrupt (SIGINT, SIGTERM) or an error
at any moment leaves the previous ``outdir`` exactly as it was (or no ``outdir``) and no
staging folder. What ``outdir`` held besides this sweep's tracks, ``sweep.json`` and
``catalog.json`` (other sweeps' tracks, other files) is carried over by hard links.
Layout of ``outdir``::

    generated/<id>/{map.yaml, map.png, centreline.csv, spec.json, report.json}
    sweep.json      every request up to the last kept one, with its outcome
    catalog.json    the kept tracks, readable by ``tracks verify --catalog``
"""

from __future__ import annotations

import json
import math
import re
import time
from pathlib import Path

from .._core import __version__
from ..catalog.catalog_file import SCHEMA, Catalog, count_kinds
from ..catalog.directions import annotate_directions
from ..catalog.entry import CatalogMeta, SweepCounts
from ..distributed.executor import Executor
from ..errors import InvalidArgumentError
from ..foundation.fileio import atomic_dir, atomic_write_dir, atomic_write_text, check_output, link_tree
from ..foundation.worker_pool import Progress, map_ordered
from .generated import generate_files
from .index import _generated_entries
from .spec_sweep import SweepFile
from .spec_sweep_report import LibrarySummary, SweepRecord, count_outcome

#: Most requests held in memory at once (their files wait until the wave is complete).
MAX_WAVE = 256


def _wave_size(need: int, tried: int, accepted: int, workers: int, left: int) -> int:
    """Requests for the next wave: enough for ``need`` more acceptances at the rate seen so
    far (plus a quarter), at least one per worker, at most MAX_WAVE and the budget left."""
    rate = accepted / tried if tried and accepted else (0.1 if tried else 1.0)
    return max(1, min(left, MAX_WAVE, max(workers, math.ceil(1.25 * need / rate))))


def generate_library(
    sweep: SweepFile,
    count: int,
    outdir: str | Path,
    executor: Executor,
    max_requests: int | None = None,
    progress: Progress | None = None,
) -> LibrarySummary:
    """Generate ``count`` accepted tracks from ``sweep`` into ``outdir`` (see module doc),
    trying at most ``max_requests`` requests (default ``10 * count``). Returns the summary
    written to ``sweep.json``; ``kept < count`` means the budget ran out."""
    if count < 1:
        raise InvalidArgumentError(f"--count must be >= 1, got {count}")
    budget = max_requests if max_requests is not None else 10 * count
    if budget < count:
        raise InvalidArgumentError(f"--max-requests {budget} is below --count {count}")
    check_output(outdir, directory=True)
    with atomic_dir(outdir) as stage:
        _carry_over(Path(outdir), stage, sweep.name)
        return _generate_into(stage, sweep, count, budget, executor, progress)


def _carry_over(old: Path, stage: Path, name: str) -> None:
    """Hard-link (or copy) into ``stage`` what ``old`` holds that this run does not rewrite."""
    if not old.is_dir():
        return
    mine = re.compile(rf"^{re.escape(name)}-\d{{5,}}$")
    for item in old.iterdir():
        if item.name in ("sweep.json", "catalog.json"):
            continue
        if item.name == "generated" and item.is_dir():
            (stage / "generated").mkdir(exist_ok=True)
            for d in item.iterdir():
                if not mine.match(d.name):  # this sweep's tracks are generated afresh
                    link_tree(d, stage / "generated" / d.name)
        else:
            link_tree(item, stage / item.name)


def _generate_into(
    out: Path, sweep: SweepFile, count: int, budget: int, executor: Executor, progress: Progress | None
) -> LibrarySummary:
    t0 = time.perf_counter()
    gen = out / "generated"
    records: list[SweepRecord] = []
    kept: list[str] = []
    while len(kept) < count and len(records) < budget:
        start = len(records)
        n_acc = count_outcome(records, "accepted")
        size = _wave_size(count - len(kept), start, n_acc, executor.workers, budget - start)
        tasks = sweep.requests(start, start + size)
        for k, (rec, files) in enumerate(map_ordered(executor, generate_files, tasks, progress), start):
            keep = bool(files) and len(kept) < count
            if keep:
                atomic_write_dir(gen / rec.id, files)  # inside the stage
                kept.append(rec.id)
            records.append(rec.with_fields(k=k, kept=keep))
    if kept:  # requests after the last kept one depend on the wave size: leave them out
        last = next(r.k for r in records if r.id == kept[-1])
        records = records[: (last or 0) + 1]
    summary = LibrarySummary(
        sweep=sweep.model_dump(mode="json"),
        count=count,
        kept=len(kept),
        requests=len(records),
        accepted=count_outcome(records, "accepted"),
        rejected=count_outcome(records, "rejected"),
        failed=count_outcome(records, "failed"),
        workers=executor.workers,
        executor=type(executor).__name__,
        seconds=round(time.perf_counter() - t0, 2),
        records=records,
    )
    atomic_write_text(out / "sweep.json", json.dumps(summary.to_json_dict(), indent=2) + "\n")
    _write_catalog(out, kept, summary)
    return summary


def _write_catalog(out: Path, kept: list[str], summary: LibrarySummary) -> None:
    by_id = {e.id: e for e in _generated_entries(out)}
    entries = [by_id[i] for i in kept]
    meta = CatalogMeta(
        catalog_schema=SCHEMA,
        built_with=f"roboracer-arena {__version__} tracks generate",
        sources_note="generated tracks: 'map' is relative to this file's directory",
        counts=count_kinds(entries),
        sweep=SweepCounts.model_validate(summary.model_dump(include=set(SweepCounts.model_fields))),
    )
    cat = Catalog(entries=entries, meta=meta, path=out / "catalog.json")
    annotate_directions(cat)
    atomic_write_text(out / "catalog.json", cat.to_json())
