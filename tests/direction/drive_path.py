"""Drive one lap with the reference pure-pursuit driver in the env and record the path."""

from __future__ import annotations

from typing import Any

import numpy as np

from roboracer_arena.drivers import EnvPurePursuit, PurePursuitParams
from roboracer_arena.envs.single import RoboRacerEnv

#: The slower retry after a contact (as `tracks verify` does).
CAUTIOUS = PurePursuitParams(max_speed=2.5, lateral_accel=2.5, lookahead_min=0.5)


def drive_one_lap(
    track: Any, reverse: bool = False, params: PurePursuitParams | None = None
) -> tuple[np.ndarray, bool]:
    """``(driven (x, y) path over one lap, lap completed without contact)``; no lidar."""
    env = RoboRacerEnv(
        track=track,
        reset_poses="grid",
        time_limit_s=None,
        collision_ends_episode=True,
        reverse=reverse,
        observation={"scan": False, "odometry": ("x", "y", "yaw", "speed")},
    )
    driver = EnvPurePursuit(
        env, params or PurePursuitParams(max_steer=float(env.max_steer), wheelbase=float(env.wheelbase))
    )
    length = env.tracks[0].length
    obs, _ = env.reset(seed=0, options={"track_id": 0})
    path = [env.odometry_raw(obs)[0, :2].copy()]
    limit = int((length / 0.5 + 30.0) * env.config.control_rate_hz)
    done = False
    for _ in range(limit):
        obs, _, terminated, _, info = env.step(driver.act(obs))
        path.append(env.odometry_raw(obs)[0, :2].copy())
        if terminated:
            break
        if float(np.min(info["progress"])) >= length:
            done = True
            break
    env.close()
    return np.asarray(path), done


def driven_lap(track: Any, reverse: bool = False) -> np.ndarray:
    """The path of one completed lap (a cautious retry after a contact); fails otherwise."""
    path, done = drive_one_lap(track, reverse)
    if not done:
        path, done = drive_one_lap(track, reverse, CAUTIOUS)
    assert done, f"{track}: no lap completed (reverse={reverse})"
    return path
