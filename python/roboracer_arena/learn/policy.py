"""A driving policy: a small tanh MLP from lidar and odometry features to a command, on
its own (``base="none"``) or as a residual on the reference pure pursuit
(``base="pure_pursuit"``, as RLPP does).

Features, per car (all in [-1, 1] or [0, 1]):

* the scan: ``num_beams`` ranges over ``fov``, each ``min(range, horizon) / horizon``;
* the car's forward speed / max_speed and its steering angle / max_steer;
* with a base: the base's steer / max_steer and speed / max_speed.

The network's two outputs ``y`` (tanh, in [-1, 1]) become ``[steer rad, speed m/s]``:

* no base: ``steer = y0 max_steer``, ``speed = lo + (hi - lo) (y1 + 1) / 2`` with ``lo, hi``
  the policy's speed range (it cannot reverse);
* residual: ``steer = base_steer + steer_residual y0 max_steer`` and
  ``speed = base_speed (1 + speed_residual y1)``, clipped to the car's limits; a zero
  network output is the base itself.

:class:`PolicySpec` is everything but the weights (the file header's content); one
:meth:`Policy.act` serves training (many parameter vectors at once), our envs, PhysX and
the ROS 2 bridge.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ..foundation.strict import NumbersAreNumbers

#: Layer shapes of the network, in file order: w0 (inputs, hidden), b0, w1 (hidden, 2), b1.
LAYERS = ("w0", "b0", "w1", "b1")


class PolicySpec(NumbersAreNumbers):
    """The observation, the network and the action of a policy: what an env must provide."""

    num_beams: int = Field(ge=2, le=100_000, description="Lidar beams the policy reads.")
    fov: float = Field(gt=0, le=2 * math.pi, description="Field of view of those beams (rad), centred ahead.")
    horizon: float = Field(gt=0, le=1e4, description="Ranges are clipped to this (m), then divided by it.")
    max_steer: float = Field(gt=0, le=1.6, description="Steering limit of the car (rad).")
    max_speed: float = Field(gt=0, le=1e3, description="Speed of a normalised speed of 1 (m/s).")
    min_speed: float = Field(ge=0, le=1e3, description="The policy never commands less (m/s).")
    base: Literal["none", "pure_pursuit"] = Field(description="Base controller the network corrects.")
    steer_residual: float = Field(0.25, ge=0, le=2, description="Residual steer range, fraction of max_steer.")
    speed_residual: float = Field(0.5, ge=0, le=0.99, description="Residual speed range, fraction of the base speed.")
    speed_range: tuple[float, float] = Field(
        (0.15, 0.6), description="No base: (low, high) fraction of max_speed the output spans."
    )
    hidden: int = Field(32, ge=1, le=4096, description="Hidden units.")
    control_rate_hz: float = Field(gt=0, le=1e4, description="Rate the policy was trained to act at (Hz).")

    @model_validator(mode="after")
    def _check(self) -> PolicySpec:
        lo, hi = self.speed_range
        if not 0 <= lo < hi <= 1:
            raise ValueError(f"speed_range must satisfy 0 <= low < high <= 1, got {self.speed_range}")
        if self.min_speed > self.max_speed:
            raise ValueError(f"min_speed ({self.min_speed}) exceeds max_speed ({self.max_speed})")
        return self

    @property
    def inputs(self) -> int:
        """Length of the feature vector."""
        return self.num_beams + 2 + (2 if self.base != "none" else 0)

    def shapes(self) -> dict[str, tuple[int, ...]]:
        """Shape of each layer array."""
        h = self.hidden
        return {"w0": (self.inputs, h), "b0": (h,), "w1": (h, 2), "b1": (2,)}

    @property
    def size(self) -> int:
        """Number of parameters."""
        return sum(math.prod(s) for s in self.shapes().values())


def init_params(spec: PolicySpec, rng: np.random.Generator) -> np.ndarray:
    """Initial flat parameters: scaled normal first layer, small output layer (a residual
    policy starts as its base, give or take a few per cent)."""
    sh = spec.shapes()
    parts = [
        rng.normal(0, 1 / math.sqrt(spec.inputs), sh["w0"]),
        np.zeros(sh["b0"]),
        rng.normal(0, 0.1 / math.sqrt(spec.hidden), sh["w1"]),
        np.zeros(sh["b1"]),
    ]
    return np.concatenate([p.ravel() for p in parts])


def unpack(spec: PolicySpec, theta: np.ndarray) -> dict[str, np.ndarray]:
    """Layer arrays (views) of flat parameters ``(..., size)``."""
    out, i = {}, 0
    for name, s in spec.shapes().items():
        n = math.prod(s)
        out[name] = theta[..., i : i + n].reshape(*theta.shape[:-1], *s)
        i += n
    return out


def pack(spec: PolicySpec, layers: dict[str, np.ndarray]) -> np.ndarray:
    """Flat parameters of layer arrays (checked against the spec's shapes)."""
    parts = []
    for name, s in spec.shapes().items():
        a = np.asarray(layers[name], dtype=np.float64)
        if a.shape != s:
            raise ValueError(f"layer {name} has shape {a.shape}, the spec needs {s}")
        parts.append(a.ravel())
    return np.concatenate(parts)


def features(
    spec: PolicySpec, scan_m: np.ndarray, speed: np.ndarray, steer: np.ndarray, base: np.ndarray | None = None
) -> np.ndarray:
    """(N, inputs) features: scans (N, num_beams) in metres, speed and steer (N,), the
    base command (N, 2) ``[steer rad, speed m/s]`` when the policy has a base. Non-finite
    ranges read as the horizon (nothing seen), non-finite odometry as 0."""
    scan = np.nan_to_num(np.asarray(scan_m, dtype=np.float64), nan=spec.horizon, posinf=spec.horizon, neginf=0.0)
    cols = [np.clip(scan / spec.horizon, 0.0, 1.0)]
    odo = np.stack([np.asarray(speed, np.float64) / spec.max_speed, np.asarray(steer, np.float64) / spec.max_steer], 1)
    cols.append(np.clip(np.nan_to_num(odo, nan=0.0, posinf=0.0, neginf=0.0), -2.0, 2.0))
    if spec.base != "none":
        if base is None:
            raise ValueError("a residual policy needs its base command")
        b = np.asarray(base, np.float64)
        cols.append(np.stack([b[:, 0] / spec.max_steer, b[:, 1] / spec.max_speed], axis=1))
    return np.concatenate(cols, axis=1)


def forward(spec: PolicySpec, theta: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Network outputs (N, 2) in [-1, 1] for parameters (N, size) or (size,) and features (N, inputs)."""
    L = unpack(spec, np.asarray(theta, dtype=np.float64))
    if L["w0"].ndim == 2:  # one parameter vector for every row
        h = np.tanh(x @ L["w0"] + L["b0"])
        return np.tanh(h @ L["w1"] + L["b1"])
    h = np.tanh(np.einsum("ni,nih->nh", x, L["w0"]) + L["b0"])
    return np.tanh(np.einsum("nh,nho->no", h, L["w1"]) + L["b1"])


def command(spec: PolicySpec, y: np.ndarray, base: np.ndarray | None = None) -> np.ndarray:
    """``[steer rad, speed m/s]`` (N, 2) of network outputs ``y`` (N, 2) (see module docstring)."""
    if spec.base == "none":
        lo, hi = spec.speed_range
        speed = spec.max_speed * (lo + (hi - lo) * 0.5 * (y[:, 1] + 1.0))
        steer = y[:, 0] * spec.max_steer
    else:
        assert base is not None
        steer = base[:, 0] + spec.steer_residual * spec.max_steer * y[:, 0]
        speed = base[:, 1] * (1.0 + spec.speed_residual * y[:, 1])
    steer = np.clip(steer, -spec.max_steer, spec.max_steer)
    speed = np.clip(speed, spec.min_speed, spec.max_speed)
    return np.stack([steer, speed], axis=1)


def act(
    spec: PolicySpec,
    theta: np.ndarray,
    scan_m: np.ndarray,
    speed: np.ndarray,
    steer: np.ndarray,
    base: np.ndarray | None = None,
) -> np.ndarray:
    """``[steer rad, speed m/s]`` (N, 2) for N cars: :func:`features`, :func:`forward`, :func:`command`."""
    b = None if base is None else np.asarray(base, np.float64)
    return command(spec, forward(spec, theta, features(spec, scan_m, speed, steer, b)), b)
