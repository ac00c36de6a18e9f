"""Train a policy file with evolution strategies on a track pool (``roboracer-arena train``).

Each generation evaluates ``pairs`` antithetic pairs (theta + sigma eps, theta - sigma eps)
on one native vector env of ``2 * pairs`` environments with autoreset disabled: both
members of a pair start on the same track at the same pose and speed, the episode ends at
a contact, on driving the wrong way, or after ``episode_steps``; the return is the
centreline progress less the collision penalty. The update uses centred ranks, weight
decay and Adam.

Everything is seeded by (seed, generation): the noise, the tracks and the starts. So a
run resumed from a checkpoint (the policy file with its optimiser state, written
atomically every ``checkpoint_every`` generations and at the end) continues exactly as an
uninterrupted run would, and an interrupted run leaves its last whole checkpoint.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..envs.vector import RoboRacerVectorEnv
from ..errors import ConfigError, PolicyFileError
from .policy import PolicySpec, init_params
from .policy_file import Policy
from .recipe import Recipe
from .runner import PolicyRunner


def policy_spec(recipe: Recipe, config: Any) -> PolicySpec:
    """The spec of a policy trained with ``recipe`` in an env of ``config``."""
    veh, lid = config.sim.vehicle, config.sim.lidar
    return PolicySpec(
        num_beams=recipe.num_beams,
        fov=float(lid.fov),
        horizon=10.0,
        max_steer=float(veh.max_steer),
        max_speed=float(veh.max_speed),
        min_speed=0.5,
        base=recipe.base,
        steer_residual=recipe.steer_residual,
        speed_residual=recipe.speed_residual,
        speed_range=recipe.speed_range,
        hidden=recipe.hidden,
        control_rate_hz=float(config.control_rate_hz),
    )


def env_settings(config: Any) -> dict[str, Any]:
    """What a policy file records of its env: enough to build an env it can drive."""
    lid = config.sim.lidar
    return {
        "control_rate_hz": float(config.control_rate_hz),
        "sim": {"lidar": {"num_beams": int(lid.num_beams), "fov": float(lid.fov), "range_max": float(lid.range_max)}},
    }


def make_env(tracks: Any, recipe: Recipe, num_envs: int | None = None) -> RoboRacerVectorEnv:
    """The training env of ``recipe`` on ``tracks`` (anything ``track=`` accepts)."""
    from gymnasium.vector import AutoresetMode

    return RoboRacerVectorEnv(
        num_envs=num_envs or 2 * recipe.pairs,
        track=tracks,
        autoreset_mode=AutoresetMode.DISABLED,
        **recipe.env_kwargs(),
    )


def _centred_ranks(x: np.ndarray) -> np.ndarray:
    ranks = np.empty(len(x))
    ranks[np.argsort(x, kind="stable")] = np.arange(len(x))
    return ranks / (len(x) - 1) - 0.5


def rollout(
    env: Any, runner: PolicyRunner, thetas: np.ndarray, steps: int, options: dict | None, seed: int
) -> tuple[np.ndarray, int]:
    """Episodic returns (E,) of one parameter vector per env, and env-steps simulated."""
    env.reset(seed=seed, options=options)
    runner.reset()
    n = env.num_envs
    ret, alive = np.zeros(n), np.ones(n, bool)
    t = 0
    for _ in range(steps):
        t += 1
        _, rew, term, trunc, _ = env.step(runner.act(thetas))
        ret += rew * alive
        alive &= ~(term | trunc)
        if not alive.any():
            break
    return ret, t * n


@dataclass
class TrainState:
    """Where a run stands: parameters, Adam moments, generations done, curve, cost so far."""

    theta: np.ndarray
    m: np.ndarray
    v: np.ndarray
    generation: int
    curve: list[dict[str, float]]
    env_steps: int
    seconds: float
    cpu_seconds: float


def _training_header(recipe: Recipe, tracks: Any, names: list[str], state: TrainState) -> dict[str, Any]:
    return {
        "recipe": recipe.to_dict(),
        "tracks": tracks if isinstance(tracks, (str, dict)) else [str(t) for t in tracks],
        "track_names": names,
        "generation": state.generation,
        "env_steps": state.env_steps,
        "seconds": round(state.seconds, 2),
        "cpu_seconds": round(state.cpu_seconds, 2),
        "curve": state.curve,
    }


def resume_state(policy: Policy, recipe: Recipe, spec: PolicySpec, where: str | Path) -> TrainState:
    """The state a checkpoint holds, if it was written by the same recipe and spec."""
    tr = policy.training

    def same(d: Any) -> Any:  # a resumed run may ask for more generations
        return {k: v for k, v in (d or {}).items() if k != "generations"}

    if policy.spec != spec or same(tr.get("recipe")) != same(_jsonable(recipe.to_dict())):
        raise PolicyFileError(f"{where}: --resume needs the same recipe and settings as the run that wrote it")
    if policy.optimiser is None:
        raise PolicyFileError(f"{where}: has no optimiser state (not a training checkpoint)")
    return TrainState(
        policy.theta.copy(),
        policy.optimiser["m"].copy(),
        policy.optimiser["v"].copy(),
        int(tr.get("generation", 0)),
        list(tr.get("curve", [])),
        int(tr.get("env_steps", 0)),
        float(tr.get("seconds", 0.0)),
        float(tr.get("cpu_seconds", 0.0)),
    )


def _jsonable(d: dict[str, Any]) -> Any:
    import json

    return json.loads(json.dumps(d))


def train_policy(
    tracks: Any,
    recipe: Recipe | None = None,
    *,
    out: str | Path | None = None,
    resume: Policy | None = None,
    max_seconds: float | None = None,
    checkpoint_every: int = 5,
    progress: Callable[[dict[str, float]], None] | None = None,
    env: Any = None,
) -> Policy:
    """Train a policy on ``tracks`` with ``recipe`` (see the module docstring); write it to
    ``out`` (checkpoints included) when given. ``resume``: a checkpoint to continue.
    ``max_seconds`` stops after the generation that crosses it (wall time, this call).
    ``env``: a training env from :func:`make_env` to reuse (several seeds on one pool)."""
    recipe = recipe or Recipe()
    if recipe.generations < 1 or recipe.pairs < 1 or recipe.episode_steps < 1:
        raise ConfigError("train: generations, pairs and episode steps must be >= 1")
    if env is None:
        env = make_env(tracks, recipe)
    elif env.num_envs != 2 * recipe.pairs:
        raise ConfigError(f"train: env has {env.num_envs} envs, the recipe needs 2 * pairs = {2 * recipe.pairs}")
    spec = policy_spec(recipe, env.config)
    runner = PolicyRunner(env, spec)
    names = [t.name for t in env.tracks]
    if resume is not None:
        state = resume_state(resume, recipe, spec, out or "checkpoint")
    else:
        theta = init_params(spec, np.random.default_rng([recipe.seed, 0xE5]))
        state = TrainState(theta, np.zeros_like(theta), np.zeros_like(theta), 0, [], 0, 0.0, 0.0)

    def snapshot() -> Policy:
        return Policy(
            spec,
            state.theta.copy(),
            env_settings(env.config),
            _training_header(recipe, tracks, names, state),
            {"m": state.m, "v": state.v},
        )

    b1, b2, eps_adam = 0.9, 0.999, 1e-8
    t0, c0 = time.perf_counter(), time.process_time()
    base_s, base_c = state.seconds, state.cpu_seconds
    while state.generation < recipe.generations:
        gen = state.generation
        rng = np.random.default_rng([recipe.seed, gen, 0xE5])
        eps = rng.normal(size=(recipe.pairs, spec.size))
        thetas = np.repeat(state.theta[None], 2 * recipe.pairs, axis=0)
        thetas[0::2] += recipe.sigma * eps
        thetas[1::2] -= recipe.sigma * eps
        seed = recipe.seed * 100_003 + gen
        env.reset(seed=seed)  # draws tracks and starts; each pair then shares env 2i's
        ids, poses, speeds = (x[0::2].repeat(2, axis=0) for x in env.start_state())
        ret, n = rollout(
            env, runner, thetas, recipe.episode_steps, {"track_ids": ids, "poses": poses, "speeds": speeds}, seed
        )
        shaped = _centred_ranks(ret)
        grad = -(shaped[0::2] - shaped[1::2]) @ eps / (2 * recipe.pairs * recipe.sigma)
        grad = grad + recipe.weight_decay * state.theta
        state.m = b1 * state.m + (1 - b1) * grad
        state.v = b2 * state.v + (1 - b2) * grad * grad
        step = (
            recipe.learning_rate
            * (state.m / (1 - b1 ** (gen + 1)))
            / (np.sqrt(state.v / (1 - b2 ** (gen + 1))) + eps_adam)
        )
        state.theta = state.theta - step
        state.generation += 1
        state.env_steps += n
        state.seconds = base_s + time.perf_counter() - t0
        state.cpu_seconds = base_c + time.process_time() - c0
        row = {
            "generation": gen,
            "mean_return": round(float(ret.mean()), 3),
            "max_return": round(float(ret.max()), 3),
            "env_steps": state.env_steps,
            "seconds": round(state.seconds, 2),
        }
        state.curve.append(row)
        if progress:
            progress(row)
        done = state.generation >= recipe.generations or (
            max_seconds is not None and time.perf_counter() - t0 >= max_seconds
        )
        if out is not None and (done or state.generation % checkpoint_every == 0):
            snapshot().save(out)
        if done:
            break
    return snapshot()
