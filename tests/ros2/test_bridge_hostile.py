"""Classes 1, 11 and 14 (``/drive``): one rule for messages from other DDS peers --
validate, count, log once, keep running. A non-finite or out-of-world ``/initialpose``
used to stop the bridge (exit 1) and discard its ``--record`` MCAP; non-finite
``/drive`` commands became "stop" silently. And ``--sim-time S`` at ``--rate max`` used
to overshoot to 2-5 x S (the stop was polled from another thread)."""

from __future__ import annotations

import json
import math
import time

import pytest

pytestmark = [pytest.mark.slow, pytest.mark.timeout(120)]

DRIVE, INITIALPOSE = "ackermann_msgs/msg/AckermannDriveStamped", "geometry_msgs/msg/PoseWithCovarianceStamped"


def _pose(x: float, y: float, qz: float = 0.0, qw: float = 1.0):
    from roboracer_arena.ros2 import msgs

    return msgs.PoseWithCovarianceStamped(
        header=msgs.Header(frame_id="map"),
        pose=msgs.PoseWithCovariance(
            pose=msgs.Pose(position=msgs.Point(x=x, y=y), orientation=msgs.Quaternion(x=0.0, y=0.0, z=qz, w=qw))
        ),
    )


def _drive(steer: float, speed: float):
    from roboracer_arena.ros2 import msgs

    return msgs.AckermannDriveStamped(
        header=msgs.Header(frame_id="ego_racecar/base_link"),
        drive=msgs.AckermannDrive(steering_angle=steer, speed=speed),
    )


def test_hostile_initialpose_and_drive_are_dropped_counted_and_the_recording_kept(
    ellipse_map, domain_id, ros_node, bridge_process, tmp_path
):
    from mcap.reader import make_reader

    rec = tmp_path / "run.mcap"
    proc = bridge_process([str(ellipse_map), "--domain-id", str(domain_id), "--record", str(rec)])
    ros_node.subscribe("/ego_racecar/odom", "nav_msgs/msg/Odometry")
    ros_node.wait_for("/ego_racecar/odom", 3, timeout=30)
    pose = ros_node.publisher("/initialpose", INITIALPOSE)
    drive = ros_node.publisher("/drive", DRIVE)
    ros_node.wait_matched("/initialpose")
    ros_node.wait_matched("/drive")
    for msg in (
        _pose(math.nan, 0.0),
        _pose(0.0, math.inf),
        _pose(0.0, 0.0, qz=math.nan),
        _pose(0.0, 0.0, qz=0.0, qw=0.0),  # a zero quaternion is no orientation
        _pose(1e12, -1e12),  # far outside the world
        _pose(-4000.0, 0.0),
        _pose(0.0, 0.0),  # inside the world's box, but in the infield
        _pose(4.6, 0.0),  # in the inner wall
        _pose(8.0, 0.0),  # beyond the outer wall
    ):
        pose.write(msg)
    for msg in (_drive(math.nan, 1.0), _drive(0.0, math.inf), _drive(-math.inf, math.nan)):
        drive.write(msg)
    time.sleep(0.5)
    pose.write(_pose(6.0, 0.0))  # a valid reset still works after the hostile ones
    ros_node.wait_for(
        "/ego_racecar/odom",
        pred=lambda m: math.hypot(m.pose.pose.position.x - 6.0, m.pose.pose.position.y) < 0.05,
        timeout=20,
    )
    code, out, err = proc.stop()
    assert code == 0, err  # still alive until stopped (SIGTERM), and a clean exit
    stats = json.loads(out)
    assert stats["error"] is None
    rejected = stats["rejected"]
    assert rejected["/initialpose: non-finite position or orientation"] == 4, rejected
    assert rejected["/initialpose: position outside the world"] == 2, rejected
    assert rejected["/initialpose: position inside a wall or off the track"] == 3, rejected
    assert rejected["/drive: non-finite steering or speed"] == 3, rejected
    assert err.count("dropped /initialpose") == 3 and err.count("dropped /drive") == 1, err  # once per kind
    with open(rec, "rb") as f:  # the recording is whole and readable, hostile messages included
        topics = [ch.topic for _, ch, _ in make_reader(f).iter_messages()]
    assert topics.count("/initialpose") == 10 and topics.count("/drive") == 3


def test_sim_time_stops_exactly_at_max_rate(ellipse_map, domain_id, bridge_process):
    proc = bridge_process(
        [str(ellipse_map), "--domain-id", str(domain_id), "--rate", "max", "--sim-time", "0.4"], duration=60
    )
    deadline = time.monotonic() + 60
    while proc.proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    code, out, err = proc.stop()
    assert code == 0, err
    assert json.loads(out)["sim_time_s"] == pytest.approx(0.4, abs=1e-9)


def test_the_python_api_applies_the_same_rule(ellipse_map):
    from roboracer_arena.ros2.bridge import Bridge

    b = Bridge(str(ellipse_map), dds=False, rate=None, stop_at=0.25)
    b.start()
    assert b.reset_ego(math.nan, 0.0, 0.0) is False and b.reset_ego(1e9, 0.0, 0.0) is False
    for x, y in ((0.0, 0.0), (4.6, 0.0), (8.0, 0.0), (0.0, 5.0)):  # in the box, off the track
        assert b.reset_ego(x, y, 0.0) is False, (x, y)
    assert b.reset_ego(6.0, 0.0, 0.0) and b.reset_ego(0.0, -3.5, 0.0)  # on it
    assert b.wait(30)
    stats = b.stop()
    assert stats["error"] is None and stats["sim_time_s"] == pytest.approx(0.25, abs=1e-9)
    assert stats["rejected"]["/initialpose: position inside a wall or off the track"] == 4
    assert sum(stats["rejected"].values()) == 6


def test_an_open_map_pose_must_be_in_its_free_space():
    """On an open map (walls only: a 10 x 8 m room with a 2 m pillar) the free space is the
    room around the start: the pillar and the outside (still inside the world's box) are
    refused, any free spot is taken."""
    import numpy as np

    from roboracer_arena.ros2.bridge import Bridge
    from roboracer_arena.track.drivable import Track

    def box(x0, y0, x1, y1):
        return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], float)

    room = Track.open_map([box(-5, -4, 5, 4), box(1, -1, 3, 1)], (-3.0, 0.0, 0.0), name="room")
    b = Bridge(room, dds=False, rate=None, stop_at=0.1)
    b.start()
    for x, y in ((2.0, 0.0), (7.0, 0.0), (0.0, -6.0)):  # the pillar; outside the room, inside the box
        assert b.reset_ego(x, y, 0.0) is False, (x, y)
    assert b.reset_ego(0.0, 3.0, 0.0) and b.reset_ego(4.0, -3.0, 1.0)
    assert b.wait(30)
    stats = b.stop()
    assert stats["error"] is None
    assert stats["rejected"] == {"/initialpose: position inside a wall or off the track": 3}
