"""``python -m benchmarks ros2``: the ROS 2 bridge on the wire.

The bridge runs as ``roboracer-arena ros2 MAP --loopback`` in a subprocess; this
process is a ROS 2-like node on the same domain (a second DDS participant over loopback
RTPS) that subscribes to ``/scan``, ``/ego_racecar/odom``, ``/tf`` and ``/clock`` and
closes the loop with a follow-the-gap controller publishing ``/drive`` on every scan.

* **max rate** (``--rate max``, full 1081-beam scan at the paper's 39.9 / 50 / 20 Hz):
  simulated seconds per wall second (real-time factor, target ≥ 20×) and messages per
  second, as the node received them and as the bridge published them.
* **real time** (``--rate 1``): latency from a ``/drive`` write (the DDS source
  timestamp) to the physics step that first uses the command, reported by the bridge;
  target under one control period (1/20 Hz = 50 ms).
"""

from __future__ import annotations

import argparse
import json
import os
import random
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

from roboracer_arena.bench.output import BenchModel, Skipped, add_bench_parser, write_json

DEFAULT_MAP = Path("f1tenth-gym") / "maps" / "berlin.yaml"
TARGET_RTF, TARGET_LATENCY_MS = 20.0, 50.0


class ModeRow(BenchModel):
    """One ``--rate`` mode as this node received it (from the first ``/clock`` on), and the
    bridge's own statistics (its ``--json`` output, as printed)."""

    mode: str
    wall_s: float
    sim_s: float
    real_time_factor_received: float
    received_per_s: float
    scans_received_per_s: float
    received: dict[str, int]
    odom_path_m: float
    bridge: dict[str, Any]


class Ros2Result(BenchModel):
    """``bench ros2``: the map, the machine's load, the targets, the max-rate and real-time rows."""

    map: str
    load_average_1min: float | None
    target_real_time_factor: float
    target_latency_ms: float
    rows: list[ModeRow]


def register(kinds) -> None:
    p = add_bench_parser(
        kinds, "ros2", "ROS 2 bridge: message rate at --rate max, /drive latency in real time", __doc__
    )
    p.add_argument("--map", type=Path, default=None, help="map YAML (default: f1tenth-gym berlin from the sources)")
    p.add_argument("--seconds", type=float, default=8.0, help="wall seconds per mode (default 8)")
    p.set_defaults(func=_run_cli)


def _default_map() -> Path:
    from roboracer_arena.foundation.paths import sources_dir

    return sources_dir(None, "bench ros2 (its default map is f1tenth-gym berlin; or pass --map)") / DEFAULT_MAP


def follow_the_gap(ranges: np.ndarray, fov: float, speed: float = 2.0, max_steer: float = 0.4) -> tuple[float, float]:
    """Steer toward the deepest free direction within ±90° (smoothed ranges), at ``speed``."""
    n = len(ranges)
    ang = np.linspace(-fov / 2, fov / 2, n)
    r = np.convolve(np.minimum(np.asarray(ranges, float), 8.0), np.ones(31) / 31, mode="same")
    r[np.abs(ang) > np.pi / 2] = 0.0
    return float(np.clip(0.6 * ang[int(np.argmax(r))], -max_steer, max_steer)), speed


