#!/usr/bin/env python3
"""Stable-Baselines3 PPO on the native vector env with the default reward, then a lap.

    pip install 'roboracer-arena[sb3]'
    python examples/ppo_sb3.py --track gym-berlin --minutes 30 --png ppo.png --json ppo.json
    python examples/ppo_sb3.py --sources DIR          # recorded maps (gym-berlin) from an installed wheel

The envs are one native batch behind SB3's ``VecEnv`` API
(:mod:`roboracer_arena.integrations.sb3`), with ``observation="normalise"`` and
``action_mode="normalised"`` (speed actions -1..1 map to 15-70 % of the top speed) and
the env's default reward (progress, a stall cost, a crash penalty). Training stops at
``--total-steps`` or after ``--minutes``; then the deterministic policy drives from the
grid start until it laps, crashes or runs out of time.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from typing import Any

import numpy as np

from roboracer_arena.scripting import add_sources_argument, apply_sources, run_script

try:
    from stable_baselines3 import PPO
    from stable_baselines3.common.callbacks import BaseCallback
    from stable_baselines3.common.vec_env import VecMonitor

    from roboracer_arena.integrations.sb3 import make_sb3_vec_env
except ImportError:
    print("ppo_sb3.py: error: needs stable-baselines3 (pip install 'roboracer-arena[sb3]')", file=sys.stderr)
    sys.exit(2)


def env_kwargs(args: argparse.Namespace, **extra: Any) -> dict[str, Any]:
    """The env the policy trains and drives in (everything else is the env's default)."""
    return {
        "track": args.track,
        "observation": "normalise",
        "action_mode": "normalised",
        "sim": {"lidar": {"num_beams": args.num_beams}},
        **extra,
    }


class Curve(BaseCallback):
    """Records the mean and best return of the last 20 finished episodes after every
    rollout, and stops training after ``seconds`` of wall time."""

    def __init__(self, seconds: float) -> None:
        super().__init__()
        self.seconds, self.rows, self.t0 = seconds, [], time.perf_counter()

    def _on_step(self) -> bool:
        return time.perf_counter() - self.t0 < self.seconds

    def _on_rollout_end(self) -> None:
        eps = [e["r"] for e in list(self.model.ep_info_buffer)[-20:]]
        if not eps:
            return
        row = {
            "env_steps": int(self.num_timesteps),
            "mean_return": float(np.mean(eps)),
            "max_return": float(np.max(eps)),
            "mean_length": float(np.mean([e["l"] for e in list(self.model.ep_info_buffer)[-20:]])),
            "seconds": round(time.perf_counter() - self.t0, 1),
        }
        self.rows.append(row)
        print(
            f"env-steps {row['env_steps']:8d}  return (last 20) mean {row['mean_return']:8.2f}"
            f" best {row['max_return']:8.2f}  length {row['mean_length']:6.0f}  {row['seconds']:7.1f} s",
            flush=True,
        )


def drive_lap(model: PPO, args: argparse.Namespace, max_time_s: float = 120.0) -> dict[str, Any]:
    """The deterministic policy from the grid start: the first lap's time, or how far it got."""
    venv = make_sb3_vec_env(
        1, **env_kwargs(args, reset_poses="grid", wrong_way_ends_episode=True, time_limit_s=max_time_s)
    )
    venv.seed(0)
    obs = venv.reset()
    progress = 0.0
    for _ in range(int(max_time_s * venv.venv.config.control_rate_hz) + 1):
        action, _ = model.predict(obs, deterministic=True)
        obs, _, dones, infos = venv.step(action)
        info = infos[0]
        progress = info["progress"]
        if info["lap_completed"] and not (dones[0] and not info["TimeLimit.truncated"]):
            return {"track": info["track"], "clean_lap": True, "lap_time": info["last_lap_time"], "progress": progress}
        if dones[0]:
            break
    return {"track": info["track"], "clean_lap": False, "lap_time": None, "progress": progress}


def train(args: argparse.Namespace) -> int:
    apply_sources(args.sources)
    venv = VecMonitor(make_sb3_vec_env(args.num_envs, **env_kwargs(args)))
    model = PPO(
        "MultiInputPolicy",
        venv,
        n_steps=args.n_steps,
        batch_size=args.batch_size,
        n_epochs=args.epochs,
        learning_rate=args.learning_rate,
        gamma=args.gamma,
        policy_kwargs={"net_arch": [64, 64], "log_std_init": -0.5},
        seed=args.seed,
        device="cpu",
        verbose=0,
    )
    curve = Curve(args.minutes * 60.0)
    model.learn(args.total_steps, callback=curve)
    seconds = time.perf_counter() - curve.t0
    print(f"trained: {model.num_timesteps} env-steps in {seconds:.0f} s")
    lap = drive_lap(model, args)
    verdict = f"clean lap in {lap['lap_time']:.2f} s" if lap["clean_lap"] else f"no clean lap ({lap['progress']:.1f} m)"
    print(f"lap on {lap['track']}: {verdict}")
    if args.save:
        model.save(args.save)
    out = {"args": {k: str(v) for k, v in vars(args).items()}, "env_steps": int(model.num_timesteps)}
    out.update(seconds=round(seconds, 1), curve=curve.rows, lap=lap)
    if args.png and curve.rows:
        from roboracer_arena.learn.curve import plot_curve

        title = f"SB3 PPO on {args.track}: {model.num_timesteps / 1e3:.0f}k env-steps, {seconds / 60:.0f} min"
        plot_curve(curve.rows, args.png, title)
    if args.json:
        from roboracer_arena.foundation.fileio import atomic_write_text

        atomic_write_text(args.json, json.dumps(out, indent=2) + "\n")
    return 0 if lap["clean_lap"] else 5


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--track", default="gym-berlin", help="any track= value: catalog id, pattern, map YAML")
    p.add_argument("--num-envs", type=int, default=16)
    p.add_argument("--num-beams", type=int, default=54, help="lidar beams (fewer = faster)")
    p.add_argument("--total-steps", type=int, default=3_000_000)
    p.add_argument("--minutes", type=float, default=30.0, help="stop training after this much wall time")
    p.add_argument("--n-steps", type=int, default=256, help="rollout length per env per update")
    p.add_argument("--batch-size", type=int, default=1024)
    p.add_argument("--epochs", type=int, default=5)
    p.add_argument("--learning-rate", type=float, default=3e-4)
    p.add_argument("--gamma", type=float, default=0.99)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--png", help="write the learning curve here (PNG)")
    p.add_argument("--json", help="write curve and lap result here (JSON)")
    p.add_argument("--save", help="save the trained model here (SB3 .zip)")
    add_sources_argument(p)
    args = p.parse_args()
    return run_script("ppo_sb3.py", lambda: train(args))


if __name__ == "__main__":
    sys.exit(main())
