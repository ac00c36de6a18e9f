"""OpenAI-style evolution strategies (numpy only) for a lidar driving policy.

The policy is a small MLP (tanh) from the normalised observation (``num_beams`` lidar
ranges clipped to a 10 m horizon, plus speed and steer) to a normalised action
(steer in [-1, 1], speed mapped into ``[min_speed_frac, max_speed_frac]`` of the top
speed: the policy cannot reverse). Each generation evaluates ``pairs`` antithetic pairs
(theta + sigma eps, theta - sigma eps) on ONE native vector env of ``2 * pairs``
environments: both members of a pair start on the same track at the same pose
(``reset(options={"track_ids", "poses"})``; a :class:`~roboracer_arena.distributed.RayVectorEnv`
spreads them over Ray actors), episodes run with autoreset DISABLED and a
finished environment's later rewards are ignored. The update uses centred ranks and Adam.

Everything is seeded: the same :class:`ESConfig` and track give the same curve.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from ..distributed.ray_vector import RayVectorEnv
from ..envs.track_pool import resolve_track_pool
from ..envs.vector import RoboRacerVectorEnv
from ..errors import ConfigError
from .evaluate import grid_laps


@dataclass(frozen=True)
class ESConfig:
    """Hyper-parameters of :func:`train` (defaults: about a minute on a 2-core laptop)."""

    generations: int = 60
    pairs: int = 24
    sigma: float = 0.1
    learning_rate: float = 0.05
    weight_decay: float = 0.005
    episode_steps: int = 300
    hidden: int = 32
    num_beams: int = 54
    min_speed_frac: float = 0.15
    max_speed_frac: float = 0.6
    seed: int = 0
    env_kwargs: dict[str, Any] = field(default_factory=dict)


def env_kwargs(cfg: ESConfig, **extra: Any) -> dict[str, Any]:
    """The env configuration the policy is trained and evaluated with."""
    kw: dict[str, Any] = {
        "action_mode": "normalised",
        "normalised_speed_range": None,  # the policy maps its own speed range (MLPPolicy.act)
        "observation": {"normalise": True, "odometry": ("speed", "steer")},
        "sim": {"lidar": {"num_beams": cfg.num_beams}},
        "collision_ends_episode": True,
        "time_limit_s": None,
    }
    kw.update(cfg.env_kwargs)
    kw.update(extra)
    return kw


class MLPPolicy:
    """``inputs -> hidden (tanh) -> 2 (tanh)``, many parameter vectors evaluated at once."""

    def __init__(self, inputs: int, hidden: int, cfg: ESConfig) -> None:
        self.inputs, self.hidden = inputs, hidden
        self.shapes = [(inputs, hidden), (hidden,), (hidden, 2), (2,)]
        self.size = sum(int(np.prod(s)) for s in self.shapes)
        self._lo, self._hi = cfg.min_speed_frac, cfg.max_speed_frac

    def init(self, rng: np.random.Generator) -> np.ndarray:
        """Initial parameters: scaled normal first layer, small output layer."""
        parts = [
            rng.normal(0, 1 / math.sqrt(self.inputs), self.shapes[0]),
            np.zeros(self.hidden),
            rng.normal(0, 0.1 / math.sqrt(self.hidden), self.shapes[2]),
            np.zeros(2),
        ]
        return np.concatenate([p.ravel() for p in parts])

    def _unpack(self, theta: np.ndarray) -> list[np.ndarray]:
        out, i = [], 0
        for s in self.shapes:
            n = int(np.prod(s))
            out.append(theta[..., i : i + n].reshape(*theta.shape[:-1], *s))
            i += n
        return out

    def act(self, theta: np.ndarray, x: np.ndarray) -> np.ndarray:
        """Normalised actions (N, 2) for parameters (N, P) (or (P,)) and features (N, inputs)."""
        w1, b1, w2, b2 = self._unpack(np.broadcast_to(theta, (len(x), self.size)))
        h = np.tanh(np.einsum("ni,nih->nh", x, w1) + b1)
        y = np.tanh(np.einsum("nh,nho->no", h, w2) + b2)
        speed = self._lo + (self._hi - self._lo) * 0.5 * (y[:, 1] + 1.0)
        return np.stack([y[:, 0], speed], axis=1).astype(np.float32)


def features(obs: dict[str, np.ndarray]) -> np.ndarray:
    """(N, inputs) policy input from a vector env observation."""
    return np.concatenate([obs["scan"], obs["odometry"]], axis=1).astype(np.float64)


def _make_env(track: Any, num_envs: int, cfg: ESConfig, **extra: Any) -> Any:
    from gymnasium.vector import AutoresetMode

    return RoboRacerVectorEnv(
        num_envs=num_envs, track=track, autoreset_mode=AutoresetMode.DISABLED, **env_kwargs(cfg, **extra)
    )


def rollout(
    env: Any, policy: MLPPolicy, thetas: np.ndarray, steps: int, options: dict | None = None, seed: int | None = None
) -> tuple[np.ndarray, int]:
    """Episodic returns (N,) of one parameter vector per env, and env-steps simulated."""
    obs, _ = env.reset(seed=seed, options=options)
    n = env.num_envs
    ret, alive = np.zeros(n), np.ones(n, bool)
    t = 0
    for _ in range(steps):
        t += 1
        obs, rew, term, trunc, _ = env.step(policy.act(thetas, features(obs)))
        ret += rew * alive
        alive &= ~(term | trunc)
        if not alive.any():
            break
    return ret, t * n


def _centred_ranks(x: np.ndarray) -> np.ndarray:
    ranks = np.empty(len(x))
    ranks[np.argsort(x, kind="stable")] = np.arange(len(x))
    return ranks / (len(x) - 1) - 0.5


@dataclass
class TrainResult:
    """What :func:`train` returns: final parameters and the learning curve."""

    theta: np.ndarray
    config: ESConfig
    curve: list[dict[str, float]]
    env_steps: int
    seconds: float

    def summary(self) -> dict[str, Any]:
        return {
            "config": {k: v for k, v in asdict(self.config).items()},
            "env_steps": self.env_steps,
            "seconds": round(self.seconds, 2),
            "curve": self.curve,
        }


def make_training_env(track: Any, cfg: ESConfig, ray_actors: int | None = None) -> Any:
    """The vector env :func:`train` uses (build it once to train several seeds on a big pool).
    With ``ray_actors``, a :class:`~roboracer_arena.distributed.RayVectorEnv` of that many
    actors (``2 * pairs`` must divide evenly; Ray connected or ``auto``): the same
    environments and seeds, so the same curve as the local env."""
    if not ray_actors:
        return _make_env(track, 2 * cfg.pairs, cfg)
    from gymnasium.vector import AutoresetMode

    if ray_actors < 1 or (2 * cfg.pairs) % ray_actors:
        raise ConfigError(f"--ray actors: 2 * pairs = {2 * cfg.pairs} envs do not split over {ray_actors} actors")
    return RayVectorEnv(
        ray_actors, 2 * cfg.pairs // ray_actors, track=track, autoreset_mode=AutoresetMode.DISABLED, **env_kwargs(cfg)
    )


def train(
    track: Any, cfg: ESConfig = ESConfig(), progress: Callable[[dict[str, float]], None] | None = None, env: Any = None
) -> TrainResult:
    """Train the policy with ES on ``track`` (anything ``track=`` accepts, pools included),
    or on ``env`` from :func:`make_training_env` (then ``track`` is ignored)."""
    if env is None:
        env = make_training_env(track, cfg)
    elif env.num_envs != 2 * cfg.pairs:
        raise ConfigError(f"train: env has {env.num_envs} envs, the config needs 2 * pairs = {2 * cfg.pairs}")
    rng = np.random.default_rng(cfg.seed)
    obs_dim = cfg.num_beams + 2
    policy = MLPPolicy(obs_dim, cfg.hidden, cfg)
    theta = policy.init(rng)
    m, v = np.zeros_like(theta), np.zeros_like(theta)
    b1, b2, eps_adam = 0.9, 0.999, 1e-8
    curve: list[dict[str, float]] = []
    steps_total, t0 = 0, time.perf_counter()
    for gen in range(cfg.generations):
        eps = rng.normal(size=(cfg.pairs, policy.size))
        thetas = np.repeat(theta[None], 2 * cfg.pairs, axis=0)
        thetas[0::2] += cfg.sigma * eps
        thetas[1::2] -= cfg.sigma * eps
        # Each pair shares a start: draw tracks and poses for every env, then copy env 2i's to 2i+1.
        env.reset(seed=cfg.seed * 100_003 + gen)
        ids, poses, speeds = (x[0::2].repeat(2, axis=0) for x in env.start_state())
        ret, n = rollout(env, policy, thetas, cfg.episode_steps, {"track_ids": ids, "poses": poses, "speeds": speeds})
        steps_total += n
        shaped = _centred_ranks(ret)
        grad = -(shaped[0::2] - shaped[1::2]) @ eps / (2 * cfg.pairs * cfg.sigma) + cfg.weight_decay * theta
        m = b1 * m + (1 - b1) * grad
        v = b2 * v + (1 - b2) * grad * grad
        theta = theta - cfg.learning_rate * (m / (1 - b1 ** (gen + 1))) / (
            np.sqrt(v / (1 - b2 ** (gen + 1))) + eps_adam
        )
        row = {
            "generation": gen,
            "mean_return": float(ret.mean()),
            "max_return": float(ret.max()),
            "env_steps": steps_total,
            "seconds": round(time.perf_counter() - t0, 3),
        }
        curve.append(row)
        if progress:
            progress(row)
    return TrainResult(theta, cfg, curve, steps_total, time.perf_counter() - t0)


def evaluate_laps(
    theta: np.ndarray, track: Any, cfg: ESConfig, max_time_s: float | None = None
) -> list[dict[str, Any]]:
    """Drive the policy from the grid start of every track of ``track`` (one env each) until
    it completes a lap, touches anything, drives the wrong way or runs out of time
    (default: the lap at 0.8 m/s, below the policy's slowest speed). Returns per track:
    name, clean_lap, lap_time (s or None), progress (m)."""
    tracks, _ = resolve_track_pool(track)
    env = _make_env(tracks, len(tracks), cfg, reset_poses="grid", wrong_way_ends_episode=True)
    policy = MLPPolicy(cfg.num_beams + 2, cfg.hidden, cfg)
    obs, _ = env.reset(seed=0, options={"track_ids": np.arange(len(tracks))})
    limit = max_time_s if max_time_s is not None else max(t.length for t in tracks) / 0.8
    clean, lap_time, progress = grid_laps(env, lambda o: policy.act(theta, features(o)), limit, obs)
    return [
        {"track": t.name, "clean_lap": bool(clean[i]), "lap_time": lap_time[i], "progress": float(progress[i])}
        for i, t in enumerate(tracks)
    ]
