"""Round 2 (issue 25): hostile DDS samples from a second participant. A bridge with
``--record`` runs in a subprocess; this process joins its domain as another DDS peer and
sends ``/initialpose`` and ``/drive`` samples with values drawn by hypothesis
(derandomized: NaN, infinities, huge and tiny numbers, zero quaternions, poses in the infield or far
outside the world). The bridge must keep running (a valid reset afterwards still
works), count every sample it drops, exit 0 when stopped, and leave a whole recording."""

from __future__ import annotations

import json
import math
import os
import random
import subprocess
import sys
import time

import pytest
from hypothesis import strategies as st

from .test_hostile import draw_cases

pytest.importorskip("cyclonedds", reason="needs the [ros2] extra")
pytestmark = [pytest.mark.slow, pytest.mark.timeout(180)]

DRIVE, INITIALPOSE, ODOM = (
    "ackermann_msgs/msg/AckermannDriveStamped",
    "geometry_msgs/msg/PoseWithCovarianceStamped",
    "nav_msgs/msg/Odometry",
)
FLOAT = st.one_of(
    st.sampled_from([math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, 0.0, -0.0, 1e12]),
    st.floats(-3, 3),
)
# Positions by construction: on the 12 x 7 m ellipse's centreline (free), in its infield
# (inside the world but off the track: dropped since the bridge checks the free space),
# or non-finite / far outside the world in one or both coordinates.
ON_TRACK = ((6.0, 0.0), (-6.0, 0.0), (0.0, 3.5), (0.0, -3.5))
WILD = st.sampled_from([math.nan, math.inf, -math.inf, 1e308, -1e4, 5e3])
XY = st.one_of(
    st.sampled_from(ON_TRACK),
    st.tuples(st.floats(-2.0, 2.0), st.floats(-1.2, 1.2)),  # the infield
    st.tuples(WILD, st.floats(-3, 3)),
    st.tuples(st.floats(-3, 3), WILD),
)
POSE = st.builds(lambda xy, q: (*xy, *q), XY, st.tuples(FLOAT, FLOAT, FLOAT, FLOAT))
FLOAT32 = st.one_of(  # AckermannDrive is float32
    st.sampled_from([math.nan, math.inf, -math.inf, 3e38, -3e38, 1e-45, 0.0, -0.0]), st.floats(-3, 3, width=32)
)
DRIVE_CMD = st.tuples(FLOAT32, FLOAT32)


def _bad_pose(x, y, qx, qy, qz, qw) -> bool:
    values = (x, y, qx, qy, qz, qw)
    return not all(math.isfinite(v) for v in values) or not any(values[2:]) or (x, y) not in ON_TRACK


def _writer(dp, name: str, typename: str):
    from cyclonedds.pub import DataWriter
    from cyclonedds.topic import Topic

    from roboracer_arena.ros2.msgs import msg_class
    from roboracer_arena.ros2.qos import qos_for
    from roboracer_arena.ros2.topics import dds_topic

    topic = Topic(dp, dds_topic(name), msg_class(typename), qos=qos_for(name))
    return topic, DataWriter(dp, topic, qos=qos_for(name))


def _wait(pred, timeout: float, what: str) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if pred():
            return
        time.sleep(0.01)
    pytest.fail(f"timed out waiting for {what}")


def test_hostile_samples_from_another_participant(ellipse_map, tmp_path):
    from cyclonedds.sub import DataReader
    from mcap.reader import make_reader

    from roboracer_arena.ros2 import msgs
    from roboracer_arena.ros2.dds import participant
    from roboracer_arena.ros2.qos import qos_for

    domain = random.SystemRandom().randint(1, 200)
    rec = tmp_path / "run.mcap"
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    proc = subprocess.Popen(
        [sys.executable, "-c", "import sys; from roboracer_arena.cli import main; sys.exit(main())", "ros2"]
        + [str(ellipse_map), "--domain-id", str(domain), "--record", str(rec), "--loopback", "--json"]
        + ["--duration", "120"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    try:
        dp = participant(domain, loopback=True)
        keep = [_writer(dp, "/initialpose", INITIALPOSE), _writer(dp, "/drive", DRIVE)]
        (_, poses), (_, drives) = keep
        odom_topic, _ = _writer(dp, "/ego_racecar/odom", ODOM)
        odom = DataReader(dp, odom_topic, qos=qos_for("/ego_racecar/odom"))
        _wait(lambda: poses.get_matched_subscriptions() and drives.get_matched_subscriptions(), 60, "the bridge")
        sent_poses = draw_cases(POSE, 40)
        sent_drives = draw_cases(DRIVE_CMD, 40)
        for (x, y, qx, qy, qz, qw), (steer, speed) in zip(sent_poses, sent_drives):
            poses.write(
                msgs.PoseWithCovarianceStamped(
                    header=msgs.Header(frame_id="map"),
                    pose=msgs.PoseWithCovariance(
                        pose=msgs.Pose(
                            position=msgs.Point(x=x, y=y), orientation=msgs.Quaternion(x=qx, y=qy, z=qz, w=qw)
                        )
                    ),
                )
            )
            drives.write(
                msgs.AckermannDriveStamped(
                    header=msgs.Header(frame_id="ego_racecar/base_link"),
                    drive=msgs.AckermannDrive(steering_angle=steer, speed=speed),
                )
            )
            time.sleep(0.02)  # within the readers' history depth
        time.sleep(0.3)
        poses.write(  # still alive: a valid reset takes effect
            msgs.PoseWithCovarianceStamped(
                header=msgs.Header(frame_id="map"),
                pose=msgs.PoseWithCovariance(
                    pose=msgs.Pose(position=msgs.Point(x=6.0, y=0.0), orientation=msgs.Quaternion(w=1.0))
                ),
            )
        )

        def reset_seen() -> bool:
            return any(
                s.sample_info.valid_data and math.hypot(s.pose.pose.position.x - 6.0, s.pose.pose.position.y) < 0.05
                for s in odom.take(N=256)
            )

        _wait(reset_seen, 30, "the valid reset after the hostile samples")
    finally:
        if proc.poll() is None:
            proc.terminate()
        out, err = proc.communicate(timeout=60)
    assert proc.returncode == 0, err[-1500:]
    stats = json.loads(out)
    assert stats["error"] is None
    with open(rec, "rb") as f:
        got = [
            (ch.topic, m.data) for _, ch, m in make_reader(f).iter_messages() if ch.topic in ("/initialpose", "/drive")
        ]
    from roboracer_arena.ros2.msgs import msg_class

    recorded_poses = [msg_class(INITIALPOSE).deserialize(d) for t, d in got if t == "/initialpose"]
    recorded_drives = [msg_class(DRIVE).deserialize(d) for t, d in got if t == "/drive"]
    assert len(recorded_poses) >= 30 and len(recorded_drives) >= 30  # (reliable, depth 10)
    bad_poses = sum(
        _bad_pose(
            p.pose.pose.position.x, p.pose.pose.position.y, *(getattr(p.pose.pose.orientation, a) for a in "xyzw")
        )
        for p in recorded_poses
    )
    bad_drives = sum(
        not (math.isfinite(d.drive.steering_angle) and math.isfinite(d.drive.speed)) for d in recorded_drives
    )
    rejected = stats["rejected"]
    assert sum(v for k, v in rejected.items() if k.startswith("/initialpose")) == bad_poses > 0, rejected
    assert rejected.get("/initialpose: position inside a wall or off the track", 0) > 0, rejected  # the infield
    assert rejected.get("/drive: non-finite steering or speed", 0) == bad_drives > 0, rejected
