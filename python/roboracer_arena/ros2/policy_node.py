"""A trained policy as a ROS 2 node over DDS, the way a racing stack runs it: it
subscribes to a car's ``/scan`` (``sensor_msgs/LaserScan``), its odometry
(``nav_msgs/Odometry``) and ``/clock``, and publishes ``/drive``
(``ackermann_msgs/AckermannDriveStamped``) on a timer in simulated time at the policy's
control rate, from the newest scan and odometry (as a ROS 2 node with
``use_sim_time`` and a wall timer does; in the bridge's lockstep mode every control
period waits for its command, so the run is deterministic). It knows the track only as a
racing stack does, from the map (the base pure pursuit follows its centreline), and the
steering angle as the last one it commanded (odometry carries no steering).

``roboracer-arena ros2 MAP --policy FILE`` runs one beside the bridge, on the wire: the
bridge cannot tell it from any other ROS 2 node.
"""

from __future__ import annotations

import math
import threading
import time
from typing import Any

import numpy as np

from ..learn.runner import policy_controller
from .dds import participant
from .msgs import msg_class
from .qos import qos_for
from .topics import CLOCK, TYPE_OF, car_names, dds_topic

#: How long the node's thread sleeps between polls (s).
_POLL_S = 0.0005
#: After the clock reaches a control instant, wait this long (wall s) for that instant's
#: scan and odometry, which the bridge publishes just after the clock.
_GRACE_S = 0.003


def _yaw(q: Any) -> float:
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


class PolicyNode:
    """Drives car ``car`` of a bridge on ``domain_id`` with ``policy`` on ``track``."""

    def __init__(self, policy: Any, track: Any, domain_id: int, *, car: int = 0, loopback: bool = False) -> None:
        from cyclonedds.pub import DataWriter
        from cyclonedds.sub import DataReader
        from cyclonedds.topic import Topic

        self.policy, self.track = policy, track
        self.names = names = car_names(car)
        self._dp = dp = participant(domain_id, loopback=loopback)

        def topic(name: str, role: str) -> Any:
            return Topic(dp, dds_topic(name), msg_class(TYPE_OF[role]), qos=qos_for(name))

        self._scan = DataReader(dp, topic(names.scan, "scan"), qos=qos_for(names.scan))
        self._odom = DataReader(dp, topic(names.odom, "odom"), qos=qos_for(names.odom))
        self._clock = DataReader(dp, topic(CLOCK, CLOCK), qos=qos_for(CLOCK))
        self._drive = DataWriter(dp, topic(names.drive, "drive"), qos=qos_for(names.drive))
        self._drive_cls = msg_class(TYPE_OF["drive"])
        self._period = 1.0 / float(policy.spec.control_rate_hz)
        self._controller: Any = None
        self._layout: tuple[int, float] | None = None
        self._odo: dict[str, float] | None = None
        self._scan_msg: Any = None
        self._due = 0.0  # next control instant (simulated s)
        self._ready_at: float | None = None  # wall time the due instant's data is awaited until
        self._steer = 0.0
        self.commands = 0
        self.error: BaseException | None = None
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._spin, name="policy-node", daemon=True)

    def start(self) -> PolicyNode:
        self._thread.start()
        return self

    def stop(self) -> None:
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(5.0)

    def _spin(self) -> None:
        try:
            while not self._stop.is_set():
                self._take()
                if self._ready_at is not None and time.monotonic() >= self._ready_at:
                    self._ready_at = None
                    self._act()
                time.sleep(_POLL_S)
        except BaseException as e:  # reported by the caller (stats), never a silent stop
            self.error = e

    def _take(self) -> None:
        for s in self._odom.take(N=64):
            if s.sample_info.valid_data:
                p, tw = s.pose.pose, s.twist.twist
                self._odo = {"x": p.position.x, "y": p.position.y, "yaw": _yaw(p.orientation), "vx": tw.linear.x}
        for s in self._scan.take(N=64):
            if s.sample_info.valid_data:
                self._scan_msg = s
        for s in self._clock.take(N=64):
            if s.sample_info.valid_data:
                t = s.clock.sec + 1e-9 * s.clock.nanosec
                if t >= self._due - 1e-6 and self._ready_at is None:
                    self._ready_at = time.monotonic() + _GRACE_S
                    self._now = s.clock

    def _act(self) -> None:
        if self._scan_msg is None or self._odo is None:
            self._ready_at = time.monotonic() + _GRACE_S  # nothing seen yet: keep waiting
            return
        msg = self._scan_msg
        ranges = np.asarray(msg.ranges, dtype=np.float64)
        layout = (len(ranges), float(msg.angle_increment) * (len(ranges) - 1))
        if self._controller is None or layout != self._layout:
            self._controller = policy_controller(self.policy, self.track, layout[0], layout[1])
            self._layout = layout
        steer, speed = self._controller(ranges, {**self._odo, "steer": self._steer})
        self._steer = steer
        now = self._now.sec + 1e-9 * self._now.nanosec
        self._due = now + self._period
        self._publish(self._now, steer, speed)

    def _publish(self, stamp: Any, steer: float, speed: float) -> None:
        m = self._drive_cls()
        m.header.stamp = stamp
        m.header.frame_id = self.names.base_link
        m.drive.steering_angle = float(steer)
        m.drive.speed = float(speed)
        self._drive.write(m)
        self.commands += 1
