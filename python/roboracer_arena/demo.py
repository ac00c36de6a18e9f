"""``make demo``: the main job end to end on embedded defaults (no server, no download).

1. a natural-language request → ``TrackSpec`` (embedded rules parser, never invents);
2. spec → screen → lattice constructor → rasterise → raster validator → ROS map;
3. map → physics-ready USD stage (floor, ducts, invisible collision walls, materials);
4. a top-down preview picture of what was built;
5. the reference pure-pursuit car drives one lap in the rapier simulator (GIF).

``--map MAP.yaml`` skips steps 1–2 and uses any ROS occupancy map instead.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from ._core import __version__
from .builder import build_environment
from .drivers import drive_laps
from .errors import ArenaError
from .foundation.fileio import check_output
from .generate import Acceptance, generate_track, write_outputs
from .parse import parse_request
from .render.preview import preview_map

#: What the demo writes into its folder (``track/`` holds the generated map).
OUTPUT_FILES = ("track.usdc", "preview.png", "lap.gif", "track/map.yaml")
DEFAULT_REQUEST = "A 60 m lap with two hairpins and a chicane in a 20 by 15 m hall, counter-clockwise."


def _step(title: str) -> float:
    print(f"\n== {title}", flush=True)
    return time.perf_counter()


def _generate(request: str, seed: int, out: Path) -> Path | None:
    t = _step(f"parse: {request!r}")
    parsed = parse_request(request)
    for field in parsed.stated:
        print(f"  {field:<18} = {getattr(parsed.spec, field)!r}")
    if parsed.unparsed:
        print(f"  not understood: {', '.join(repr(f.text) for f in parsed.unparsed)}")
    print(f"  ({(time.perf_counter() - t) * 1e3:.1f} ms)")

    _step(f"generate (lattice constructor, seed {seed})")
    outcome = generate_track(parsed.spec, seed=seed)
    print(f"  {outcome.summary()}")
    if not isinstance(outcome, Acceptance):
        return None
    paths = write_outputs(outcome, out / "track")
    for c in outcome.report.checks:
        print(f"  {c.line()}")
    return Path(paths["map_yaml"])


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(
        prog="python -m roboracer_arena.demo", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    p.add_argument("--out", type=Path, default=Path("out/demo"), help="output folder (default out/demo)")
    p.add_argument("--request", default=DEFAULT_REQUEST, help="natural-language track request")
    p.add_argument("--seed", type=int, default=0, help="constructor seed (default 0)")
    p.add_argument("--map", type=Path, metavar="MAP.yaml", help="use this ROS map instead of generating one")
    p.add_argument("--no-drive", action="store_true", help="skip the simulated lap")
    args = p.parse_args(argv)

    try:  # every output checked before any work: a file as --out, a read-only folder, the map itself
        check_output(args.out, directory=True)
        for name in OUTPUT_FILES:
            check_output(args.out / name, inputs=[args.map])
    except ArenaError as e:
        print(f"demo: error: {e}", file=sys.stderr)
        return 2
    print(f"RoboRacer Arena {__version__} demo → {args.out}/")
    try:
        map_yaml = args.map or _generate(args.request, args.seed, args.out)
        if map_yaml is None:
            return 3
        usd = args.out / "track.usdc"
        _step(f"build USD from {map_yaml}")
        report = build_environment(map_yaml, usd)
        print("  " + report.summary().replace("\n", "\n  "))

        _step("preview")
        png = args.out / "preview.png"
        preview_map(map_yaml, png)
        print(f"  wrote {png}")

        if not args.no_drive:
            _step("drive one lap with the reference pure-pursuit driver (rapier physics, 1081-beam lidar)")
            gif = args.out / "lap.gif"
            res = drive_laps(str(map_yaml), 1, video=gif, progress=True)
            verdict = "completed" if res.completed else ("COLLIDED" if res.collided else "did not finish")
            print(
                f"  {verdict}: {res.laps_completed}/1 lap of {res.track_length:.1f} m in {res.sim_time:.2f} s "
                f"simulated ({res.wall_time:.2f} s wall), top speed {res.max_speed:.2f} m/s"
            )
            print(f"  wrote {gif}")
    except ArenaError as e:
        print(f"demo: error: {e}", file=sys.stderr)
        return 2
    print(f"\nDone. Open {args.out}/preview.png, {args.out}/lap.gif; load {args.out}/track.usdc in any USD tool.")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
