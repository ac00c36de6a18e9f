"""The ROS 2 bridge: runs the simulator and speaks ROS 2 on the wire through DDS.

A ROS 2 node on the same domain id sees the topics of :mod:`.topics` with ROS 2 type
names and QoS (:mod:`.msgs`, :mod:`.qos`): scans, odometry, ``/tf``, ``/tf_static``,
``/clock``, ``/map``, ``/centreline`` and ``/global_path`` (``nav_msgs/Path``: the track's
minimum-curvature raceline with the car's own limits, latched); it drives the cars with ``/drive`` (and
``/opp_drive``, ``/car<i>/drive``) and resets the ego with ``/initialpose``.

Time is simulated (:mod:`.clock`): ``rate=1.0`` (default) holds it to real time,
``rate=None`` runs as fast as possible; ``lockstep=True`` advances exactly one control
period (``1/drive_hz``) per ``/drive`` message the ego receives, with that message's
command, so a run is a deterministic function of the commands sent (the other cars
keep their latest command). ``/initialpose`` puts the ego at rest at the given pose and
the other cars at rest where they are; simulated time keeps running (``/clock`` stays
monotonic).

Messages from other DDS participants follow one rule: validate, count, log once per
kind, keep running. A non-finite ``/drive`` command or ``/initialpose``, or a pose
outside the world (the track's extent plus a margin) or off its free space (inside a
wall, in an infield, beyond the outer wall: ``_core.Simulator.free_space``), is dropped; ``stats()["rejected"]``
counts them by kind and the first of each kind is logged as a warning. An error inside
the bridge stops it, but a recording is still finished (whole and readable up to then).
"""

from __future__ import annotations

import collections
import logging
import math
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np

from .._core import EVENT_WALL
from ..errors import InvalidArgumentError
from ..foundation.fileio import check_output
from . import state_msgs as sm
from .cdr import LaserScanPacker, OdometryPacker, TfPacker, pack_clock
from .clock import BridgeConfig, Pacer, Schedule
from .dds import participant, raw_writer
from .graph import announce
from .msgs import msg_class
from .qos import qos_for
from .recorder import McapRecorder
from .source import SimSource, check_open_map_starts, sim_source
from .start import fixed_poses, fixed_speeds
from .topics import CENTRELINE, CLOCK, GLOBAL_PATH, INITIALPOSE, MAP, TF, TF_STATIC, TYPE_OF, car_names, dds_topic

_POLL_S = 0.002  # longest sleep between checks for commands while pacing
#: A reset pose may lie this far (m) outside the centreline's bounding box, or half its
#: larger side if that is more; further out there are no walls and nothing to simulate.
_POSE_MARGIN_M = 10.0
_log = logging.getLogger(__name__)


