"""``roboracer-arena build MAP.yaml -o OUT.usdc``: any ROS occupancy map → a physics-ready
USD stage (floor, invisible collision walls, the visible ducts: air-duct tubes with rings,
materials, physics scene). Prints the build report (per-stage times, mesh sizes, USD size, round-trip IoU)."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..builder import build_environment, resolve_config
from ..errors import InvalidArgumentError
from ._common import add_json_flag, print_json


def register(sub) -> None:
    p = sub.add_parser("build", help="ROS occupancy map → physics-ready USD stage", description=__doc__)
    p.add_argument("map", type=Path, metavar="MAP.yaml", help="ROS map YAML (image beside it)")
    p.add_argument(
        "-o", "--out", type=Path, required=True, metavar="OUT.usdc", help="output stage (.usdc, .usda or .usd)"
    )
    p.add_argument("--config", type=Path, metavar="F", help="BuildConfig file (.toml or .json)")
    p.add_argument(
        "--start",
        metavar="x,y[,yaw]",
        help="seed the corridor from this pose (map frame, m/rad) instead of finding the ring (an open map's start pose); "
        "write --start=-1.5,2 when x is negative",
    )
    kind = p.add_mutually_exclusive_group()
    kind.add_argument(
        "--open",
        action="store_const",
        const=True,
        dest="open",
        help="build an open map (walls from every occupied region, no centreline) even when the map has a closed corridor; "
        "by default a map without one is built as an open map, and the report says so",
    )
    kind.add_argument(
        "--track-only",
        action="store_const",
        const=False,
        dest="open",
        help="refuse a map without a closed corridor instead of building it as an open map",
    )
    p.add_argument(
        "--unknown",
        choices=("occupied", "free"),
        default="occupied",
        help="open maps: unknown cells are walls (default, as nav2 with allow_unknown false) or floor (as F1TENTH Gym)",
    )
    p.add_argument(
        "--close-gaps",
        type=float,
        default=None,
        metavar="W",
        help="close the openings of the walls up to W m wide first (doorways, sensor leaks) so a leaking loop "
        "becomes a closed corridor; the report lists every gap closed",
    )
    p.add_argument("--usda", action="store_true", help="write text USD (the output must end in .usda or .usd)")
    p.add_argument("--no-textures", action="store_true", help="plain colours, no PNG textures beside the stage")
    p.add_argument(
        "--car",
        action="store_true",
        help="add the paper's car as a PhysX vehicle at the grid start (needs the 'physx' extra)",
    )
    add_json_flag(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    cfg = resolve_config(args.config)
    if args.usda:
        if args.out.suffix.lower() == ".usdc":
            raise InvalidArgumentError(f"{args.out}: --usda asks for text USD but the output ends in .usdc; use .usda")
        cfg = cfg.model_copy(update={"usd_format": "usda"})
    if args.no_textures:
        cfg = cfg.model_copy(update={"materials": cfg.materials.model_copy(update={"textures": False})})
    report = build_environment(
        args.map,
        args.out,
        cfg,
        start=args.start,
        car=args.car,
        open=args.open,
        unknown=args.unknown,
        close_gaps_m=args.close_gaps,
    )
    if args.json:
        print_json(report.model_dump(mode="json"))
    else:
        print(report.summary())
    return 0
