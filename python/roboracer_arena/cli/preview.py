"""``roboracer-arena preview MAP.yaml|STAGE.usdc -o OUT.png``: a picture of a track.

Top-down (the default), framed with a title, legend, scale bar and the map-frame axes.
From a map: the raster, the extracted corridor (tinted), the ducts (visible),
the collision walls (invisible in the simulator), the racing direction as arrows along the
centreline, and the start line with the car where the env's grid start puts it. From a
built stage: its meshes read back, over the source map when it is still there. A
generated track (``centreline.csv`` and ``report.json`` beside its map) also gets its
design centreline and detected features labelled.

``--3d STAGE.usdc``: a lit 3D still of the built stage (floor, ducts with rings, collision
walls as the physics sees them, the car at the start), rendered offscreen with VTK (the
``render3d`` extra); no display or GPU needed.

The picture format comes from the extension of ``-o``: .png, .jpg or .jpeg."""

from __future__ import annotations

import argparse
from dataclasses import asdict
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import ArenaError, InvalidArgumentError
from ..foundation.fileio import check_output, image_named_by, read_text
from ._common import add_json_flag, print_json

if TYPE_CHECKING:  # the renderers import heavy optional packages: load them only when used
    from ..render.preview import PreviewSummary
    from ..render.still3d import StillSummary

USD_SUFFIXES = {".usd", ".usda", ".usdc"}


def register(sub) -> None:
    p = sub.add_parser(
        "preview",
        help="picture of a map or a built stage (top-down, or --3d)",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("source", type=Path, metavar="MAP.yaml|STAGE.usdc", help="a ROS map YAML or a built USD stage")
    p.add_argument(
        "-o", "--out", type=Path, required=True, metavar="OUT.png", help="picture to write (.png, .jpg or .jpeg)"
    )
    p.add_argument(
        "--3d", dest="three_d", action="store_true", help="lit 3D still of a built stage (needs the render3d extra)"
    )
    p.add_argument("--config", type=Path, metavar="F", help="BuildConfig file for a map (.toml or .json)")
    p.add_argument(
        "--start",
        metavar="x,y[,yaw]",
        help="seed the corridor from this pose (maps only; --start=-1.5,2 when x is negative)",
    )
    p.add_argument(
        "--close-gaps",
        type=float,
        default=None,
        metavar="W",
        help="close the openings of the walls up to W m wide first and mark every gap closed (a map only)",
    )
    p.add_argument("--cars", type=int, default=1, metavar="N", help="cars on the grid drawn at the start (default 1)")
    p.add_argument("--max-px", type=int, default=2048, help="longest side of the top-down map in pixels (default 2048)")
    add_json_flag(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from ..render.formats import image_format

    image_format(args.out)  # before any work: a wrong extension is bad input
    if args.max_px < 16:
        raise InvalidArgumentError(f"--max-px must be at least 16, got {args.max_px}")
    if not 1 <= args.cars <= 64:
        raise InvalidArgumentError(f"--cars must be between 1 and 64, got {args.cars}")
    check_output(args.out, inputs=[args.source, *_map_image(args.source)])
    is_stage = args.source.suffix.lower() in USD_SUFFIXES
    summary: StillSummary | PreviewSummary
    if args.three_d:
        if not is_stage:
            raise InvalidArgumentError(f"--3d renders a built stage (.usd, .usda, .usdc), got {args.source}")
        from ..render.still3d import render_still

        summary = render_still(args.source, args.out)
    elif is_stage:
        from ..render.preview import preview_usd

        summary = preview_usd(args.source, args.out, max_px=args.max_px, vehicles=args.cars)
    else:
        from ..render.preview import preview_map

        summary = preview_map(
            args.source,
            args.out,
            config=args.config,
            start=args.start,
            max_px=args.max_px,
            vehicles=args.cars,
            close_gaps_m=args.close_gaps,
        )
    if args.json:
        print_json(asdict(summary))
    else:
        print(f"wrote {summary.output} ({summary.size_px[0]}x{summary.size_px[1]} px): {', '.join(summary.drawn)}")
    return 0


def _map_image(source: Path) -> list[Path]:
    """The image a map YAML names (so the picture cannot overwrite it), if readable;
    a broken YAML is left for the loader to report."""
    if source.suffix.lower() in USD_SUFFIXES:
        return []
    try:
        image = image_named_by(read_text(source, "map YAML", 1 << 20))
    except ArenaError:
        return []
    return [source.parent / image] if image else []
