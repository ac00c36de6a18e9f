"""``roboracer-arena bench KIND``: how fast this machine runs the simulator. ``physics``
times the native simulator (vehicle-steps/s, lidar off) and ``env`` the gymnasium env
(env-steps/s with a full scan every step); each prints its table and the project's
targets, and can write JSON. The paper's benchmarks and the peer comparisons (F1TENTH Gym,
the DE / random baselines, ...) are not in the wheel: they run from a checkout with
``python -m benchmarks KIND`` (``make bench``)."""

from __future__ import annotations

import argparse
import sys

from ..bench import env, physics

#: Kinds that moved to the checkout's ``benchmarks/`` package (``python -m benchmarks KIND``).
MOVED: tuple[str, ...] = (
    "all",
    "build",
    "constructors",
    "fidelity",
    "generalisation",
    "library",
    "parser",
    "ray",
    "ros2",
)


def register(sub) -> None:
    p = sub.add_parser(
        "bench",
        help="measure this machine's simulator and env throughput",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    kinds = p.add_subparsers(dest="kind", metavar="KIND", required=True)
    physics.register(kinds)
    env.register(kinds)
    for kind in MOVED:  # no help= : not listed; any flags are taken as they are (no option prefix)
        m = kinds.add_parser(kind, add_help=False, prefix_chars="\0")
        m.add_argument("rest", nargs="*")
        m.set_defaults(func=_moved)


def _moved(args: argparse.Namespace) -> int:
    print(
        f"roboracer-arena bench {args.kind}: this benchmark moved out of the package; run it from a "
        f"checkout of the repository: python -m benchmarks {args.kind} (see BENCHMARKS.md)",
        file=sys.stderr,
    )
    return 2