class Bridge:
    """Simulator ↔ ROS 2 over DDS. ``start()`` runs it in a background thread, ``stop()``
    ends it (also a context manager). ``stats()`` reports what it did.

    Args:
        env_or_sim: a track, a ``RoboRacerArena-v0`` env or a ``_core.Simulator`` (see
            :func:`~roboracer_arena.ros2.source.sim_source`).
        cars: vehicles when the bridge builds the simulator from a track (default 1).
        domain_id: ROS 2 domain id (``ROS_DOMAIN_ID``), 0..232.
        rate: simulated seconds per wall second; None = as fast as possible.
        lockstep: one control period per ego ``/drive`` message (deterministic).
        config: rates and simulator configuration (:class:`~.clock.BridgeConfig`).
        record: optional MCAP path; everything published and every command received.
        loopback: configure DDS for the loopback interface (see :mod:`.dds`).
        dds: False runs the simulation and the recording without any DDS entity.
        seed: the simulator's seed (start noise, when configured, draws from it).
        start_poses: fixed start poses, (3,) for one car or one (x, y, yaw) per car (the
            env's reset option ``poses``; the CLI's ``--start``); default: the configured
            start (``config.start``, the env's grid start unless set otherwise).
        start_speeds: rolling-start forward speeds (m/s), one per car (reset option ``speeds``).
        stop_at: stop exactly when this much simulated time has run (seconds; None: run
            until ``stop()``); checked by the simulation thread, so it never overshoots.
    """

    def __init__(
        self,
        env_or_sim: Any,
        *,
        cars: int | None = None,
        domain_id: int = 0,
        rate: float | None = 1.0,
        lockstep: bool = False,
        config: BridgeConfig | None = None,
        record: str | Path | None = None,
        loopback: bool = False,
        dds: bool = True,
        seed: int = 0,
        start_poses: Any = None,
        start_speeds: Any = None,
        stop_at: float | None = None,
    ) -> None:
        if record is not None:  # before any work: a bad target fails now, not after the run
            check_output(record, inputs=[env_or_sim] if isinstance(env_or_sim, (str, Path)) else [])
        if stop_at is not None and not (math.isfinite(stop_at) and stop_at > 0):
            raise InvalidArgumentError(f"stop_at must be a finite number of seconds > 0, got {stop_at}")
        self.config = config or BridgeConfig()
        start = self.config.start
        if start_poses is not None:  # fixed poses: no grid to search (open maps have none to find)
            start = start.model_copy(update={"reset_poses": "centreline_start"})
        self.src: SimSource = sim_source(env_or_sim, cars=cars, config=self.config.sim, seed=seed, start=start)
        self._start_poses = fixed_poses(start_poses, self.src.vehicles)
        check_open_map_starts(self.src, self._start_poses)
        self._start_speeds = fixed_speeds(start_speeds, self.src.vehicles)
        #: Where the cars started (1, V, 3), set by :meth:`start`.
        self.start_poses: np.ndarray | None = None
        self.domain_id, self.loopback, self.use_dds = domain_id, loopback, dds
        self.lockstep = lockstep
        self.pacer = Pacer(None if lockstep else rate)
        self.record_path = None if record is None else Path(record)
        self.names = [car_names(i) for i in range(self.src.vehicles)]
        r = self.config.rates
        self.dt = float(self.src.sim.dt)
        self.control_steps = max(1, round(1.0 / (r.drive_hz * self.dt)))
        self.schedule = Schedule(self.dt, {"clock": 1 / r.clock_hz, "odom": 1 / r.odom_hz, "scan": 1 / r.scan_hz})
        E, V = self.src.num_envs, self.src.vehicles
        self.actions = np.zeros((E, V, 2))
        self.scans = np.zeros((E, V, int(self.src.sim.num_beams)), np.float32)
        self.state = np.zeros((E, V, len(self.src.fields)))
        self.events = np.zeros((E, V), np.uint8)
        self.step = 0
        self.stop_step = None if stop_at is None else max(1, math.ceil(stop_at / self.dt - 1e-9))
        line = np.asarray(self.src.centreline, float)
        lo, hi = line.min(axis=0), line.max(axis=0)
        margin = max(_POSE_MARGIN_M, 0.5 * float(np.max(hi - lo)))
        self._world = (lo - margin, hi + margin)
        self._free = self.src.sim.free_space(self.src.track_id)  # checked from any thread
        self.rejected: collections.Counter = collections.Counter()
        lid = self.src.config.lidar
        self._odom_packers = [OdometryPacker(n) for n in self.names]
        self._scan_packers = [
            LaserScanPacker(n, lid.fov, lid.range_min, lid.range_max, 1.0 / r.scan_hz) for n in self.names
        ]
        self._tf_packer = TfPacker([n.base_link for n in self.names])
        self._raw: dict[str, Any] = {}
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._dp: Any = None
        self._writers: dict[str, Any] = {}
        self._readers: dict[str, Any] = {}
        self._discovery_writer: Any = None
        self._recorder: Any = None
        self._pending_lockstep: collections.deque = collections.deque()
        self._pending_latency: list[int] = []
        self._reset_pose: tuple[float, float, float] | None = None
        self.published: collections.Counter = collections.Counter()
        self.drive_latency_s: collections.deque = collections.deque(maxlen=10_000)
        #: Per car, the simulation calls (each one control period or less) with a wall contact.
        self.wall_contact_steps = np.zeros(self.src.vehicles, np.int64)
        self.error: BaseException | None = None
        self._wall0 = self._cpu0 = 0.0
        self._periods_done = 0

    # ------------------------------------------------------------------ lifecycle
    @property
    def sim_time(self) -> float:
        return self.step * self.dt

    def start(self) -> Bridge:
        """Create the DDS entities, publish the latched topics and start simulating."""
        if self._thread is not None:
            raise RuntimeError("bridge already started")
        if self.record_path is not None:
            self._recorder = McapRecorder(self.record_path, inputs=[self.src.name])
        if self.use_dds:
            self._open_dds()
        self.start_poses = self.src.reset(self._start_poses, self._start_speeds)
        self.src.sim.observe(self.scans, self.state, self.events)
        self._publish_latched()
        self._publish_due(self.schedule.due(0))
        self._wall0, self._cpu0 = time.perf_counter(), time.process_time()
        self.pacer.reanchor(0.0)
        self._thread = threading.Thread(target=self._run, name="ros2-bridge", daemon=True)
        self._thread.start()
        return self

    def stop(self, timeout: float = 10.0) -> dict[str, Any]:
        """Stop simulating, close the recording and the DDS entities; returns :meth:`stats`."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout)
        if self._recorder is not None:
            try:  # also after an error: what was recorded until then is whole and kept
                self._recorder.close()
            except BaseException:
                self._recorder.abort()
                raise
        self._writers.clear()
        self._raw.clear()
        self._readers.clear()
        self._discovery_writer = None
        self._dp = None  # cyclonedds deletes the entities with the last reference
        return self.stats()

    def wait(self, timeout: float | None = None) -> bool:
        """Block until the bridge stops (or ``timeout``); True if it has stopped."""
        if self._thread is None:
            return True
        self._thread.join(timeout)
        return not self._thread.is_alive()

    def __enter__(self) -> Bridge:
        return self.start()

    def __exit__(self, *_: Any) -> None:
        self.stop()

    def stats(self) -> dict[str, Any]:
        """Simulated and wall time, messages published per topic, ``/drive`` latencies."""
        wall = time.perf_counter() - self._wall0 if self._wall0 else 0.0
        lat = np.asarray(self.drive_latency_s, dtype=float)
        return {
            "sim_time_s": round(self.sim_time, 6),
            "wall_time_s": round(wall, 6),
            "cpu_time_s": round(time.process_time() - self._cpu0, 3) if self._wall0 else 0.0,
            "real_time_factor": round(self.sim_time / wall, 3) if wall > 0 else None,
            "published": dict(self.published),
            "messages": int(sum(self.published.values())),
            "drive_commands": int(len(lat)),
            "drive_latency_ms": None
            if not len(lat)
            else {
                "median": round(float(np.median(lat)) * 1e3, 3),
                "p99": round(float(np.quantile(lat, 0.99)) * 1e3, 3),
                "max": round(float(lat.max()) * 1e3, 3),
            },
            "rejected": dict(self.rejected),
            "laps": [int(v) for v in self.state[0, :, self.src.fields["laps"]]] if "laps" in self.src.fields else None,
            "wall_contact_steps": [int(v) for v in self.wall_contact_steps],
            "error": None if self.error is None else repr(self.error),
        }

    # ------------------------------------------------------------------ DDS
    def _open_dds(self) -> None:
        from cyclonedds.pub import DataWriter
        from cyclonedds.sub import DataReader
        from cyclonedds.topic import Topic

        self._dp = dp = participant(self.domain_id, loopback=self.loopback)
        topics: dict[str, Any] = {}

        def topic(name: str, typename: str) -> Any:
            if name not in topics:
                topics[name] = Topic(dp, dds_topic(name), msg_class(typename), qos=qos_for(name))
            return topics[name]

        for name in (INITIALPOSE, *(n.drive for n in self.names)):  # readers first: commands are not lost
            typename = TYPE_OF[INITIALPOSE] if name == INITIALPOSE else TYPE_OF["drive"]
            self._readers[name] = DataReader(dp, topic(name, typename), qos=qos_for(name))
        outs = [(TF, TF), (TF_STATIC, TF_STATIC), (CLOCK, CLOCK), (MAP, MAP), (CENTRELINE, CENTRELINE)]
        if self.src.raceline is not None:
            outs.append((GLOBAL_PATH, GLOBAL_PATH))
        outs += [(n.scan, "scan") for n in self.names] + [(n.odom, "odom") for n in self.names]
        for name, role in outs:
            self._writers[name] = w = DataWriter(dp, topic(name, TYPE_OF[role]), qos=qos_for(name))
            self._raw[name] = raw_writer(w, msg_class(TYPE_OF[role]))
        # The bridge as a ROS 2 node (ros2 node list / info): its endpoints, by GUID.
        self._discovery_writer = announce(dp, self._readers.values(), self._writers.values())

    def _emit(self, topic: str, msg: Any, typename: str) -> None:
        w = self._writers.get(topic)
        if w is not None:
            w.write(msg)
        if self._recorder is not None:
            self._recorder.write(topic, typename, msg, self.sim_time)
        self.published[topic] += 1

    def _emit_cdr(self, topic: str, data: bytes, typename: str) -> None:
        """Publish serialised ``data`` (the bytes go to DDS and the recording unchanged)."""
        w = self._raw.get(topic)
        if w is not None:
            w(data)
        if self._recorder is not None:
            self._recorder.write_cdr(topic, typename, data, self.sim_time)
        self.published[topic] += 1

    # ------------------------------------------------------------------ publishing
    def _publish_latched(self) -> None:
        lid = self.src.config.lidar
        statics = [sm.transform(0.0, n.base_link, n.laser, lid.mount_x, 0.0, lid.mount_z, 0.0) for n in self.names]
        self._emit(TF_STATIC, sm.tf_message(statics), TYPE_OF[TF_STATIC])
        if self.src.occupancy_map is not None:
            self._emit(MAP, sm.occupancy_grid(self.src.occupancy_map), TYPE_OF[MAP])
        self._emit(CENTRELINE, sm.centreline_marker(self.src.centreline), TYPE_OF[CENTRELINE])
        if self.src.raceline is not None:
            self._emit(GLOBAL_PATH, sm.global_path(self.src.raceline), TYPE_OF[GLOBAL_PATH])

    def _publish_due(self, due: list[str]) -> None:
        t, f, st = self.sim_time, self.src.fields, self.state[0]
        if "clock" in due:
            self._emit_cdr(CLOCK, pack_clock(t), TYPE_OF[CLOCK])
        if "odom" in due:
            cols = [f[k] for k in ("x", "y", "yaw", "vx", "vy", "yaw_rate")]
            rows = st[:, cols].tolist()
            for odom_packer, n, (x, y, yaw, vx, vy, wz) in zip(self._odom_packers, self.names, rows):
                self._emit_cdr(n.odom, odom_packer.pack(t, x, y, yaw, vx, vy, wz), TYPE_OF["odom"])
            self._emit_cdr(TF, self._tf_packer.pack(t, [row[:3] for row in rows]), TYPE_OF[TF])
        if "scan" in due:
            for i, (scan_packer, n) in enumerate(zip(self._scan_packers, self.names)):
                self._emit_cdr(n.scan, scan_packer.pack(t, self.scans[0, i]), TYPE_OF["scan"])

    # ------------------------------------------------------------------ commands
    def _poll(self) -> None:
        for i, n in enumerate(self.names):
            r = self._readers.get(n.drive)
            if r is None:
                continue
            for s in r.take(N=256):
                if not s.sample_info.valid_data:
                    continue
                cmd = (float(s.drive.steering_angle), float(s.drive.speed))
                if self._recorder is not None:  # recorded as received: the log shows what peers sent
                    self._recorder.write(n.drive, TYPE_OF["drive"], s, self.sim_time)
                if not all(math.isfinite(v) for v in cmd):
                    self._reject(n.drive, "non-finite steering or speed", cmd)
                    continue
                if self.lockstep and i == 0:
                    self._pending_lockstep.append((cmd, s.sample_info.source_timestamp))
                else:
                    self.actions[:, i] = cmd
                    self._pending_latency.append(s.sample_info.source_timestamp)
        r = self._readers.get(INITIALPOSE)
        if r is not None:
            for s in r.take(N=16):
                if s.sample_info.valid_data:
                    if self._recorder is not None:
                        self._recorder.write(INITIALPOSE, TYPE_OF[INITIALPOSE], s, self.sim_time)
                    p = s.pose.pose
                    q = p.orientation
                    raw = (p.position.x, p.position.y, q.x, q.y, q.z, q.w)
                    if not all(math.isfinite(v) for v in raw) or not any(raw[2:]):
                        self._reject(INITIALPOSE, "non-finite position or orientation", raw)
                        continue
                    self.reset_ego(p.position.x, p.position.y, sm.quaternion_yaw(q))

    def _reject(self, topic: str, why: str, values: Any) -> None:
        """Count a dropped external message; log the first of each kind (no flood)."""
        key = f"{topic}: {why}"
        self.rejected[key] += 1
        if self.rejected[key] == 1:
            _log.warning("ros2 bridge: dropped %s message (%s): %s; further ones are only counted", topic, why, values)

    def drive(self, car: int, steer: float, speed: float) -> None:
        """Command car ``car`` from Python, as a ``/drive`` message would (recorded too; in
        lockstep mode an ego command is queued and advances one control period). The core
        applies the env's action rule: NaN -> 0, ±inf and out-of-range values -> the
        bounds (a ``/drive`` message with non-finite values is dropped and counted)."""
        if not 0 <= car < self.src.vehicles:
            raise IndexError(f"car {car} out of range (0..{self.src.vehicles - 1})")
        if self._recorder is not None:
            n = self.names[car]
            self._recorder.write(
                n.drive, TYPE_OF["drive"], sm.drive_command(self.sim_time, n.base_link, steer, speed), self.sim_time
            )
        if self.lockstep and car == 0:
            self._pending_lockstep.append(((float(steer), float(speed)), time.time_ns()))
        else:
            self.actions[:, car] = (steer, speed)

    def reset_ego(self, x: float, y: float, yaw: float) -> bool:
        """Put the ego at rest at (x, y, yaw) at the next step (what ``/initialpose`` does).
        A non-finite pose, one outside the world or one off the track's free space is
        dropped and counted (False)."""
        x, y, yaw = float(x), float(y), float(yaw)
        lo, hi = self._world
        if not all(math.isfinite(v) for v in (x, y, yaw)):
            self._reject(INITIALPOSE, "non-finite position or orientation", (x, y, yaw))
            return False
        if not (lo[0] <= x <= hi[0] and lo[1] <= y <= hi[1]):
            self._reject(INITIALPOSE, "position outside the world", (x, y))
            return False
        if not self._free.contains(x, y):  # the walls the simulator holds
            self._reject(INITIALPOSE, "position inside a wall or off the track", (x, y))
            return False
        self._reset_pose = (x, y, yaw)
        return True

    def _apply_reset(self) -> None:
        if self._reset_pose is None:  # (the caller checks; nothing to apply)
            return
        x, y, yaw = self._reset_pose
        self._reset_pose = None
        f = self.src.fields
        poses = np.stack([self.state[..., f["x"]], self.state[..., f["y"]], self.state[..., f["yaw"]]], axis=-1)
        poses[:, 0] = (x, y, yaw)
        self.actions[:, 0] = 0.0
        self.src.sim.reset(np.ones(self.src.num_envs, bool), poses)
        # No extra publication now: the next scheduled ones show the new pose, so every
        # stream keeps strictly increasing stamps (tf2 rejects repeated stamps).
        self.src.sim.observe(self.scans, self.state, self.events)

    # ------------------------------------------------------------------ loop
    def _run(self) -> None:
        try:
            period_end = None
            while not self._stop.is_set():
                self._poll()
                if self._reset_pose is not None:
                    self._apply_reset()
                if self.lockstep and period_end is None:
                    if not self._pending_lockstep:
                        time.sleep(0.0005)
                        continue
                    cmd, ts = self._pending_lockstep.popleft()
                    self.actions[:, 0] = cmd
                    self._pending_latency.append(ts)
                    period_end = self.step + self.control_steps
                if self.stop_step is not None and self.step >= self.stop_step:
                    break
                end = self.schedule.next_step()
                if period_end is not None:
                    end = min(end, period_end)
                if self.stop_step is not None:
                    end = min(end, self.stop_step)
                self._advance(end - self.step, scan=self.schedule.next_step_of("scan") == end)
                if period_end is not None and self.step >= period_end:
                    period_end = None
                    self._periods_done += 1
                self._pace()
        except BaseException as e:
            self.error = e

    def _advance(self, n: int, scan: bool) -> None:
        if self._pending_latency:
            now = time.time_ns()
            self.drive_latency_s.extend((now - ts) * 1e-9 for ts in self._pending_latency)
            self._pending_latency.clear()
        self.src.sim.step(self.actions, n, self.scans if scan else None, self.state, self.events)
        self.wall_contact_steps += (self.events[0] & EVENT_WALL) != 0
        self.step += n
        self._publish_due(self.schedule.due(self.step))

    def _pace(self) -> None:
        while not self._stop.is_set():
            wait = self.pacer.wait_time(self.sim_time)
            if wait <= 0:
                return
            time.sleep(min(wait, _POLL_S))
            self._poll()
