"""``roboracer-arena drive MAP``: drive the reference pure-pursuit car around any map
(ROS map YAML, or a catalog id) in its racing direction (``--reverse``: the other way)
and report lap times and contacts; optionally write a GIF/MP4 of the drive.

``--policy FILE`` drives a trained policy file (``roboracer-arena train``) instead, in
the env settings the file names; ``--engine physx`` drives it (or the pure pursuit) on
the PhysX car of the stage ``build --car`` writes (needs the [physx] extra).

Exit codes: 0 every lap completed, 5 the car crashed or did not finish the laps in the
time allowed, 2 bad input."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..drivers import PurePursuitParams, drive_laps
from ..errors import InvalidArgumentError
from ..foundation.fileio import check_output
from . import EXIT_LAP_FAILED, EXIT_OK
from ._common import add_json_flag, print_json


def register(sub) -> None:
    p = sub.add_parser(
        "drive", help="drive the reference pure-pursuit car around a map (lap time, GIF)", description=__doc__
    )
    p.add_argument("map", metavar="MAP", help="ROS map YAML (or a catalog id)")
    p.add_argument("--laps", type=int, default=1, help="laps to drive (default 1)")
    p.add_argument("--gif", type=Path, metavar="OUT.gif", help="write the drive to OUT.gif (or .mp4)")
    p.add_argument("--fps", type=float, default=10.0, help="frames per second of the video (default 10)")
    p.add_argument("--max-speed", type=float, default=None, help="speed cap of the driver (m/s, default 5)")
    p.add_argument("--max-time", type=float, default=None, help="give up after this much simulated time (s)")
    p.add_argument("--reverse", action="store_true", help="drive against the track's racing direction")
    p.add_argument(
        "--mcap",
        type=Path,
        metavar="RUN.mcap",
        help="record the drive as ROS 2 messages to an MCAP file (needs the [ros2] extra)",
    )
    p.add_argument("--policy", type=Path, metavar="FILE", help="drive this policy file instead of the pure pursuit")
    p.add_argument(
        "--raceline",
        action="store_true",
        help="race the track's raceline at its planned speeds (the racing driver) instead of the centreline",
    )
    p.add_argument(
        "--engine",
        choices=("ours", "physx"),
        default="ours",
        help="ours (default) or physx: the PhysX car of a stage built with 'build --car' (see --stage)",
    )
    p.add_argument(
        "--stage",
        type=Path,
        metavar="STAGE.usda",
        help="with --engine physx: the stage to drive (default: built from MAP with a car into a temporary folder)",
    )
    add_json_flag(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    if args.laps < 1:
        raise InvalidArgumentError(f"--laps must be >= 1, got {args.laps}")
    for out in (args.gif, getattr(args, "mcap", None)):
        if out is not None:
            check_output(out, inputs=[args.map])
    params = None
    if args.max_speed is not None:
        if not args.max_speed > 0:
            raise InvalidArgumentError(f"--max-speed must be > 0, got {args.max_speed}")
        params = PurePursuitParams(max_speed=args.max_speed)
    wrapper = None
    if getattr(args, "mcap", None) is not None:
        from ..ros2.episode_recorder import McapEpisodeRecorder

        def wrapper(env):
            return McapEpisodeRecorder(env, args.mcap)

    policy, extra = None, {}
    if args.policy is not None:
        from ..learn import PolicyDriver, load_policy, policy_env_kwargs

        policy = load_policy(args.policy)
        extra = {"controller": lambda env: PolicyDriver(env, policy), **policy_env_kwargs(policy)}
    if args.raceline:
        if args.reverse or args.policy is not None or args.engine == "physx":
            raise InvalidArgumentError(
                "--raceline drives our engine's pure pursuit the racing way: no --reverse, --policy or --engine physx"
            )
        from ..raceline.driver import raceline_drive_kwargs_for

        race = raceline_drive_kwargs_for(args.map, wrapper)
        params, wrapper, extra = race["params"], race["env_wrapper"], {"path": race["path"]}
    if args.engine == "physx":
        from .drive_physx import run_physx

        return run_physx(args, policy, params)
    res = drive_laps(
        args.map,
        args.laps,
        params=params,
        video=args.gif,
        video_fps=args.fps,
        max_time_s=args.max_time,
        progress=not args.json,
        reverse=args.reverse,
        env_wrapper=wrapper,
        **extra,
    )
    status = EXIT_OK if res.completed else EXIT_LAP_FAILED
    if args.json:
        print_json(res.to_dict())
        return status
    verdict = "completed" if res.completed else ("COLLIDED" if res.collided else "did not finish")
    print(
        f"{res.track}: {verdict} {res.laps_completed}/{res.laps_requested} laps of {res.track_length:.1f} m "
        f"in {res.sim_time:.2f} s simulated ({res.wall_time:.2f} s wall), top speed {res.max_speed:.2f} m/s"
    )
    for i, t in enumerate(res.lap_times, 1):
        print(f"  lap {i}: {t:.2f} s")
    if res.collided:
        print(f"  contact on {res.contact_steps} control step(s), first at (x, y) = {tuple(res.contact_at or ())}")
        w = res.corridor_width_at_contact
        if w is not None and res.vehicle_width is not None and w < res.vehicle_width + 0.2:
            print(
                f"  the corridor there is only {w:.2f} m wide for a {res.vehicle_width:.2f} m wide car: "
                "the map's drivable path is too narrow at that point"
            )
    if res.video:
        print(f"  wrote {res.video}")
    if getattr(args, "mcap", None) is not None:
        print(f"  wrote {args.mcap}")
    return status
