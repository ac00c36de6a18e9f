"""The ROS 2 bridge takes an open map through the same loading path as a track:
f1tenth_gym_ros's own default map, ``levine.yaml``, with the default start."""

from __future__ import annotations

import json
import random

import pytest

pytest.importorskip("cyclonedds", reason="needs the [ros2] extra")


@pytest.mark.parametrize("start", [[], ["--start", "0", "0", "0"]], ids=["default start", "f1tenth_gym_ros start"])
def test_ros2_bridge_runs_levine(sources, capsys, start):
    from roboracer_arena.cli import main

    levine = sources / "f1tenth-gym-ros" / "maps" / "levine.yaml"
    domain = str(random.SystemRandom().randint(1, 200))
    args = ["ros2", str(levine), "--loopback", "--sim-time", "1", "--rate", "max", "--domain-id", domain, "--json"]
    assert main(args + start) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["error"] is None and out["sim_time_s"] >= 1.0
    assert out["published"]["/scan"] > 10 and out["published"]["/map"] == 1
