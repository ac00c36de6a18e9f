"""Fixtures for the ROS 2 tests: a small ROS map, a random DDS domain id, and a second
DDS participant that behaves like a ROS 2 node (subscribes and publishes ROS 2 topics)."""

from __future__ import annotations

import os
import random
import subprocess
import sys
import threading
import time

import pytest

pytest.importorskip("cyclonedds", reason="needs the [ros2] extra")


@pytest.fixture
def domain_id() -> int:
    """A random domain id, so parallel test runs on one machine do not see each other."""
    return random.SystemRandom().randint(1, 200)


class RosNode:
    """A DDS participant speaking ROS 2: readers keep every sample they receive (on a
    background thread), writers publish with the ROS 2 QoS."""

    def __init__(self, domain_id: int) -> None:
        from roboracer_arena.ros2.dds import participant

        self.dp = participant(domain_id, loopback=True)
        self.samples: dict[str, list] = {}
        self.arrival: dict[str, list[float]] = {}
        self._readers: dict[str, object] = {}
        self._writers: dict[str, object] = {}
        self._topics: dict[str, object] = {}
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._spin, daemon=True)
        self._thread.start()

    def _topic(self, name: str, typename: str):
        from cyclonedds.topic import Topic

        from roboracer_arena.ros2.msgs import msg_class
        from roboracer_arena.ros2.qos import qos_for
        from roboracer_arena.ros2.topics import dds_topic

        if name not in self._topics:
            self._topics[name] = Topic(self.dp, dds_topic(name), msg_class(typename), qos=qos_for(name))
        return self._topics[name]

    def subscribe(self, name: str, typename: str) -> None:
        from cyclonedds.sub import DataReader

        from roboracer_arena.ros2.qos import qos_for

        with self._lock:
            self.samples.setdefault(name, [])
            self.arrival.setdefault(name, [])
            self._readers[name] = DataReader(self.dp, self._topic(name, typename), qos=qos_for(name))

    def publisher(self, name: str, typename: str):
        from cyclonedds.pub import DataWriter

        from roboracer_arena.ros2.qos import qos_for

        w = DataWriter(self.dp, self._topic(name, typename), qos=qos_for(name))
        self._writers[name] = w
        return w

    def _spin(self) -> None:
        while not self._stop.is_set():
            with self._lock:
                for name, r in self._readers.items():
                    got = [s for s in r.take(N=256) if s.sample_info.valid_data]
                    if got:
                        now = time.perf_counter()
                        self.samples[name].extend(got)
                        self.arrival[name].extend([now] * len(got))
            time.sleep(0.001)

    def get(self, name: str) -> list:
        with self._lock:
            return list(self.samples.get(name, []))

    def wait_for(self, name: str, count: int = 1, timeout: float = 20.0, pred=None) -> list:
        """Samples of ``name`` once ``count`` of them (matching ``pred``) arrived; fails after ``timeout``."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            got = [s for s in self.get(name) if pred is None or pred(s)]
            if len(got) >= count:
                return got
            time.sleep(0.005)
        pytest.fail(f"timed out after {timeout} s waiting for {count} sample(s) on {name} (got {len(self.get(name))})")

    def wait_matched(self, name: str, timeout: float = 20.0) -> None:
        """Wait until the writer of ``name`` has matched a reader (the bridge)."""
        w = self._writers[name]
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if w.get_matched_subscriptions():
                return
            time.sleep(0.01)
        pytest.fail(f"no subscriber matched {name} within {timeout} s")

    def wait_reader_matched(self, name: str, timeout: float = 20.0) -> None:
        """Wait until the reader of ``name`` has matched a writer (the bridge)."""
        r = self._readers[name]
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if r.get_matched_publications():
                return
            time.sleep(0.01)
        pytest.fail(f"no publisher matched {name} within {timeout} s")

    def close(self) -> None:
        self._stop.set()
        self._thread.join(5)
        self._readers.clear()
        self._writers.clear()
        self._topics.clear()
        self.dp = None


@pytest.fixture
def node_factory():
    nodes: list[RosNode] = []

    def make(domain_id: int) -> RosNode:
        nodes.append(RosNode(domain_id))
        return nodes[-1]

    yield make
    for n in nodes:
        n.close()


@pytest.fixture
def ros_node(domain_id, node_factory):
    return node_factory(domain_id)


class BridgeProcess:
    """``roboracer-arena ros2 ...`` in a subprocess (stopped by the test, bounded by --duration)."""

    def __init__(self, args: list[str], duration: float = 60.0) -> None:
        cmd = [
            sys.executable,
            "-c",
            "import sys; from roboracer_arena.cli import main; sys.exit(main())",
            "ros2",
            *args,
            "--loopback",
            "--json",
            "--duration",
            str(duration),
        ]
        env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
        self.proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)

    def stop(self, timeout: float = 20.0) -> tuple[int, str, str]:
        if self.proc.poll() is None:
            self.proc.terminate()
        try:
            out, err = self.proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            out, err = self.proc.communicate()
        return self.proc.returncode, out, err


@pytest.fixture
def bridge_process():
    procs: list[BridgeProcess] = []

    def start(args: list[str], duration: float = 60.0) -> BridgeProcess:
        p = BridgeProcess(args, duration)
        procs.append(p)
        return p

    yield start
    for p in procs:
        p.stop()
