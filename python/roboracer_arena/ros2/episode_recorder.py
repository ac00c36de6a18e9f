"""A gymnasium wrapper that records a ``RoboRacerArena-v0`` env's episodes to MCAP.

Every ``reset`` and ``step`` writes, stamped with the simulated time (which keeps
running across episodes so the file's clock is monotonic), each car's scan and odometry,
``/tf`` and ``/clock``, and each step's drive command (the sanitised ``[steer, speed]``
the simulator received) as ``ackermann_msgs/AckermannDriveStamped`` on the car's drive
topic. ``/tf_static``, the centreline marker and ``/map`` (when the track came from a
map) are written once per track. Topic names are the bridge's (:mod:`.topics`).
``close()`` finishes the file and ``abort()`` discards it; a recorder never closed
removes its temporary file when collected or at exit (never a stray hidden file).

Attributes the wrapped env exposes (``odometry_raw``, ``simulator_state``, ...) are
forwarded, so drivers written for the env work on the wrapper too.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import gymnasium as gym
import numpy as np

from . import state_msgs as sm
from .recorder import McapRecorder
from .source import _load_map
from .topics import CENTRELINE, CLOCK, MAP, TF, TF_STATIC, TYPE_OF, car_names

if TYPE_CHECKING:
    from ..envs.batch import SimBatch
    from ..envs.single import RoboRacerEnv


class McapEpisodeRecorder(gym.Wrapper):
    """Record a single ``RoboRacerArena-v0`` env to ``path`` (see module docstring)."""

    def __init__(self, env: gym.Env, path: str | Path) -> None:
        super().__init__(env)
        from ..envs.single import RoboRacerEnv  # here: the envs package is heavy and optional for ros2 users

        inner = env.unwrapped
        if not isinstance(inner, RoboRacerEnv):
            raise TypeError("McapEpisodeRecorder wraps a RoboRacerArena-v0 single env")
        self._inner: RoboRacerEnv = inner
        self._batch: SimBatch = inner._batch
        self._names = [car_names(i) for i in range(inner.config.vehicles_per_env)]
        self._dt = inner.config.control_dt
        self._t = 0.0
        self._steps = 0
        self._tracks_done: set[int] = set()
        self.episodes = 0
        # Last: nothing after it can fail and leave the temporary file open.
        self.recorder = McapRecorder(path, inputs=[t.source for t in inner.tracks if isinstance(t.source, (str, Path))])

    def __getattr__(self, name: str) -> Any:  # forward env helpers (gymnasium>=1.0 does not)
        if name.startswith("_"):
            raise AttributeError(name)
        return getattr(self.env.unwrapped, name)

    def reset(self, **kwargs: Any):
        obs, info = self.env.reset(**kwargs)
        if self._steps:
            self._t += self._dt  # the new episode starts one control period after the last step
        self.episodes += 1
        self._write_track()
        self._write_state(scan=True)
        return obs, info

    def step(self, action: Any):
        obs, reward, terminated, truncated, info = self.env.step(action)
        self._steps += 1
        t_cmd = self._t
        self._t += self._dt
        b, rec = self._batch, self.recorder
        for i, n in enumerate(self._names):
            steer, speed = (float(v) for v in b.actions[0, i])
            rec.write(n.drive, TYPE_OF["drive"], sm.drive_command(t_cmd, n.base_link, steer, speed), t_cmd)
        self._write_state(scan=True)
        return obs, reward, terminated, truncated, info

    def close(self) -> None:
        """Finish the recording (whole and readable up to the last step) and close the env."""
        try:
            self.recorder.close()
        finally:
            super().close()

    def abort(self) -> None:
        """Discard the recording (its temporary file) and close the env."""
        try:
            self.recorder.abort()
        finally:
            super().close()

    # ------------------------------------------------------------------ helpers
    def _write_track(self) -> None:
        inner, rec, t = self._inner, self.recorder, self._t
        tid = int(self._batch.track_ids[0])
        if tid in self._tracks_done:
            return
        self._tracks_done.add(tid)
        track, lid = inner.tracks[tid], inner.config.sim.lidar
        statics = [sm.transform(t, n.base_link, n.laser, lid.mount_x, 0.0, lid.mount_z, 0.0) for n in self._names]
        rec.write(TF_STATIC, TYPE_OF[TF_STATIC], sm.tf_message(statics), t)
        occ = _load_map(track.source)
        if occ is not None:
            rec.write(MAP, TYPE_OF[MAP], sm.occupancy_grid(occ, t), t)
        rec.write(CENTRELINE, TYPE_OF[CENTRELINE], sm.centreline_marker(track.centreline, t), t)

    def _write_state(self, scan: bool) -> None:
        b, rec, t = self._batch, self.recorder, self._t
        f, st = b.field_index, b.state[0]
        lid = self._inner.config.sim.lidar
        rec.write(CLOCK, TYPE_OF[CLOCK], sm.clock(t), t)
        tfs = []
        for i, n in enumerate(self._names):
            x, y, yaw = (float(st[i, f[k]]) for k in ("x", "y", "yaw"))
            rec.write(
                n.odom,
                TYPE_OF["odom"],
                sm.odometry(n, t, x, y, yaw, float(st[i, f["vx"]]), float(st[i, f["vy"]]), float(st[i, f["yaw_rate"]])),
                t,
            )
            tfs.append(sm.transform(t, "map", n.base_link, x, y, 0.0, yaw))
            if scan and self._inner.config.observation.scan:
                ranges = np.clip(b.scans[0, i], lid.range_min, lid.range_max)
                rec.write(
                    n.scan,
                    TYPE_OF["scan"],
                    sm.laser_scan(n, t, ranges, lid.fov, lid.range_min, lid.range_max, 1.0 / lid.rate_hz),
                    t,
                )
        rec.write(TF, TYPE_OF[TF], sm.tf_message(tfs), t)
