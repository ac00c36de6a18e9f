"""The paper-reproduction benchmarks, peer comparisons and baselines of RoboRacer Arena,
run from a checkout (they are not in the wheel): ``python -m benchmarks KIND`` (or
``make bench`` for ``all``). Each ``<kind>.py`` provides ``register(subparsers)`` (its CLI)
and ``run_quick()`` (used by ``all``), prints a table and compares with the paper or a
peer simulator. The wheel's own ``roboracer-arena bench env|physics`` measure a user's
machine and are reused here (:mod:`roboracer_arena.bench`).

Also here: their inputs (``data/``), the DE / random baseline constructors
(:mod:`benchmarks.baselines`), one-off evidence scripts (``python -m benchmarks.<script>``)
and the Rust criterion benches (``criterion/``, run by ``cargo bench -p arena_core``)."""

from __future__ import annotations

from pathlib import Path

#: The checkout this package lives in (its parent directory).
CHECKOUT = Path(__file__).resolve().parent.parent
DATA_DIR = Path(__file__).resolve().parent / "data"


def bench_data(name: str) -> Path:
    """A benchmark input in this checkout (``benchmarks/data/<name>``)."""
    return DATA_DIR / name
