"""``roboracer-arena validate MAP.yaml --spec SPEC.json``: run the raster validator on any
ROS map. Exit 0 when every check passes, 4 when some check fails."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..generate import validate_map
from ..maps.occupancy import load_map
from ..spec import TrackSpec
from . import EXIT_GENERATION_FAILURE, EXIT_OK
from ._common import add_json_flag, print_json


def register(sub) -> None:
    p = sub.add_parser("validate", help="check a map against a TrackSpec on the raster", description=__doc__)
    p.add_argument("map", type=Path, metavar="MAP.yaml", help="ROS map YAML (image beside it)")
    p.add_argument("--spec", type=Path, required=True, metavar="SPEC.json", help="TrackSpec JSON file")
    add_json_flag(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    spec = TrackSpec.from_file(args.spec)
    m = load_map(args.map)
    report, _ = validate_map(m, spec)
    if args.json:
        print_json({"map": str(args.map), **report.model_dump(mode="json")})
    else:
        for c in report.checks:
            print(c.line())
        print(f"{args.map}: {'valid' if report.valid else 'INVALID'}")
    return EXIT_OK if report.valid else EXIT_GENERATION_FAILURE
