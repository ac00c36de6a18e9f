"""Classes 4 and 6: schema floors on every rate and time step (5e-324 Hz and dt = 1e-300
passed "> 0" and then divided by zero), and sweep files validated over their whole range
at load (they were checked against request 0 only, and crashed mid-run later)."""

from __future__ import annotations

import json
import math

import pytest

from roboracer_arena import _core
from roboracer_arena.errors import ArenaError, ConfigError, SpecError


@pytest.mark.parametrize("rates", [{"scan_hz": 5e-324}, {"odom_hz": 1e-300}, {"drive_hz": 5e-324}, {"clock_hz": 1e-9}])
def test_bridge_rates_have_a_floor(tmp_path, rates):
    from roboracer_arena.ros2.clock import BridgeConfig

    p = tmp_path / "c.json"
    p.write_text(json.dumps({"rates": rates}))
    with pytest.raises(ConfigError, match="greater than or equal to 0.01"):
        BridgeConfig.load(p)


@pytest.mark.parametrize(
    "sim", [{"physics": {"dt": 1e-300}}, {"physics": {"dt": 5e-324}}, {"lidar": {"rate_hz": 5e-324}}]
)
def test_sim_steps_and_rates_have_a_floor_on_both_sides(sim):
    from roboracer_arena.config.sim import SimConfig

    with pytest.raises(ValueError):
        SimConfig.model_validate(sim)
    with pytest.raises(ArenaError, match="at least"):
        _core.check_config("sim", sim)


def test_gym_make_refuses_a_vanishing_step_and_rate(oval):
    import gymnasium as gym

    with pytest.raises(ConfigError):
        gym.make("RoboRacerArena-v0", track=oval, sim={"physics": {"dt": 1e-300}})
    with pytest.raises(ConfigError):
        gym.make("RoboRacerArena-v0", track=oval, control_rate_hz=5e-324)


def test_bridge_rate_flag_has_a_floor():
    from roboracer_arena.ros2.clock import Pacer

    with pytest.raises(ConfigError):
        Pacer(5e-324)


# -- class 6: whole-range sweep validation ---------------------------------------------

BASE = {"name": "s", "fixed": {"corridor_width_m": 1.5, "hall_x_m": 15, "hall_y_m": 12}}


@pytest.mark.parametrize(
    "ranges,msg",
    [
        ({"hairpins": [0, 51]}, "hairpins=51"),  # request 0 draws 44 (valid); 1 in 52 later ones draw 51
        ({"lap_length_m": [30, math.inf]}, "finite"),
        ({"lap_length_m": [math.nan, 40]}, "finite"),
    ],
)
def test_a_sweep_range_that_can_draw_a_bad_spec_fails_at_load(tmp_path, ranges, msg):
    from roboracer_arena.library.spec_sweep import load_sweep

    p = tmp_path / "s.json"
    p.write_text(json.dumps({**BASE, "ranges": ranges}, allow_nan=True).replace("Infinity", "1e999"))
    with pytest.raises(SpecError, match=msg.split("=")[0]):
        load_sweep(p)


def test_a_fixed_feature_order_that_some_draws_contradict_fails_at_load(tmp_path):
    from roboracer_arena.library.spec_sweep import load_sweep

    p = tmp_path / "s.json"
    doc = {**BASE, "ranges": {"hairpins": [1, 2]}, "fixed": {**BASE["fixed"], "feature_order": ["hairpin"]}}
    p.write_text(json.dumps(doc))
    with pytest.raises(SpecError, match="hairpins=2"):
        load_sweep(p)


def test_the_example_sweep_still_loads():
    from roboracer_arena.library.spec_sweep import EXAMPLE_SWEEP, SweepFile

    SweepFile.model_validate(EXAMPLE_SWEEP)
