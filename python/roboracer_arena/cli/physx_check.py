"""``roboracer-arena physx-check STAGE.usdc``: load a built stage in PhysX (ovphysx, CPU)
and check that it holds: a single-sided PhysX lidar scan from the env's grid start equals
our scan (at least 99 % of the beams within 1 cm), car-sized bodies sent at the walls at
speeds up to the car's top speed all stay in the corridor and above the floor (on an open
map: in the free region, from stations spread over the floor plan); reports the load time. Exit 0 when every part holds, 6 when one does not, 2 for bad input or a
missing ``physx`` extra (pip install 'roboracer-arena[physx]')."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..errors import InvalidArgumentError
from . import EXIT_OK
from ._common import add_json_flag, print_json

#: The stage loaded but does not hold in PhysX.
EXIT_PHYSX_FAILED = 6


def register(sub) -> None:
    p = sub.add_parser("physx-check", help="check a built stage in PhysX (the 'physx' extra)", description=__doc__)
    p.add_argument("stage", type=Path, metavar="STAGE.usdc", help="a stage written by 'build'")
    p.add_argument(
        "--points", type=int, default=12, metavar="N", help="stations along the track to send bodies from (1-200)"
    )
    p.add_argument("--seconds", type=float, default=2.0, metavar="S", help="simulated time per probe run (0.1-30)")
    add_json_flag(p)
    p.set_defaults(func=run)


def _stdout_done() -> None:
    """After the JSON: point fd 1 at stderr for the rest of the process, so what the native
    engine prints at exit (its teardown) cannot follow the JSON on stdout. Only in a real
    command process (``sys.stdout`` is the process's own), never under a test's capture."""
    import os
    import sys

    out, err = sys.__stdout__, sys.__stderr__
    if out is None or err is None or sys.stdout is not out:
        return
    try:
        out.flush()
        os.dup2(err.fileno(), out.fileno())
    except (OSError, ValueError):
        pass


def run(args: argparse.Namespace) -> int:
    from ..physx.check import check_stage

    if not 1 <= args.points <= 200:
        raise InvalidArgumentError(f"--points must be 1-200, got {args.points}")
    if not 0.1 <= args.seconds <= 30:
        raise InvalidArgumentError(f"--seconds must be 0.1-30, got {args.seconds}")
    report = check_stage(args.stage, points=args.points, seconds=args.seconds)
    if args.json:
        print_json(report.to_json_dict())
        _stdout_done()
    else:
        print(report.summary())
    return EXIT_OK if report.ok else EXIT_PHYSX_FAILED
