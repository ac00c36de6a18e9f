"""MCAP recording of ROS 2 messages (``ros2msg`` schemas, CDR payloads) that Foxglove and
``ros2 bag`` (with the MCAP storage plugin) open.

The payload of each message is exactly the XCDR1 serialisation the bridge sends on the
wire (:func:`~roboracer_arena.ros2.msgs.serialize`); each channel carries the ROS 2
QoS it was offered with (``offered_qos_profiles``) so ``ros2 bag play`` republishes the
latched topics as transient local. The target is checked before anything runs
(:func:`~roboracer_arena.foundation.fileio.check_output`); the file is written beside it and renamed
into place, with the umask's permissions, on :meth:`McapRecorder.close` (never
half-written). SIGINT and SIGTERM are held back while a message or the footer is being
written, so an interrupt lands between messages and the file can always be finished.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ..foundation.fileio import StagedFile, signals_held
from . import msgs
from ._deps import require
from .qos import DEPTH, LATCHED

_QOS_YAML = (
    "- history: 1\n  depth: {depth}\n  reliability: 1\n  durability: {durability}\n"
    "  deadline:\n    sec: 0\n    nsec: 0\n  lifespan:\n    sec: 0\n    nsec: 0\n  liveliness: 1\n"
    "  liveliness_lease_duration:\n    sec: 0\n    nsec: 0\n  avoid_ros_namespace_conventions: false\n"
)


class McapRecorder:
    """Write ROS 2 messages to an MCAP file. Thread safe; use as a context manager or call
    :meth:`close` (``abort()`` discards the file). ``inputs``: files the recording must not
    overwrite (the map it records, its config)."""

    def __init__(self, path: str | os.PathLike[str], inputs: Iterable[str | Path | None] = ()) -> None:
        require("mcap")
        from mcap.writer import CompressionType, Writer

        self._staged = StagedFile(Path(path), inputs)
        self.path = self._staged.path
        self._tmp = self._staged.tmp
        self._stream = open(self._tmp, "wb")
        self._writer = Writer(self._stream, compression=CompressionType.ZSTD)
        self._writer.start(profile="ros2", library="roboracer-arena")
        self._schemas: dict[str, int] = {}
        self._channels: dict[str, int] = {}
        self._seq = 0
        self._lock = threading.Lock()
        self.counts: dict[str, int] = {}
        self.closed = False

    def _channel(self, topic: str, typename: str) -> int:
        cid = self._channels.get(topic)
        if cid is None:
            sid = self._schemas.get(typename)
            if sid is None:
                sid = self._writer.register_schema(typename, "ros2msg", msgs.schema_text(typename).encode())
                self._schemas[typename] = sid
            qos = _QOS_YAML.format(depth=1 if topic in LATCHED else DEPTH, durability=1 if topic in LATCHED else 2)
            cid = self._writer.register_channel(topic, "cdr", sid, metadata={"offered_qos_profiles": qos})
            self._channels[topic] = cid
        return cid

    def write_cdr(self, topic: str, typename: str, data: bytes, t: float) -> None:
        """Record already serialised ``data`` on ``topic`` at ``t`` simulated seconds."""
        ns = int(round(t * 1e9))
        with self._lock, signals_held():
            if self.closed:
                return
            cid = self._channel(topic, typename)
            self._writer.add_message(cid, log_time=ns, data=data, publish_time=ns, sequence=self._seq)
            self._seq += 1
            self.counts[topic] = self.counts.get(topic, 0) + 1

    def write(self, topic: str, typename: str, msg: Any, t: float) -> None:
        """Serialise ``msg`` (an IdlStruct of ``typename``) and record it."""
        self.write_cdr(topic, typename, msgs.serialize(msg), t)

    def close(self) -> Path:
        """Finish the file and move it into place; returns its path. If finishing fails
        the temporary file is removed and the error raised."""
        with self._lock, signals_held():
            if not self.closed:
                self.closed = True
                try:
                    self._writer.finish()
                    self._stream.close()
                except BaseException:
                    self._stream.close()
                    self._staged.discard()
                    raise
                self._staged.commit()
        return self.path

    def abort(self) -> None:
        """Discard the recording."""
        with self._lock, signals_held():
            if not self.closed:
                self.closed = True
                self._stream.close()
                self._staged.discard()

    def __enter__(self) -> McapRecorder:
        return self

    def __exit__(self, exc_type: Any, *_: Any) -> None:
        if exc_type is None:
            self.close()
        else:
            self.abort()
