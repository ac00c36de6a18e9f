"""``roboracer-arena bench KIND``: benchmarks that print a table beside the paper's
figures and can write JSON. Each kind lives in ``roboracer_arena.bench.<kind>`` and
exposes ``register(subparsers)``; ``all`` runs every kind with its quick defaults."""

from __future__ import annotations

import argparse
import json
from importlib import import_module
from pathlib import Path

from ..fileio import atomic_write_text

# Benchmark kinds, in the order `bench all` runs them.
KINDS: list[str] = [
    "build",
    "physics",
    "env",
    "fidelity",
    "constructors",
    "parser",
    "library",
    "ros2",
    "generalisation",
    "ray",
]


def register(sub) -> None:
    p = sub.add_parser("bench", help="run benchmarks and compare with the paper", description=__doc__)
    kinds = p.add_subparsers(dest="kind", metavar="KIND", required=True)
    for kind in KINDS:
        import_module(f"roboracer_arena.bench.{kind}").register(kinds)
    a = kinds.add_parser("all", help="run every benchmark with quick defaults")
    a.add_argument("--json", metavar="FILE", type=Path, help="write all results to FILE as JSON")
    a.set_defaults(func=_run_all)


def _run_all(args: argparse.Namespace) -> int:
    results = {}
    for kind in KINDS:
        module = import_module(f"roboracer_arena.bench.{kind}")
        print(f"\n== bench {kind}")
        results[kind] = module.run_quick().to_json_dict()
    if args.json:
        atomic_write_text(args.json, json.dumps(results, indent=2))
        print(f"\nwrote {args.json}")
    return 0
