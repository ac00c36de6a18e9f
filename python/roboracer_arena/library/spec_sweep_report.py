"""Typed records of the generated-track sweeps: one :class:`SweepRecord` per request (what
a worker returns beside the track's files), and the summaries written to ``sweep.json`` by
``tracks catalog --generate`` (:class:`GeneratedSweepSummary`) and ``tracks generate
--sweep`` (:class:`LibrarySummary`). Frozen, ``extra="forbid"``; fields in file order."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Literal

from ..foundation.frozen_model import FrozenModel

Outcome = Literal["accepted", "rejected", "failed"]


class SweepRecord(FrozenModel):
    """One request: its track id, generation seed, outcome, time and spec (as JSON);
    ``candidates_tried`` for an acceptance, ``violations`` for a rejection; ``k`` (its
    index in a sweep file) and ``kept`` (whether it is in the library) are set by the run."""

    k: int | None = None
    id: str
    seed: int
    outcome: Outcome
    seconds: float
    spec: dict[str, Any]
    candidates_tried: int | None = None
    violations: list[str] | None = None
    kept: bool | None = None


def count_outcome(records: Sequence[SweepRecord], outcome: Outcome) -> int:
    """Records with ``outcome``."""
    return sum(r.outcome == outcome for r in records)


class GeneratedSweepSummary(FrozenModel):
    """The packaged sweep (:mod:`.generated`): its grid, counts and every record."""

    sweep: dict[str, Any]
    specs_tried: int
    accepted: int
    rejected: int
    failed: int
    kept: int
    seconds: float
    records: list[SweepRecord]


class LibrarySummary(FrozenModel):
    """A sweep-file library run (:mod:`.sweep_run`); ``kept < count`` means the request
    budget ran out."""

    sweep: dict[str, Any]
    count: int
    kept: int
    requests: int
    accepted: int
    rejected: int
    failed: int
    workers: int
    executor: str
    seconds: float
    records: list[SweepRecord]
