"""Rollout frames carry the time, speed and lap of the episode."""

from __future__ import annotations

import numpy as np

from roboracer_arena.drivers import PurePursuitDriver
from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.render.sim_view import hud_lines

SMALL = "gen-l040-w12-h2c1s1-clo-s0"


def test_frames_carry_time_speed_and_lap():
    env = RoboRacerEnv(
        track=SMALL, render_mode="rgb_array", render_size=300, reset_poses="grid", sim={"lidar": {"num_beams": 19}}
    )
    obs, _ = env.reset(seed=0)
    driver = PurePursuitDriver.for_env(env)
    for _ in range(20):
        obs, *_ = env.step(driver.act(obs))
    b = env.unwrapped._batch
    speed = float(b.state[0, 0, b.field_index["speed"]])
    lines = hud_lines(b, 0)
    assert lines[0] == f"time {20 * env.config.control_dt:.2f} s" == "time 1.00 s"
    assert lines[1] == f"speed {speed:.2f} m/s, lap 1" and speed > 0.5
    with_hud = env.render()
    plain = env._view.draw(int(b.track_ids[0]), b.state[0], b.field_index, None)
    changed = np.any(with_hud != plain, axis=2)
    assert changed.sum() > 300  # the read-out is drawn (rays aside, it is the only difference)
    env.close()


def test_several_cars_get_a_line_each():
    env = RoboRacerEnv(track=SMALL, reset_poses="grid", vehicles_per_env=3, sim={"lidar": {"num_beams": 19}})
    env.reset(seed=0)
    lines = hud_lines(env._batch, 0)
    assert lines[0] == "time 0.00 s" and [ln.split(":")[0] for ln in lines[1:]] == ["car 1", "car 2", "car 3"]
    env.close()
