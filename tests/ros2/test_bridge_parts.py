"""Bridge parts without the network: schedule and pacing, config, topic names, QoS, CLI
input errors, and the library API on an env and on a raw simulator."""

from __future__ import annotations

import json
import time

import numpy as np
import pytest

from roboracer_arena.errors import ConfigError
from roboracer_arena.ros2.clock import BridgeConfig, Pacer, Schedule
from roboracer_arena.ros2.topics import car_names


def test_schedule_hits_the_paper_rates_on_the_physics_clock():
    s = Schedule(0.005, {"scan": 1 / 39.9, "odom": 1 / 50, "clock": 1 / 100})
    counts = {"scan": 0, "odom": 0, "clock": 0}
    step, last_scan = 0, None
    counts.update({k: 1 for k in s.due(0)})
    while step < 2000:  # 10 simulated seconds
        step = s.next_step()
        for k in s.due(step):
            counts[k] += 1
            if k == "scan":
                k_scan = counts["scan"] - 1
                assert step * 0.005 >= k_scan / 39.9 - 1e-9 and step * 0.005 < k_scan / 39.9 + 0.005
                last_scan = step
    assert counts == {"scan": 400, "odom": 501, "clock": 1001} and last_scan <= 2000


def test_pacer_holds_real_time_and_max_does_not_wait():
    p = Pacer(1.0)
    assert 0.05 < p.wait_time(0.1) <= 0.1
    p2 = Pacer(4.0)
    assert p2.wait_time(0.1) <= 0.025 + 1e-3
    assert Pacer(None).wait_time(1e6) == 0.0
    slow = Pacer(1.0, max_lag=0.01)
    time.sleep(0.03)
    assert slow.wait_time(0.0) == 0.0 and slow.wait_time(0.02) > 0.0  # re-anchored, no catch-up burst
    with pytest.raises(ConfigError):
        Pacer(0.0)


def test_bridge_config_file(tmp_path):
    good = tmp_path / "b.json"
    good.write_text(json.dumps({"rates": {"scan_hz": 10, "odom_hz": 25}, "sim": {"lidar": {"num_beams": 271}}}))
    cfg = BridgeConfig.load(good)
    assert cfg.rates.scan_hz == 10 and cfg.rates.drive_hz == 20 and cfg.sim.lidar.num_beams == 271
    bad = tmp_path / "bad.json"
    bad.write_text('{"rates": {"scan_hz": -1}}')
    with pytest.raises(ConfigError, match=r"bad\.json.*rates\.scan_hz"):
        BridgeConfig.load(bad)
    broken = tmp_path / "broken.json"
    broken.write_text("{")
    with pytest.raises(ConfigError, match="broken.json: bridge config is not valid JSON"):
        BridgeConfig.load(broken)


def test_topic_names_follow_f1tenth_gym_ros():
    assert car_names(0).scan == "/scan" and car_names(0).odom == "/ego_racecar/odom" and car_names(0).drive == "/drive"
    assert car_names(1).scan == "/opp_scan" and car_names(1).odom == "/opp_racecar/odom"
    assert car_names(1).drive == "/opp_drive" and car_names(1).base_link == "opp_racecar/base_link"
    assert car_names(3).scan == "/car3/scan" and car_names(3).laser == "car3/laser"


def test_qos_is_ros2_default_and_latched_for_map():
    from cyclonedds.core import Policy

    from roboracer_arena.ros2.qos import qos_for

    scan, latched = qos_for("/scan"), qos_for("/map")
    assert scan[Policy.Reliability].__scope__ == "Reliability" and isinstance(
        scan[Policy.Reliability], Policy.Reliability.Reliable
    )
    assert scan[Policy.History] == Policy.History.KeepLast(10)
    assert scan[Policy.Durability] == Policy.Durability.Volatile
    assert latched[Policy.Durability] == Policy.Durability.TransientLocal
    assert qos_for("/tf_static")[Policy.Durability] == Policy.Durability.TransientLocal
    assert scan[Policy.DataRepresentation] == Policy.DataRepresentation(use_cdrv0_representation=True)


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["ros2", "missing.yaml", "--duration", "1"], "missing.yaml"),
        (["ros2", "x.yaml", "--domain-id", "500"], "--domain-id"),
        (["ros2", "x.yaml", "--cars", "0"], "--cars"),
        (["ros2", "x.yaml", "--duration", "-1"], "--duration"),
    ],
)
def test_cli_bad_input_exits_2(argv, needle, capsys):
    from roboracer_arena.cli import main

    assert main(argv) == 2
    assert needle in capsys.readouterr().err


