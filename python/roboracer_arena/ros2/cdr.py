"""Fast CDR packers for the bridge's high-rate messages (scan, odometry, ``/tf``, ``/clock``).

A car's frame names never change, so each of these messages has a fixed XCDR1 layout
(little endian, 4-byte encapsulation header, primitives aligned to their size from the
end of the header); one precompiled :class:`struct.Struct` per layout packs a message
from plain numbers in a few microseconds, where building and serialising the
``cyclonedds`` IdlStruct takes about a hundred. The bytes are identical to
``msgs.serialize`` of the :mod:`.state_msgs` builders (and to rosbags', see the tests).
Messages published once (``/map``, ``/tf_static``, the marker) use the IdlStructs.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Sequence

import numpy as np

from .topics import MAP_FRAME, CarNames

HEADER = b"\x00\x01\x00\x00"  # CDR little endian, no options
_ZEROS36 = (0.0,) * 36


class _Layout:
    """Builds a struct format while tracking the CDR offset (for alignment)."""

    def __init__(self) -> None:
        self.fmt, self.off = ["<"], 0

    def prim(self, code: str, size: int, count: int = 1) -> None:
        pad = (-self.off) % size
        if pad:
            self.fmt.append(f"{pad}x")
        self.fmt.append(f"{count}{code}")
        self.off += pad + size * count

    def string(self, s: str) -> tuple[int, bytes]:
        """A string field: uint32 length (with the NUL), the bytes, the NUL. Returns its values."""
        b = s.encode()
        self.prim("I", 4)
        self.fmt.append(f"{len(b) + 1}s")
        self.off += len(b) + 1
        return len(b) + 1, b

    def struct(self) -> struct.Struct:
        return struct.Struct("".join(self.fmt))


def _sec_nsec(t: float) -> tuple[int, int]:
    ns = int(round(t * 1e9))
    return ns // 1_000_000_000, ns % 1_000_000_000


def pack_clock(t: float) -> bytes:
    """``rosgraph_msgs/Clock``."""
    return HEADER + struct.pack("<iI", *_sec_nsec(t))


class OdometryPacker:
    """``nav_msgs/Odometry`` of one car (see :func:`.state_msgs.odometry`)."""

    def __init__(self, names: CarNames) -> None:
        lay = _Layout()
        lay.prim("i", 4)
        lay.prim("I", 4)
        self._frame = lay.string(MAP_FRAME)
        self._child = lay.string(names.base_link)
        lay.prim("d", 8, 7 + 36 + 6 + 36)
        self._s = lay.struct()

    def pack(self, t: float, x: float, y: float, yaw: float, vx: float, vy: float, yaw_rate: float) -> bytes:
        sec, nsec = _sec_nsec(t)
        return HEADER + self._s.pack(
            sec,
            nsec,
            *self._frame,
            *self._child,
            x,
            y,
            0.0,
            0.0,
            0.0,
            math.sin(yaw / 2),
            math.cos(yaw / 2),
            *_ZEROS36,
            vx,
            vy,
            0.0,
            0.0,
            0.0,
            yaw_rate,
            *_ZEROS36,
        )


class TfPacker:
    """``tf2_msgs/TFMessage`` of ``map`` → each car's ``base_link`` (planar poses)."""

    def __init__(self, children: Sequence[str], parent: str = MAP_FRAME) -> None:
        lay = _Layout()
        lay.prim("I", 4)
        self._strings = []
        for child in children:
            lay.prim("i", 4)
            lay.prim("I", 4)
            parent_v = lay.string(parent)
            child_v = lay.string(child)
            lay.prim("d", 8, 7)
            self._strings.append((parent_v, child_v))
        self._n = len(children)
        self._s = lay.struct()

    def pack(self, t: float, poses: Sequence[tuple[float, float, float]]) -> bytes:
        sec, nsec = _sec_nsec(t)
        vals: list = [self._n]
        for ((pl, pb), (cl, cb)), (x, y, yaw) in zip(self._strings, poses):
            vals += (sec, nsec, pl, pb, cl, cb, x, y, 0.0, 0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))
        return HEADER + self._s.pack(*vals)


class LaserScanPacker:
    """``sensor_msgs/LaserScan`` of one car (see :func:`.state_msgs.laser_scan`)."""

    def __init__(self, names: CarNames, fov: float, range_min: float, range_max: float, scan_time: float) -> None:
        lay = _Layout()
        lay.prim("i", 4)
        lay.prim("I", 4)
        self._frame = lay.string(names.laser)
        lay.prim("f", 4, 7)
        lay.prim("I", 4)  # ranges count; float32 elements follow, aligned (offset is a multiple of 4)
        self._s = lay.struct()
        self._fixed = (fov, range_min, range_max, scan_time)

    def pack(self, t: float, ranges: np.ndarray) -> bytes:
        sec, nsec = _sec_nsec(t)
        fov, rmin, rmax, scan_time = self._fixed
        n = len(ranges)
        inc = fov / (n - 1) if n > 1 else 0.0
        head = self._s.pack(sec, nsec, *self._frame, -fov / 2, fov / 2, inc, 0.0, scan_time, rmin, rmax, n)
        return b"".join((HEADER, head, np.ascontiguousarray(ranges, dtype="<f4").tobytes(), b"\0\0\0\0"))
