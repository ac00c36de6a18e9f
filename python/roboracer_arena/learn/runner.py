"""Run a policy in one of our envs (single env or native vector env, every car): read the
simulator's scans and state, compute the base controller's command where the policy has
one, and return the env's action. Training (one parameter vector per env) and driving
(one policy for every car) share it.

:func:`scan_indices` is the one rule for which beams of a scan the policy reads: the
same field of view, and either the same beam count or a count whose beams include the
policy's evenly (e.g. 1081 beams read every 20th for a 55-beam policy).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..drivers import PurePursuitParams
from ..envs.env_config import EnvConfig
from ..errors import PolicyFileError
from .policy import PolicySpec, act
from .pursuit_base import PursuitBase

#: Relative tolerance on the field of view, control rate and steering limit of an env.
_TOL = 1e-6


def scan_indices(spec: PolicySpec, num_beams: int, fov: float) -> np.ndarray:
    """Indices of the beams of a ``num_beams`` scan over ``fov`` the policy reads;
    :class:`PolicyFileError` if that scan does not hold the policy's beams."""
    if not math.isclose(fov, spec.fov, rel_tol=_TOL):
        raise PolicyFileError(f"the policy reads a lidar of fov {spec.fov:.6g} rad; this one has {fov:.6g} rad")
    if num_beams == spec.num_beams:
        return np.arange(num_beams)
    stride, rest = divmod(num_beams - 1, spec.num_beams - 1)
    if rest or stride < 1:
        raise PolicyFileError(
            f"the policy reads {spec.num_beams} beams; a scan of {num_beams} beams over the same fov does not hold "
            f"them (it needs {spec.num_beams} or (k * {spec.num_beams - 1} + 1) beams)"
        )
    return np.arange(0, num_beams, stride)


def check_env(spec: PolicySpec, config: Any) -> np.ndarray:
    """Refuse (:class:`PolicyFileError`) an env config the policy does not fit; return the
    scan indices it reads (:func:`scan_indices`)."""
    lid, veh = config.sim.lidar, config.sim.vehicle
    if not config.observation.scan:
        raise PolicyFileError("the policy reads the lidar; this env's observation has no scan")
    idx = scan_indices(spec, int(lid.num_beams), float(lid.fov))
    if not math.isclose(config.control_rate_hz, spec.control_rate_hz, rel_tol=_TOL):
        raise PolicyFileError(
            f"the policy acts at {spec.control_rate_hz:g} Hz; this env's control rate is {config.control_rate_hz:g} Hz"
        )
    if not math.isclose(veh.max_steer, spec.max_steer, rel_tol=_TOL):
        raise PolicyFileError(f"the policy steers to {spec.max_steer:g} rad; this car's limit is {veh.max_steer:g} rad")
    return idx


def base_params(config: Any, pursuit: dict[str, Any] | None = None) -> PurePursuitParams:
    """The base pure pursuit's parameters for an env's car (``pursuit`` overrides, as stored
    in a policy file's ``env.pure_pursuit``)."""
    veh = config.sim.vehicle
    kw: dict[str, Any] = {"max_steer": float(veh.max_steer), "wheelbase": float(veh.wheelbase)}
    kw.update(pursuit or {})
    return PurePursuitParams(**kw)


class PolicyRunner:
    """Acts for every car of ``env`` with a policy of ``spec`` (see the module docstring)."""

    def __init__(self, env: Any, spec: PolicySpec, pursuit: dict[str, Any] | None = None) -> None:
        self.env = env.unwrapped
        self.spec = spec
        self._beams = check_env(spec, self.env.config)
        self._vector = hasattr(self.env, "num_envs")
        self.base: PursuitBase | None = None
        if spec.base == "pure_pursuit":
            lines = [t.centreline for t in self.env.tracks]
            self.base = PursuitBase(lines, base_params(self.env.config, pursuit))

    def reset(self, cars: Any = slice(None)) -> None:
        """Forget the base's projection of ``cars`` (flat car indices; after their reset)."""
        if self.base is not None:
            self.base.reset(cars)

    def commands(self, theta: np.ndarray) -> np.ndarray:
        """``[steer rad, speed m/s]`` (N, 2) of every car (env-major), for parameters
        ``theta`` (size,) or one row per car (N, size)."""
        env = self.env
        state, f = env.simulator_state
        scans = env.simulator_scans
        v = env.vehicles_per_env
        state = state.reshape(-1, state.shape[-1])
        scans = scans.reshape(-1, scans.shape[-1])[:, self._beams]
        ids = np.atleast_1d(env.current_track_ids if self._vector else env.current_track_id)
        speed, steer = state[:, f["vx"]], state[:, f["steer"]]
        base = None
        if self.base is not None:
            base = np.stack(
                self.base.act(np.repeat(ids, v), state[:, f["x"]], state[:, f["y"]], state[:, f["yaw"]], speed), 1
            )
        return act(self.spec, theta, scans, speed, steer, base)

    def act(self, theta: np.ndarray) -> np.ndarray:
        """The env's action (its action mode and shape) for :meth:`commands`."""
        cmds = self.commands(theta)
        v = self.env.vehicles_per_env
        shape = (self.env.num_envs, v, 2) if self._vector else (v, 2)
        return self.env.from_ackermann(cmds.reshape(shape))


class PolicyDriver:
    """A trained policy as a driver of an env, like the reference pure pursuit's
    :class:`~roboracer_arena.drivers.EnvPurePursuit`: ``act(obs)`` returns the env's action
    for every car (the observation itself is not read: the policy reads the simulator's
    scan and state, so any observation config works)."""

    def __init__(self, env: Any, policy: Any) -> None:
        self.policy = policy
        self.runner = PolicyRunner(env, policy.spec, policy.env.get("pure_pursuit"))

    def act(self, obs: Any = None) -> np.ndarray:
        return self.runner.act(self.policy.theta)

    def reset(self) -> None:
        self.runner.reset()


def policy_controller(policy: Any, track: Any, lidar_beams: int, lidar_fov: float, config: Any = None) -> Any:
    """A trained policy as a ``controller(scan, odometry) -> (steer, speed)`` for one car
    on ``track`` in any engine (PhysX, the ROS 2 bridge): ``scan`` is that engine's ranges
    (m) of ``lidar_beams`` beams over ``lidar_fov`` (the policy reads its own beams of
    them, :func:`scan_indices`), ``odometry`` a mapping with ``x, y, yaw`` (map frame),
    ``vx`` (forward speed) and ``steer``. ``config``: the env config whose car the base
    pure pursuit steers (default :class:`~roboracer_arena.envs.env_config.EnvConfig`)."""
    spec = policy.spec
    beams = scan_indices(spec, int(lidar_beams), float(lidar_fov))
    base = None
    if spec.base == "pure_pursuit":
        base = PursuitBase([track.centreline], base_params(config or EnvConfig(), policy.env.get("pure_pursuit")))
    zero = np.zeros(1, np.int64)

    def act(scan: np.ndarray, odo: Any) -> tuple[float, float]:
        ranges = np.asarray(scan, np.float64).reshape(-1)[beams][None]
        b = None
        if base is not None:
            b = np.stack(base.act(zero, odo["x"], odo["y"], odo["yaw"], odo["vx"]), 1)
        cmd = policy.act(ranges, odo["vx"], odo["steer"], b)
        return float(cmd[0, 0]), float(cmd[0, 1])

    return act
