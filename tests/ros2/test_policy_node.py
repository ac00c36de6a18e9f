"""``roboracer-arena ros2 MAP --policy FILE``: a trained policy file drives the ego car as
a ROS 2 node over DDS (scan, odometry and clock in, /drive out), in lockstep, and laps the
map without touching a wall, as it does in the env."""

from __future__ import annotations

import json

from roboracer_arena.cli import main

TRACK = "gen-l040-w12-h2c1s1-clo-s0"


def test_policy_node_laps_over_dds(tmp_path, domain_id, capsys):
    policy = tmp_path / "p.npz"
    assert (
        main(
            [
                "train",
                "--tracks",
                TRACK,
                "--pairs",
                "2",
                "--generations",
                "2",
                "--no-eval",
                "--out",
                str(policy),
                "--json",
            ]
        )
        == 0
    )
    capsys.readouterr()
    assert main(["drive", TRACK, "--policy", str(policy), "--json"]) == 0
    lap = json.loads(capsys.readouterr().out)["lap_times"][0]
    args = ["ros2", TRACK, "--policy", str(policy), "--lockstep", "--loopback", "--domain-id", str(domain_id)]
    assert main([*args, "--sim-time", f"{lap + 3.0:.2f}", "--duration", "120", "--json"]) == 0
    stats = json.loads(capsys.readouterr().out)
    assert stats["error"] is None
    assert stats["laps"] == [1] and stats["wall_contact_steps"] == [0]
    assert stats["policy_commands"] >= int(lap * 20) - 2
