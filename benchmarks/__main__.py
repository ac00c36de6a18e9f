"""``python -m benchmarks KIND``: the benchmarks of the paper and the peer comparisons,
each printing a table beside the published figures and able to write JSON; ``all`` runs
every kind with its quick defaults (``make bench``) but ``peer``, which needs F1TENTH Gym
installed by hand. ``env`` and ``physics`` are the wheel's
own machine benchmarks (``roboracer-arena bench``) with the paper's and F1TENTH Gym's
figures beside them."""

from __future__ import annotations

import argparse
import json
import sys
from importlib import import_module
from pathlib import Path

from roboracer_arena.cli._common import check_numeric_flags, check_outputs, raise_interrupt_on_sigterm
from roboracer_arena.errors import ArenaError
from roboracer_arena.foundation.fileio import atomic_write_text

# Benchmark kinds, in the order `all` runs them.
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
    "raceline",
]
# Kinds `all` leaves out: they need a peer installed by hand (F1TENTH Gym is not on PyPI), or
# the `physx` extra and minutes of CPU (engines: our engine and PhysX, open loop).
BY_HAND: list[str] = ["peer", "engines"]


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__)
    kinds = p.add_subparsers(dest="kind", metavar="KIND", required=True)
    for kind in KINDS + BY_HAND:
        import_module(f"benchmarks.{kind}").register(kinds)
    a = kinds.add_parser("all", help="run every benchmark with quick defaults")
    a.add_argument("--json", metavar="FILE", type=Path, help="write all results to FILE as JSON")
    a.set_defaults(func=_run_all)
    return p


def _run_all(args: argparse.Namespace) -> int:
    results = {}
    for kind in KINDS:
        module = import_module(f"benchmarks.{kind}")
        print(f"\n== bench {kind}")
        results[kind] = module.run_quick().to_json_dict()
    if args.json:
        atomic_write_text(args.json, json.dumps(results, indent=2))
        print(f"\nwrote {args.json}")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Run one benchmark kind with the CLI's flag and output checks (``roboracer-arena``'s);
    an :class:`ArenaError` is one line on stderr and exit 2; Ctrl-C or SIGTERM one line and exit 130."""
    args = build_parser().parse_args(argv)
    try:
        raise_interrupt_on_sigterm()
        check_numeric_flags(args)
        check_outputs(args)
        return int(args.func(args) or 0)
    except ArenaError as e:
        print(f"python -m benchmarks {args.kind}: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # Ctrl-C or SIGTERM: one line, as roboracer-arena does
        print(f"python -m benchmarks {args.kind}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
