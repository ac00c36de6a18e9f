"""Judge a policy the way a user meets it: one lap from the grid start of each track, in
the env settings the policy file names, with no randomisation; a lap is clean when it
completes without touching anything or driving the wrong way.

:func:`policy_env_kwargs` is the one place a policy file becomes env settings (``drive
--policy``, the ROS 2 bridge and this evaluation use it).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..envs.track_pool import resolve_track_pool
from ..envs.vector import RoboRacerVectorEnv
from .policy_file import Policy
from .runner import PolicyRunner


def policy_env_kwargs(policy: Policy, **extra: Any) -> dict[str, Any]:
    """Env keyword arguments that fit ``policy``: its control rate and lidar, ackermann
    actions, a raw scan, ``extra`` on top."""
    env = policy.env
    lidar = dict(env.get("sim", {}).get("lidar", {}))
    lidar.setdefault("num_beams", policy.spec.num_beams)
    lidar.setdefault("fov", policy.spec.fov)
    kw: dict[str, Any] = {
        "control_rate_hz": float(env.get("control_rate_hz", policy.spec.control_rate_hz)),
        "action_mode": "ackermann",
        "observation": {"normalise": False, "odometry": ("x", "y", "yaw", "vx", "steer")},
        "sim": {"lidar": lidar},
    }
    kw.update(extra)
    return kw


def grid_laps(env: Any, act: Any, limit_s: float, obs: Any = None) -> tuple[np.ndarray, list[float | None], np.ndarray]:
    """Step a vector env just reset with one env per track (autoreset disabled) with
    ``act(obs)`` until every env completed a lap, ended its episode or ``limit_s`` of
    simulated time passed. Returns per env: clean lap (completed without ending the
    episode), lap time (s, or None) and progress (m)."""
    n, dt = env.num_envs, env.config.control_dt
    done, clean, progress = np.zeros(n, bool), np.zeros(n, bool), np.zeros(n)
    lap_time: list[float | None] = [None] * n
    for _ in range(int(limit_s / dt)):
        obs, _, term, _, info = env.step(act(obs))
        live = ~done
        progress[live] = info["progress"][live]
        for e in np.flatnonzero(live & info["lap_completed"] & ~term):
            clean[e], lap_time[e] = True, float(info["last_lap_time"][e])
        done |= term | info["lap_completed"]
        if done.all():
            break
    return clean, lap_time, progress


def evaluate_policy(
    policy: Policy, track: Any, max_time_s: float | None = None, theta: np.ndarray | None = None
) -> list[dict[str, Any]]:
    """One lap from the grid start of every track of ``track`` (anything ``track=`` accepts),
    all at once on a vector env of one env per track. Returns per track: ``track``,
    ``clean_lap``, ``lap_time`` (s, or None), ``progress`` (m), ``length`` (m).
    ``max_time_s``: give up after this much simulated time (default: the longest lap at
    0.8 m/s). ``theta``: other parameters of the same spec (e.g. zeros: the base alone)."""
    from gymnasium.vector import AutoresetMode

    tracks, _ = resolve_track_pool(track)
    env = RoboRacerVectorEnv(
        num_envs=len(tracks),
        track=tracks,
        autoreset_mode=AutoresetMode.DISABLED,
        **policy_env_kwargs(
            policy,
            reset_poses="grid",
            collision_ends_episode=True,
            wrong_way_ends_episode=True,
            time_limit_s=None,
        ),
    )
    runner = PolicyRunner(env, policy.spec, policy.env.get("pure_pursuit"))
    params = policy.theta if theta is None else theta
    env.reset(seed=0, options={"track_ids": np.arange(len(tracks))})
    limit = max_time_s if max_time_s is not None else max(t.length for t in tracks) / 0.8
    clean, lap_time, progress = grid_laps(env, lambda _obs: runner.act(params), limit)
    env.close()
    return [
        {
            "track": t.name,
            "clean_lap": bool(clean[i]),
            "lap_time": lap_time[i],
            "progress": round(float(progress[i]), 3),
            "length": round(float(t.length), 3),
        }
        for i, t in enumerate(tracks)
    ]
