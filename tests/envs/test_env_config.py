import pytest

from roboracer_arena.envs.env_config import EnvConfig
from roboracer_arena.errors import ConfigError


def test_defaults_are_20hz_with_substeps_from_dt():
    c = EnvConfig()
    assert c.control_rate_hz == 20.0
    assert c.substeps == round(1 / (20.0 * c.sim.physics.dt))
    assert c.control_dt == pytest.approx(0.05)
    assert c.max_episode_steps == round(120.0 / 0.05)


def test_substeps_follow_rate_and_dt():
    c = EnvConfig.build(control_rate_hz=100.0, sim={"physics": {"dt": 0.01}})
    assert c.substeps == 1 and c.control_dt == pytest.approx(0.01)
    assert EnvConfig.build(control_rate_hz=1000.0).substeps == 1  # never zero
    assert EnvConfig.build(time_limit_s=None).max_episode_steps is None


def test_overrides_merge_with_a_base_config():
    base = EnvConfig.build(vehicles_per_env=3, sim={"physics": {"dt": 0.01}})
    c = EnvConfig.build(base, action_mode="normalised", sim={"lidar": {"num_beams": 271}})
    assert c.vehicles_per_env == 3 and c.action_mode == "normalised"
    assert c.sim.physics.dt == 0.01 and c.sim.lidar.num_beams == 271  # nested dicts merge


@pytest.mark.parametrize(
    "bad",
    [
        {"control_rate_hz": 0},
        {"action_mode": "torque"},
        {"observation": {"odometry": ["x", "altitude"]}},
        {"observation": {"scan": False, "odometry": []}},
        {"observation": {"odometry": ["x", "x"]}},
        {"reward": {"collision_penalty": -1}},
        {"no_such_option": 1},
        {"sim": {"physics": {"dt": float("nan")}}},
    ],
)
def test_bad_values_raise_config_error(bad):
    with pytest.raises(ConfigError):
        EnvConfig.build(**bad)
