"""The bridge on the wire: ``roboracer-arena ros2`` in a subprocess, a second DDS
participant in the test acting as a ROS 2 node (real RTPS over the loopback interface)."""

from __future__ import annotations

import json
import math
import time

import numpy as np
import pytest

from roboracer_arena.ros2 import state_msgs as sm

pytestmark = [pytest.mark.slow, pytest.mark.timeout(120)]

SCAN, ODOM, TF, TF_STATIC, CLOCK, MAP, CENTRELINE = (
    "sensor_msgs/msg/LaserScan",
    "nav_msgs/msg/Odometry",
    "tf2_msgs/msg/TFMessage",
    "tf2_msgs/msg/TFMessage",
    "rosgraph_msgs/msg/Clock",
    "nav_msgs/msg/OccupancyGrid",
    "visualization_msgs/msg/Marker",
)
DRIVE, INITIALPOSE = "ackermann_msgs/msg/AckermannDriveStamped", "geometry_msgs/msg/PoseWithCovarianceStamped"


def _subscribe_all(node, cars: int = 1) -> None:
    from roboracer_arena.ros2.topics import car_names

    for name, typ in (
        ("/tf", TF),
        ("/tf_static", TF_STATIC),
        ("/clock", CLOCK),
        ("/map", MAP),
        ("/centreline", CENTRELINE),
        ("/global_path", "nav_msgs/msg/Path"),
    ):
        node.subscribe(name, typ)
    for i in range(cars):
        n = car_names(i)
        node.subscribe(n.scan, SCAN)
        node.subscribe(n.odom, ODOM)


def _drive(node, speed: float, steer: float = 0.0, topic: str = "/drive"):
    from roboracer_arena.ros2 import msgs

    w = node._writers.get(topic) or node.publisher(topic, DRIVE)
    node.wait_matched(topic)
    w.write(
        msgs.AckermannDriveStamped(
            header=msgs.Header(frame_id="ego_racecar/base_link"),
            drive=msgs.AckermannDrive(steering_angle=steer, speed=speed),
        )
    )
    return w


def _progress(points: np.ndarray, xy: np.ndarray) -> float:
    """Arc length (m) of the projection of ``xy`` on the closed polyline ``points``."""
    seg = np.diff(points, axis=0)
    seg_len = np.linalg.norm(seg, axis=1)
    cum = np.concatenate([[0.0], np.cumsum(seg_len)])
    t = np.clip(((xy - points[:-1]) * seg).sum(axis=1) / np.maximum(seg_len**2, 1e-12), 0, 1)
    d = np.linalg.norm(points[:-1] + t[:, None] * seg - xy, axis=1)
    k = int(np.argmin(d))
    return float(cum[k] + t[k] * seg_len[k])


