import numpy as np
import pytest

from roboracer_arena.drivers import PurePursuitDriver, PurePursuitParams


def test_speed_profile_is_slower_in_the_bends(oval):
    d = PurePursuitDriver(oval.centreline)
    x, y = d.points[:, 0], d.points[:, 1]
    straight = d.speed_profile[(np.abs(x) < 1.0) & (np.abs(y) > 2.9)]
    bend = d.speed_profile[x > 5.0]
    assert bend.max() <= np.sqrt(d.params.lateral_accel * 3.0) + 1e-6  # v = sqrt(a / kappa), R = 3 m
    assert straight.min() > bend.max()
    assert d.length == pytest.approx(oval.length, rel=1e-6)


def test_on_the_line_it_steers_into_the_bend_and_corrects_offsets(oval):
    d = PurePursuitDriver(oval.centreline)
    # on the bottom straight heading +x (CCW): the bend ahead turns left
    steer_mid, _ = d.act_pose(0.0, -3.0, 0.0, 1.0)
    assert abs(steer_mid) < 0.02
    d.reset()
    steer_left_of_line, _ = d.act_pose(0.0, -2.7, 0.0, 1.0)  # 0.3 m left of the line: steer right
    d.reset()
    steer_right_of_line, _ = d.act_pose(0.0, -3.3, 0.0, 1.0)
    assert steer_left_of_line < 0 < steer_right_of_line
    d.reset()
    steer_bend, _ = d.act_pose(3.0 + 3 * np.cos(-0.8), 3 * np.sin(-0.8), np.pi / 2 - 0.8, 2.0)
    assert steer_bend > 0.05


def test_commands_stay_in_bounds_and_nan_poses_stop(oval):
    p = PurePursuitParams(max_steer=0.3, max_speed=2.0)
    d = PurePursuitDriver(oval.centreline, p)
    rng = np.random.default_rng(0)
    for _ in range(200):
        steer, v = d.act_pose(*rng.uniform([-9, -4, -np.pi, 0], [9, 4, np.pi, 6]))
        assert abs(steer) <= 0.3 and p.min_speed <= v <= 2.0
    assert np.array_equal(d.act_pose(np.nan, 0.0, 0.0, 1.0), [0.0, 0.0])


def test_projection_tracks_progress_locally(oval):
    d = PurePursuitDriver(oval.centreline)
    i0 = d.project(0.0, -3.0)
    i1 = d.project(0.5, -3.0)
    assert (i1 - i0) % len(d.points) == pytest.approx(0.5 / d.ds, abs=1.5)


def test_env_driver_needs_the_pose_in_the_observation(oval):
    from roboracer_arena.envs.single import RoboRacerEnv
    from roboracer_arena.errors import ConfigError

    env = RoboRacerEnv(track=oval, observation={"odometry": ["speed"]}, sim={"lidar": {"num_beams": 9}})
    with pytest.raises(ConfigError, match="x, y, yaw"):
        PurePursuitDriver.for_env(env)


def test_env_driver_works_with_normalised_observations_and_actions(oval):
    from roboracer_arena.envs.single import RoboRacerEnv

    env = RoboRacerEnv(
        track=oval,
        observation={"normalise": True},
        action_mode="normalised",
        reset_poses="grid",
        sim={"lidar": {"num_beams": 9}},
    )
    driver = PurePursuitDriver.for_env(env)
    obs, _ = env.reset(seed=0)
    for _ in range(100):
        action = driver.act(obs)
        assert env.action_space.contains(action)
        obs, _, term, _, info = env.step(action)
        assert not term
    assert info["progress"] > 10.0