def test_cli_bad_rate_and_config(tmp_path, ellipse_map, capsys):
    from roboracer_arena.cli import main

    with pytest.raises(SystemExit) as e:
        main(["ros2", str(ellipse_map), "--rate", "fast"])
    assert e.value.code == 2
    bad = tmp_path / "c.json"
    bad.write_text('{"rates": {"nope": 1}}')
    assert main(["ros2", str(ellipse_map), "--config", str(bad)]) == 2
    assert "c.json" in capsys.readouterr().err


def test_library_bridge_on_an_env_and_on_a_simulator(ellipse_map, domain_id):
    """``Bridge(env)`` shares the env's simulator; ``Bridge(sim)`` takes a raw simulator."""
    import gymnasium as gym

    from roboracer_arena import _core
    from roboracer_arena.config.sim import SimConfig
    from roboracer_arena.ros2 import Bridge

    env = gym.make("RoboRacerArena-v0", track=str(ellipse_map))
    env.reset(seed=0)
    with Bridge(env, rate=2.0, domain_id=domain_id, loopback=True) as b:  # paced: stops near 0.5 s
        b.drive(0, 0.0, 2.0)  # straight ahead: stop after 0.5 s (about 0.8 m), before the ellipse's wall
        deadline = time.monotonic() + 30
        while b.sim_time < 0.5 and time.monotonic() < deadline:
            time.sleep(0.01)
    st = b.stats()
    assert st["error"] is None and st["published"]["/scan"] >= 19 and st["published"]["/map"] == 1
    start = env.unwrapped.simulator_state[0][0, :2]  # where the env's reset put the car
    left = b.state[0, 0, :2].copy()  # where the bridge left it
    obs, *_ = env.step(np.array([0.0, 2.0], np.float32))  # the env continues from where the bridge left it
    odo = env.unwrapped.odometry_raw(obs)[0]
    xy = odo[[env.unwrapped.odometry_index["x"], env.unwrapped.odometry_index["y"]]]
    assert np.hypot(*(left - start)) > 0.5  # the bridge drove the env's simulator (about 0.8 m)...
    assert np.hypot(*(xy - left)) < 0.2  # ...and the env's next 50 ms step starts there

    walls, centre = _core.stadium_track()
    sim = _core.Simulator([(walls, centre)], 1, 2, SimConfig(), 0)
    b = Bridge(sim, rate=None, dds=False).start()
    while b.sim_time < 0.2:
        time.sleep(0.01)
    st = b.stop()
    assert st["published"]["/opp_racecar/odom"] >= 10 and "/map" not in st["published"]
    assert np.isfinite(b.state).all()


def test_missing_extra_names_the_package():
    from roboracer_arena.ros2._deps import require

    with pytest.raises(ConfigError, match=r"roboracer-arena\[ros2\]"):
        require("mcap_ros2_no_such_module")


def test_cli_runs_for_a_simulated_duration(ellipse_map, domain_id, tmp_path, capsys):
    from roboracer_arena.cli import main

    rec = tmp_path / "r.mcap"
    assert (
        main(
            [
                "ros2",
                str(ellipse_map),
                "--rate",
                "max",
                "--sim-time",
                "1",
                "--loopback",
                "--domain-id",
                str(domain_id),
                "--record",
                str(rec),
                "--json",
            ]
        )
        == 0
    )
    stats = json.loads(capsys.readouterr().out)
    assert stats["sim_time_s"] >= 1.0 and stats["published"]["/scan"] >= 40 and rec.stat().st_size > 10_000
    assert not list(tmp_path.glob(".r.*"))  # no temporary file left behind
