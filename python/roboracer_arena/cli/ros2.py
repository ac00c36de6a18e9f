"""``roboracer-arena ros2 TRACK``: run the simulator behind a ROS 2 interface over DDS
(no ROS install needed). A ROS 2 node on the same ROS_DOMAIN_ID sees the
f1tenth_gym_ros topics (/scan, /ego_racecar/odom, /tf, /tf_static, /clock, /map) and
drives the car with /drive (ackermann_msgs/AckermannDriveStamped); /initialpose resets
it. --cars 2 adds /opp_scan, /opp_racecar/odom, /opp_drive; more cars /car<i>/....

Needs the optional extra: pip install 'roboracer-arena[ros2]'. On a machine whose only
interface is loopback, pass --loopback (or set CYCLONEDDS_URI) on both sides."""

from __future__ import annotations

import argparse
import json
import math
import signal
import sys
import time
from pathlib import Path

from ..config.sim import MIN_RATE_HZ
from ..errors import InvalidArgumentError
from ..ros2.clock import BridgeConfig
from ..ros2.dds import check_domain_id, profile
from ._common import add_json_flag, print_json


def _rate(value: str) -> float | None:
    if value == "max":
        return None
    try:
        r = float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--rate must be a positive number or 'max', got {value!r}") from None
    if not (math.isfinite(r) and MIN_RATE_HZ <= r <= 1e6):
        raise argparse.ArgumentTypeError(f"--rate must be in [{MIN_RATE_HZ:g}, 1e6] or 'max', got {value!r}")
    return r


def register(sub) -> None:
    p = sub.add_parser(
        "ros2",
        help="run the simulator behind a ROS 2 (DDS) interface, optionally recording MCAP",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("track", metavar="TRACK", nargs="?", help="ROS map YAML (or a catalog id)")
    p.add_argument("--cars", type=int, default=1, help="number of cars (default 1; 2 = ego + opponent)")
    p.add_argument("--domain-id", type=int, default=None, help="ROS 2 domain id 0..232 (default: $ROS_DOMAIN_ID or 0)")
    p.add_argument(
        "--rate",
        type=_rate,
        default=1.0,
        metavar="R|max",
        help="simulated seconds per wall second (default 1 = real time; 'max' = as fast as possible)",
    )
    p.add_argument(
        "--lockstep",
        action="store_true",
        help="advance one control period (1/drive_hz) per /drive message received (deterministic)",
    )
    p.add_argument("--config", type=Path, metavar="F", help="JSON bridge config: {'rates': {...}, 'sim': {...}}")
    p.add_argument("--record", type=Path, metavar="RUN.mcap", help="record every message to an MCAP file")
    p.add_argument(
        "--loopback",
        action="store_true",
        help="configure DDS for the loopback interface only (no multicast; unicast discovery on 127.0.0.1)",
    )
    p.add_argument(
        "--start",
        type=float,
        nargs=3,
        action="append",
        metavar=("X", "Y", "YAW"),
        help="start pose of a car in the map frame (m, m, rad); once per car, ego first "
        "(default: the env's grid start, as gym.make(..., reset_poses='grid'))",
    )
    p.add_argument(
        "--reset-poses",
        choices=("grid", "centreline_start", "random"),
        default=None,
        help="where the cars start without --start, as the env's reset_poses (default grid; "
        "other start options: the 'start' section of --config)",
    )
    p.add_argument(
        "--print-profile",
        choices=("cyclonedds", "fastdds"),
        metavar="cyclonedds|fastdds",
        help="print the loopback discovery profile a ROS 2 node on that DDS needs to find a --loopback "
        "bridge (cyclonedds: the CYCLONEDDS_URI value; fastdds: the XML file FASTRTPS_DEFAULT_PROFILES_FILE "
        "names) and exit",
    )
    p.add_argument(
        "--policy",
        type=Path,
        metavar="FILE",
        help="also run a trained policy file (roboracer-arena train) as a ROS 2 node driving the ego car over DDS",
    )
    p.add_argument("--duration", type=float, default=None, metavar="S", help="stop after S wall seconds")
    p.add_argument("--sim-time", type=float, default=None, metavar="S", help="stop after S simulated seconds")
    add_json_flag(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    import os

    from ..ros2.bridge import Bridge

    if args.print_profile:
        sys.stdout.write(profile(args.print_profile, "any" if args.domain_id is None else args.domain_id))
        return 0
    if args.track is None:
        raise InvalidArgumentError("ros2: a TRACK (map YAML or catalog id) is needed, unless --print-profile")
    if args.cars < 1 or args.cars > 64:
        raise InvalidArgumentError(f"--cars must be in 1..64, got {args.cars}")
    for flag in ("duration", "sim_time"):
        v = getattr(args, flag)
        if v is not None and not v > 0:
            raise InvalidArgumentError(f"--{flag.replace('_', '-')} must be > 0, got {v}")
    domain = args.domain_id
    if domain is None:
        env = os.environ.get("ROS_DOMAIN_ID", "0") or "0"
        if not env.isdigit():
            raise InvalidArgumentError(f"ROS_DOMAIN_ID must be an integer, got {env!r}")
        domain = int(env)
    check_domain_id(domain)
    config = BridgeConfig.load(args.config) if args.config else BridgeConfig()
    policy = None
    if args.policy is not None:
        from ..learn import load_policy

        policy = load_policy(args.policy)
    if args.reset_poses is not None:
        config = config.model_copy(update={"start": config.start.model_copy(update={"reset_poses": args.reset_poses})})
    bridge = Bridge(
        args.track,
        cars=args.cars,
        domain_id=domain,
        rate=args.rate,
        lockstep=args.lockstep,
        config=config,
        record=args.record,
        loopback=args.loopback,
        start_poses=args.start,
        stop_at=args.sim_time,
    )
    stop = {"flag": False}

    def on_signal(*_):
        stop["flag"] = True

    signal.signal(signal.SIGTERM, on_signal)
    node = None
    if policy is not None:
        from types import SimpleNamespace

        from ..ros2.policy_node import PolicyNode

        node = PolicyNode(policy, SimpleNamespace(centreline=bridge.src.centreline), domain, loopback=args.loopback)
        node.start()
    bridge.start()
    if not args.json:
        mode = "lockstep" if args.lockstep else ("max rate" if args.rate is None else f"{args.rate:g}x real time")
        print(
            f"ros2 bridge on domain {domain}: {bridge.src.name}, {args.cars} car(s), {mode}; Ctrl-C stops", flush=True
        )
    t0 = time.monotonic()
    try:
        while not stop["flag"] and not bridge.wait(0.05):
            if args.duration is not None and time.monotonic() - t0 >= args.duration:
                break
    except KeyboardInterrupt:
        pass
    stats = bridge.stop()
    if node is not None:
        node.stop()
        stats["policy_commands"] = node.commands
        if node.error is not None and not stats["error"]:
            stats["error"] = f"policy node: {node.error!r}"
    if args.record:
        stats["record"] = str(args.record)
    if args.json:
        print_json(stats)
    else:
        print(json.dumps({k: stats[k] for k in ("sim_time_s", "wall_time_s", "real_time_factor", "messages")}))
    if stats["error"]:
        print(f"roboracer-arena ros2: error: {stats['error']}", file=sys.stderr)
        return 1
    return 0