def _run_mode(map_path: Path, rate: str, seconds: float) -> ModeRow:
    from cyclonedds.pub import DataWriter
    from cyclonedds.sub import DataReader
    from cyclonedds.topic import Topic

    from roboracer_arena.ros2 import msgs
    from roboracer_arena.ros2 import state_msgs as sm
    from roboracer_arena.ros2.dds import participant
    from roboracer_arena.ros2.qos import qos_for
    from roboracer_arena.ros2.topics import dds_topic

    domain = random.SystemRandom().randint(1, 200)
    dp = participant(domain, loopback=True)
    subs = {
        "/scan": "sensor_msgs/msg/LaserScan",
        "/ego_racecar/odom": "nav_msgs/msg/Odometry",
        "/tf": "tf2_msgs/msg/TFMessage",
        "/clock": "rosgraph_msgs/msg/Clock",
    }
    readers: dict[str, DataReader[Any]] = {
        t: DataReader(dp, Topic(dp, dds_topic(t), msgs.msg_class(ty), qos=qos_for(t)), qos=qos_for(t))
        for t, ty in subs.items()
    }
    drive_w: DataWriter[Any] = DataWriter(
        dp, Topic(dp, dds_topic("/drive"), msgs.AckermannDriveStamped, qos=qos_for("/drive")), qos=qos_for("/drive")
    )
    cmd = [
        sys.executable,
        "-c",
        "import sys; from roboracer_arena.cli import main; sys.exit(main())",
        "ros2",
        str(map_path),
        "--domain-id",
        str(domain),
        "--rate",
        rate,
        "--loopback",
        "--json",
        "--duration",
        str(seconds + 30),
    ]
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    counts = {t: 0 for t in subs}
    first_clock: float | None = None
    last_clock: float | None = None
    t_first = t_last = 0.0
    path_len, last_xy = 0.0, None
    deadline = time.monotonic() + seconds + 25  # discovery and startup included
    try:
        while time.monotonic() < deadline:
            got_any = False
            for t, r in readers.items():
                for s in r.take(N=512):
                    if not s.sample_info.valid_data:
                        continue
                    got_any = True
                    counts[t] += 1
                    if t == "/clock":
                        c = sm.stamp_seconds(s.clock)
                        now = time.perf_counter()
                        if first_clock is None:
                            first_clock, t_first = c, now
                            counts = {k: 0 for k in counts}  # count from the first clock on
                        last_clock, t_last = c, now
                    elif t == "/scan" and first_clock is not None:
                        steer, speed = follow_the_gap(np.asarray(s.ranges), s.angle_max - s.angle_min)
                        drive_w.write(
                            msgs.AckermannDriveStamped(
                                header=msgs.Header(stamp=s.header.stamp, frame_id="ego_racecar/base_link"),
                                drive=msgs.AckermannDrive(steering_angle=steer, speed=speed),
                            )
                        )
                    elif t == "/ego_racecar/odom":
                        p = s.pose.pose.position
                        if last_xy is not None:
                            path_len += float(np.hypot(p.x - last_xy[0], p.y - last_xy[1]))
                        last_xy = (p.x, p.y)
            if first_clock is not None and time.perf_counter() - t_first >= seconds:
                break
            if not got_any:
                time.sleep(0.0005)
    finally:
        proc.terminate()
        try:
            out, err = proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            out, err = proc.communicate()
    if first_clock is None or last_clock is None:
        raise RuntimeError(f"bench ros2: no /clock received from the bridge (stderr: {err.strip()[-300:]})")
    wall = max(t_last - t_first, 1e-9)
    bridge = json.loads(out[out.index("{") :]) if "{" in out else {}
    received = sum(counts.values())
    return ModeRow(
        mode=f"--rate {rate}",
        wall_s=round(wall, 3),
        sim_s=round(last_clock - first_clock, 3),
        real_time_factor_received=round((last_clock - first_clock) / wall, 2),
        received_per_s=round(received / wall, 1),
        scans_received_per_s=round(counts["/scan"] / wall, 1),
        received=counts,
        odom_path_m=round(path_len, 2),
        bridge=bridge,
    )


def run(map_path: Path | None = None, seconds: float = 8.0) -> Ros2Result:
    """Measure both modes and print the table; returns the results."""
    map_path = Path(map_path or _default_map())
    rows = [_run_mode(map_path, "max", seconds), _run_mode(map_path, "1", seconds)]
    load = round(os.getloadavg()[0], 2) if hasattr(os, "getloadavg") else None
    mx, rt = rows
    lat = rt.bridge.get("drive_latency_ms") or {}
    print(
        f"ROS 2 bridge on {map_path.stem}: 1 car, 1081-beam scan at 39.9 Hz, odometry+tf 50 Hz, /clock 100 Hz, "
        f"DDS over loopback to a second process (follow-the-gap on every scan); load average {load}"
    )
    print(f"{'mode':<12}{'sim s/wall s':>14}{'msgs/s recv':>13}{'scans/s':>9}{'bridge CPU s':>14}  target")
    ok = "ok" if mx.real_time_factor_received >= TARGET_RTF else "MISS"
    for r in rows:
        tgt = f"≥{TARGET_RTF:.0f}× {ok}" if r is mx else ""
        print(
            f"{r.mode:<12}{r.real_time_factor_received:>14.2f}{r.received_per_s:>13,.0f}"
            f"{r.scans_received_per_s:>9,.0f}{r.bridge.get('cpu_time_s', float('nan')):>14.2f}  {tgt}"
        )
    if lat:
        ok = "ok" if lat["p99"] < TARGET_LATENCY_MS else "MISS"
        print(
            f"/drive write → command in effect (real time, {rt.bridge.get('drive_commands')} commands): "
            f"median {lat['median']:.2f} ms, p99 {lat['p99']:.2f} ms, max {lat['max']:.2f} ms "
            f"(target p99 < {TARGET_LATENCY_MS:.0f} ms = one control period) {ok}"
        )
    return Ros2Result(
        map=map_path.stem,
        load_average_1min=load,
        target_real_time_factor=TARGET_RTF,
        target_latency_ms=TARGET_LATENCY_MS,
        rows=rows,
    )


def run_quick() -> Ros2Result | Skipped:
    try:
        import cyclonedds  # noqa: F401
    except ImportError:
        print("bench ros2: skipped (the [ros2] extra is not installed)")
        return Skipped(skipped="cyclonedds not installed")
    return run(seconds=5.0)


def _run_cli(args: argparse.Namespace) -> int:
    res = run(args.map, args.seconds)
    write_json(args.json, res)
    return 0
