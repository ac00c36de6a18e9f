"""MCAP recordings read back with the ROS 2 decoder (``mcap-ros2-support``): the
bridge's ``record=``, the gymnasium episode recorder and ``drive --mcap``."""

from __future__ import annotations

import json
import math
from collections import defaultdict

import numpy as np
import pytest

pytest.importorskip("mcap_ros2")

pytestmark = pytest.mark.timeout(120)


def read_mcap(path) -> tuple[dict[str, list], dict[str, str]]:
    """(decoded messages by topic, schema name by topic), decoded from ros2msg + CDR."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    out, schemas = defaultdict(list), {}
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        assert reader.get_header().profile == "ros2"
        last = -1
        for schema, channel, message, decoded in reader.iter_decoded_messages(log_time_order=False):
            assert schema.encoding == "ros2msg" and channel.message_encoding == "cdr"
            assert message.log_time >= last  # written in time order
            last = message.log_time
            out[channel.topic].append(decoded)
            schemas[channel.topic] = schema.name
    return out, schemas


def test_bridge_records_what_it_publishes(ellipse_map, tmp_path):
    from roboracer_arena.maps.occupancy import load_map
    from roboracer_arena.ros2 import Bridge

    path = tmp_path / "bridge.mcap"
    bridge = Bridge(str(ellipse_map), rate=None, lockstep=True, record=path, dds=False)
    bridge.start()
    for _ in range(40):  # 2 s of lockstep control periods at 1.5 m/s
        bridge.drive(0, 0.0, 1.5)
    deadline = __import__("time").monotonic() + 60
    while bridge.sim_time < 2.0 - 1e-9 and __import__("time").monotonic() < deadline:
        bridge.wait(0.01)
    stats = bridge.stop()
    assert stats["error"] is None and stats["sim_time_s"] == pytest.approx(2.0)
    msgs, schemas = read_mcap(path)
    assert {t: len(v) for t, v in msgs.items()} == {**stats["published"], "/drive": 40}
    assert len(msgs["/scan"]) == math.floor(2.0 * 39.9) + 1 and len(msgs["/ego_racecar/odom"]) == 101
    assert len(msgs["/clock"]) == 201 and len(msgs["/map"]) == len(msgs["/tf_static"]) == 1
    assert schemas["/scan"] == "sensor_msgs/msg/LaserScan" and schemas["/centreline"] == "visualization_msgs/msg/Marker"
    scan = msgs["/scan"][-1]
    assert len(scan.ranges) == 1081 and scan.angle_increment == pytest.approx(1.5 * math.pi / 1080, rel=1e-6)
    grid, occ = msgs["/map"][0], load_map(ellipse_map)
    assert (grid.info.height, grid.info.width) == occ.shape and len(grid.data) == occ.data.size
    assert msgs["/drive"][0].drive.speed == pytest.approx(1.5)
    odo = msgs["/ego_racecar/odom"]
    p0, p1 = odo[0].pose.pose.position, odo[-1].pose.pose.position
    assert 1.5 < math.hypot(p1.x - p0.x, p1.y - p0.y) < 3.2
    clocks = [c.clock.sec + c.clock.nanosec * 1e-9 for c in msgs["/clock"]]
    assert all(b > a for a, b in zip(clocks, clocks[1:]))
    assert len(msgs["/centreline"][0].points) > 50


def test_episode_recorder_wraps_an_env(ellipse_map, tmp_path):
    import gymnasium as gym

    from roboracer_arena.ros2 import McapEpisodeRecorder

    path = tmp_path / "episodes.mcap"
    env = McapEpisodeRecorder(
        gym.make("RoboRacerArena-v0", track=str(ellipse_map), reset_poses="grid", vehicles_per_env=2).unwrapped, path
    )
    for ep in range(2):
        env.reset(seed=ep)
        for _ in range(10):
            env.step(np.array([[0.0, 1.0], [0.0, 0.5]], np.float32))
    env.close()
    msgs, _ = read_mcap(path)
    assert len(msgs["/drive"]) == len(msgs["/opp_drive"]) == 20
    assert msgs["/drive"][0].drive.speed == pytest.approx(1.0) and msgs["/opp_drive"][0].drive.speed == 0.5
    assert len(msgs["/scan"]) == len(msgs["/opp_scan"]) == len(msgs["/ego_racecar/odom"]) == 22
    assert len(msgs["/map"]) == 1 and len(msgs["/tf"][0].transforms) == 2
    stamps = [m.header.stamp.sec + m.header.stamp.nanosec * 1e-9 for m in msgs["/ego_racecar/odom"]]
    assert all(b > a for a, b in zip(stamps, stamps[1:]))  # time keeps running across episodes


def test_drive_cli_writes_mcap(ellipse_map, tmp_path, capsys):
    from roboracer_arena.cli import main

    path = tmp_path / "run.mcap"
    code = main(["drive", str(ellipse_map), "--max-time", "3", "--mcap", str(path), "--json"])
    res = json.loads(capsys.readouterr().out)
    assert code == (0 if res["completed"] else 5)  # 3 s is short of a lap: exit 5, the MCAP still written
    msgs, _ = read_mcap(path)
    steps = round(res["sim_time"] * 20)
    assert len(msgs["/drive"]) == steps and len(msgs["/scan"]) == steps + 1
    assert max(m.drive.speed for m in msgs["/drive"]) > 1.0
    o0, o1 = msgs["/ego_racecar/odom"][0], msgs["/ego_racecar/odom"][-1]
    assert (
        math.hypot(o1.pose.pose.position.x - o0.pose.pose.position.x, o1.pose.pose.position.y - o0.pose.pose.position.y)
        > 2.0
    )
