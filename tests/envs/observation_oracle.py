"""Test-only reference of the normalised observation: the numpy arithmetic that
``envs/observation.py`` ran every step before the core took it over
(``_core.ObservationNormaliser``), kept here verbatim so that the core can be held to
it bit for bit."""

from __future__ import annotations

import math

import numpy as np

from roboracer_arena.envs.env_config import EnvConfig


class ObservationOracle:
    """The former ``ObservationAssembler._odometry`` (normalised) and ``_frame``'s scan."""

    def __init__(self, config: EnvConfig, field_index: dict[str, int]) -> None:
        cfg = self.cfg = config.observation
        self.fields = tuple(cfg.odometry)
        self.cols = np.array([field_index[f] for f in self.fields], np.intp)
        self._xy = (field_index["x"], field_index["y"], field_index["yaw"])
        self.columns = tuple(c for f in self.fields for c in ((f"{f}_sin", f"{f}_cos") if f == "yaw" else (f,)))
        veh, lid = config.sim.vehicle, config.sim.lidar
        self._scan_scale = np.float32(1.0 / min(cfg.horizon, float(lid.range_max)))
        self._scale = {
            "vx": veh.max_speed,
            "vy": veh.max_speed,
            "speed": veh.max_speed,
            "yaw_rate": 2 * math.pi,
            "steer": veh.max_steer,
        }

    def scan(self, scans: np.ndarray) -> np.ndarray:
        scan = scans * self._scan_scale
        np.minimum(scan, 1.0, out=scan)
        return scan

    def odometry(self, state: np.ndarray, start: np.ndarray) -> np.ndarray:
        raw = state[..., self.cols]
        ix, iy, iyaw = self._xy
        dx, dy = state[..., ix] - start[..., 0], state[..., iy] - start[..., 1]
        c0, s0 = np.cos(start[..., 2]), np.sin(start[..., 2])
        rel_yaw = state[..., iyaw] - start[..., 2]
        parts = []
        for j, f in enumerate(self.fields):
            if f == "x":
                parts.append((dx * c0 + dy * s0) / self.cfg.position_scale)
            elif f == "y":
                parts.append((-dx * s0 + dy * c0) / self.cfg.position_scale)
            elif f == "yaw":
                parts += [np.sin(rel_yaw), np.cos(rel_yaw)]
            else:
                parts.append(raw[..., j] / self._scale[f])
        high = np.array([np.inf if c in ("x", "y") else 1.0 for c in self.columns])
        return np.clip(np.stack(parts, axis=-1), -high, high).astype(np.float32)
