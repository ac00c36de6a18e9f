"""``roboracer-arena preview MAP.yaml|OUT.usdc -o OUT.png``: a top-down picture. From a map:
the raster, the extracted corridor (tinted), collision walls, ducts and centreline. From a
built stage: its meshes read back, over the source map when it is still there. A generated
track (``centreline.csv`` and ``report.json`` beside its map) also gets its centreline and
detected features labelled."""

from __future__ import annotations

import argparse
from dataclasses import asdict
from pathlib import Path

from ._common import add_json_flag, print_json

USD_SUFFIXES = {".usd", ".usda", ".usdc"}


def register(sub) -> None:
    p = sub.add_parser("preview", help="top-down PNG of a map or a built stage", description=__doc__)
    p.add_argument("source", type=Path, metavar="MAP.yaml|OUT.usdc", help="a ROS map YAML or a built USD stage")
    p.add_argument("-o", "--out", type=Path, required=True, metavar="OUT.png", help="picture to write (PNG)")
    p.add_argument("--config", type=Path, metavar="F", help="BuildConfig file for a map (.toml or .json)")
    p.add_argument("--start", metavar="x,y[,yaw]", help="seed the corridor from this pose (maps only; --start=-1.5,2 when x is negative)")
    p.add_argument("--max-px", type=int, default=2048, help="longest side of the picture in pixels (default 2048)")
    add_json_flag(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from ..errors import InvalidArgumentError
    from ..fileio import check_output
    from ..render.preview import preview_map, preview_usd

    if args.max_px < 16:
        raise InvalidArgumentError(f"--max-px must be at least 16, got {args.max_px}")
    check_output(args.out, inputs=[args.source, *_map_image(args.source)])
    if args.source.suffix.lower() in USD_SUFFIXES:
        summary = preview_usd(args.source, args.out, max_px=args.max_px)
    else:
        summary = preview_map(args.source, args.out, config=args.config, start=args.start, max_px=args.max_px)
    if args.json:
        print_json(asdict(summary))
    else:
        print(f"wrote {summary.output} ({summary.size_px[0]}x{summary.size_px[1]} px): {', '.join(summary.drawn)}")
    return 0


def _map_image(source: Path) -> list[Path]:
    """The image a map YAML names (so the picture cannot overwrite it), if readable;
    a broken YAML is left for the loader to report."""
    from ..errors import ArenaError
    from ..fileio import read_text
    from ..maps import image_named_by

    if source.suffix.lower() in USD_SUFFIXES:
        return []
    try:
        image = image_named_by(read_text(source, "map YAML", 1 << 20))
    except ArenaError:
        return []
    return [source.parent / image] if image else []