def test_topics_scan_clock_tf_map_drive_and_initialpose(ellipse_map, domain_id, ros_node, bridge_process):
    from roboracer_arena.maps.occupancy import load_map

    _subscribe_all(ros_node)
    proc = bridge_process([str(ellipse_map), "--domain-id", str(domain_id)])

    # Latched topics arrive although the node may have joined after they were written.
    grid = ros_node.wait_for("/map")[0]
    occ = load_map(ellipse_map)
    assert (grid.info.height, grid.info.width) == occ.shape and grid.header.frame_id == "map"
    assert grid.info.resolution == pytest.approx(occ.resolution)
    assert set(np.unique(grid.data)) <= {-1, 0, 100} and 0 in grid.data and 100 in grid.data
    marker = ros_node.wait_for("/centreline")[0]
    line = np.array([[p.x, p.y] for p in marker.points])
    assert len(line) > 50 and np.allclose(line[0], line[-1])
    # The raceline (issue 35): a closed nav_msgs/Path in map, yaw along the line, inside the corridor.
    path = ros_node.wait_for("/global_path")[0]
    xy = np.array([[p.pose.position.x, p.pose.position.y] for p in path.poses])
    assert path.header.frame_id == "map" and len(xy) > 50 and np.allclose(xy[0], xy[-1])
    step = np.diff(xy, axis=0)
    q = path.poses[0].pose.orientation
    assert math.atan2(2 * q.w * q.z, 1 - 2 * q.z * q.z) == pytest.approx(math.atan2(step[0, 1], step[0, 0]), abs=1e-6)
    r = np.hypot(xy[:, 0] / 6.0, xy[:, 1] / 3.5)  # the ellipse's centreline is r = 1; the corridor is 1.8 m wide
    assert np.all(np.abs(r - 1.0) < 0.2)
    static = ros_node.wait_for("/tf_static")[0].transforms[0]
    assert (static.header.frame_id, static.child_frame_id) == ("ego_racecar/base_link", "ego_racecar/laser")
    assert static.transform.translation.x == pytest.approx(0.12)

    # Scan: 1081 beams over 270 deg, laser frame.
    scan = ros_node.wait_for("/scan", 3)[-1]
    assert len(scan.ranges) == 1081 and scan.header.frame_id == "ego_racecar/laser"
    assert scan.angle_min == pytest.approx(-0.75 * math.pi, abs=1e-6)
    assert scan.angle_max == pytest.approx(0.75 * math.pi, abs=1e-6)
    assert scan.angle_increment == pytest.approx(1.5 * math.pi / 1080, rel=1e-6)
    assert scan.angle_min + 1080 * scan.angle_increment == pytest.approx(scan.angle_max, abs=1e-5)
    r = np.asarray(scan.ranges)
    assert r.min() > 0.1 and r.max() <= scan.range_max and r.max() < 15.0  # walls all around

    # The tf chain map -> base_link -> laser resolves to the laser pose.
    tf = ros_node.wait_for("/tf", 2)[-1].transforms[0]
    assert (tf.header.frame_id, tf.child_frame_id) == ("map", "ego_racecar/base_link")
    yaw = sm.quaternion_yaw(tf.transform.rotation)
    lx = tf.transform.translation.x + math.cos(yaw) * static.transform.translation.x
    ly = tf.transform.translation.y + math.sin(yaw) * static.transform.translation.x
    assert np.isfinite([lx, ly]).all()
    # The car starts at the env's grid start (start_grid.py), the laser 0.12 m ahead of it.
    from roboracer_arena.envs.track_argument import resolve_tracks
    from roboracer_arena.track.start_grid import grid_start_s

    s_grid = grid_start_s(resolve_tracks(str(ellipse_map))[0], 1, 1.0)
    lap = _progress(line, line[-2])
    gap = (_progress(line, np.array([lx, ly])) - (s_grid + 0.12) + lap / 2) % lap - lap / 2
    assert gap == pytest.approx(0.0, abs=0.08)  # ahead of the start on the line

    # /drive at 1.5 m/s moves the car forward along the track.
    start = ros_node.wait_for("/ego_racecar/odom")[-1]
    p0 = start.pose.pose.position
    s0 = _progress(line, np.array([p0.x, p0.y]))
    t_cmd = sm.stamp_seconds(start.header.stamp)
    _drive(ros_node, 1.5)
    odoms = ros_node.wait_for("/ego_racecar/odom", pred=lambda m: sm.stamp_seconds(m.header.stamp) > t_cmd + 1.5)
    end = odoms[-1]
    p1 = end.pose.pose.position
    s1 = _progress(line, np.array([p1.x, p1.y]))
    assert 1.0 < (s1 - s0) % _progress(line, line[-2]) < 3.5
    assert 1.2 < end.twist.twist.linear.x < 1.8 and end.child_frame_id == "ego_racecar/base_link"

    # /clock is monotonic and tracks the odometry stamps.
    clocks = [sm.stamp_seconds(c.clock) for c in ros_node.get("/clock")]
    assert len(clocks) > 50 and all(b > a for a, b in zip(clocks, clocks[1:]))

    # /initialpose puts the ego at rest where asked; time keeps running.
    from roboracer_arena.ros2 import msgs

    w = ros_node.publisher("/initialpose", INITIALPOSE)
    ros_node.wait_matched("/initialpose")
    _drive(ros_node, 0.0)
    target = line[len(line) // 4]
    heading = math.atan2(*(line[len(line) // 4 + 1] - target)[::-1])
    w.write(
        msgs.PoseWithCovarianceStamped(
            header=msgs.Header(frame_id="map"),
            pose=msgs.PoseWithCovariance(
                pose=msgs.Pose(
                    position=msgs.Point(x=float(target[0]), y=float(target[1])), orientation=sm.yaw_quaternion(heading)
                )
            ),
        )
    )
    near = ros_node.wait_for(
        "/ego_racecar/odom",
        pred=lambda m: math.hypot(m.pose.pose.position.x - target[0], m.pose.pose.position.y - target[1]) < 0.05,
    )[0]
    assert sm.quaternion_yaw(near.pose.pose.orientation) == pytest.approx(heading, abs=0.05)
    assert sm.stamp_seconds(near.header.stamp) > sm.stamp_seconds(end.header.stamp)
    clocks = [sm.stamp_seconds(c.clock) for c in ros_node.get("/clock")]
    assert all(b > a for a, b in zip(clocks, clocks[1:]))

    for _ in range(10):  # steady state (the first command may wait for the end of discovery)
        _drive(ros_node, 0.0)
        time.sleep(0.03)
    time.sleep(0.2)
    code, out, err = proc.stop()
    assert code == 0, err
    stats = json.loads(out)  # real time: a /drive takes effect within one control period (50 ms)
    assert stats["drive_commands"] == 12 and stats["drive_latency_ms"]["median"] < 50.0, stats
    assert 0.8 < stats["real_time_factor"] < 1.2


def test_two_cars_use_the_opponent_topics(ellipse_map, domain_id, ros_node, bridge_process, tmp_path):
    _subscribe_all(ros_node, cars=2)
    rec = tmp_path / "two.mcap"
    proc = bridge_process(
        [str(ellipse_map), "--domain-id", str(domain_id), "--cars", "2", "--rate", "max", "--record", str(rec)]
    )
    opp = ros_node.wait_for("/opp_racecar/odom", 3)[-1]
    assert opp.child_frame_id == "opp_racecar/base_link"
    assert len(ros_node.wait_for("/opp_scan")[-1].ranges) == 1081
    ego = ros_node.wait_for("/ego_racecar/odom")[-1].pose.pose.position
    assert math.hypot(opp.pose.pose.position.x - ego.x, opp.pose.pose.position.y - ego.y) > 0.5
    tf = ros_node.wait_for("/tf")[-1]
    assert [t.child_frame_id for t in tf.transforms] == ["ego_racecar/base_link", "opp_racecar/base_link"]
    _drive(ros_node, 1.0, topic="/opp_drive")
    ros_node.wait_for("/opp_racecar/odom", pred=lambda m: m.twist.twist.linear.x > 0.5)
    code, out, err = proc.stop()
    assert code == 0, err
    from test_mcap import read_mcap

    stats, (recorded, _) = json.loads(out), read_mcap(rec)
    assert stats["record"] == str(rec) and len(recorded["/opp_drive"]) == 1
    assert {t: len(v) for t, v in recorded.items() if t != "/opp_drive"} == stats["published"]


def _lockstep_run(ellipse_map, domain_id, node, bridge_process, commands) -> list[tuple]:
    """Drive one lockstep run like a controller: send a command, wait for the /clock of the
    end of its control period, send the next. Returns every odometry message (at 50 Hz)."""
    node.subscribe("/ego_racecar/odom", ODOM)
    node.subscribe("/clock", CLOCK)
    proc = bridge_process([str(ellipse_map), "--domain-id", str(domain_id), "--lockstep"])
    from roboracer_arena.ros2 import msgs

    w = node.publisher("/drive", DRIVE)
    node.wait_matched("/drive")
    node.wait_reader_matched("/ego_racecar/odom")
    node.wait_reader_matched("/clock")
    for k, (steer, speed) in enumerate(commands, 1):
        w.write(msgs.AckermannDriveStamped(drive=msgs.AckermannDrive(steering_angle=steer, speed=speed)))
        node.wait_for("/clock", pred=lambda m, k=k: abs(sm.stamp_seconds(m.clock) - 0.05 * k) < 1e-6)
    time.sleep(0.3)  # lockstep: nothing more may arrive without a command
    assert max(sm.stamp_seconds(m.clock) for m in node.get("/clock")) == pytest.approx(0.05 * len(commands))
    out = []
    for m in node.get("/ego_racecar/odom"):
        p, tw = m.pose.pose, m.twist.twist
        out.append(
            (
                sm.stamp_seconds(m.header.stamp),
                p.position.x,
                p.position.y,
                p.orientation.z,
                p.orientation.w,
                tw.linear.x,
                tw.linear.y,
                tw.angular.z,
            )
        )
    code, _, err = proc.stop()
    assert code == 0, err
    return [o for o in out if o[0] > 0.0]  # the t = 0 message may predate the node's match


def test_lockstep_gives_identical_trajectories(ellipse_map, node_factory, bridge_process):
    import random

    commands = [(0.25 * math.sin(k / 6.0), 2.0) for k in range(40)]
    runs = []
    for _ in range(2):
        d = random.SystemRandom().randint(1, 200)
        runs.append(_lockstep_run(ellipse_map, d, node_factory(d), bridge_process, commands))
    assert len(runs[0]) == 100 and runs[0] == runs[1]  # 2 s at 50 Hz, bit-identical
    (x0, y0), (x1, y1) = runs[0][0][1:3], runs[0][-1][1:3]
    assert math.hypot(x1 - x0, y1 - y0) > 1.5  # it really drove
