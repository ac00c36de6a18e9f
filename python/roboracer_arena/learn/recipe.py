"""The default training recipe of ``roboracer-arena train``, and the held-out maps it is
judged on.

The recipe was chosen by measurement (``python -m benchmarks generalisation``; the
figures are in BENCHMARKS.md): a residual MLP on the reference pure pursuit (RLPP's
structure), trained with evolution strategies on the pool of every catalog track except
the held-out recorded maps, with domain randomisation of tyre friction, mass, actuator
lags, lidar noise and dropout, and an actuation delay of 0 to 2 control steps.

:data:`HELD_OUT` lists whole families of recorded maps (a map and its redraws or
variants), so no layout of a held-out map is trained on under another name.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any, Literal

#: Recorded maps never trained on by default: the generalisation benchmark's test set.
HELD_OUT: tuple[str, ...] = (
    "gym-skirk",
    "gym-vegas",
    "gym-example",
    "cps-torino-redraw",
    "cps-torino-redraw-small",
    "cps-columbia-small",
    "cps-columbia-simple",
    "cps-plechaty2",
    "cps-plechaty2nobox",
    "cps-operngasse-9",
    "cps-blackbox2022-1",
    "cps-blackbox2022-3",
    "cps-treitlstrasse-3-u-v1",
    "cps-treitlstrasse-3-u-v2",
    "cps-treitlstrasse-3-u-v3",
)

#: The randomisation of the default recipe (``EnvConfig.randomisation``).
RANDOMISATION: dict[str, Any] = {
    "friction_scale": (0.8, 1.1),
    "mass_scale": (0.85, 1.2),
    "lag_scale": (0.8, 1.5),
    "lidar_noise_std": (0.0, 0.02),
    "lidar_dropout": 0.01,
    "action_delay_steps": (0, 2),
}


@dataclass(frozen=True)
class Recipe:
    """Everything that decides a training run (besides the tracks): the policy's structure,
    the ES hyper-parameters and the env it trains in."""

    base: Literal["none", "pure_pursuit"] = "pure_pursuit"
    num_beams: int = 55  # 1081-beam scans hold them (every 20th beam)
    hidden: int = 32
    steer_residual: float = 0.25
    speed_residual: float = 0.5
    speed_range: tuple[float, float] = (0.15, 0.6)  # without a base: fraction of max speed
    generations: int = 40
    pairs: int = 16
    sigma: float = 0.05
    learning_rate: float = 0.03
    weight_decay: float = 0.005
    episode_steps: int = 300
    randomise: bool = True
    seed: int = 0
    control_rate_hz: float = 20.0
    env_overrides: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    def env_kwargs(self) -> dict[str, Any]:
        """Keyword arguments of the training env (:class:`~roboracer_arena.envs.RoboRacerVectorEnv`)."""
        kw: dict[str, Any] = {
            "action_mode": "ackermann",
            "control_rate_hz": self.control_rate_hz,
            "observation": {"normalise": False, "odometry": ("vx", "steer")},
            "sim": {"lidar": {"num_beams": self.num_beams}},
            "collision_ends_episode": True,
            "wrong_way_ends_episode": True,
            "time_limit_s": None,
            "reset_poses": "random",
            "start_speed_noise": 2.0,
        }
        if self.randomise:
            kw["randomisation"] = dict(RANDOMISATION)
        kw.update(self.env_overrides)
        return kw
