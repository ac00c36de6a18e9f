"""Cross-vendor interop: the bridge (Cyclone DDS) against a C++ node on Fast DDS, the DDS
under ROS 2's default RMW (rmw_fastrtps_cpp), built from IDL written to the ROS 2 message
definitions (tests/interop/fastdds). The node discovers the bridge with the shipped
loopback profile (``fastdds_loopback_profile()``), in both start orders, and:

* decodes scans and odometry to the values a Cyclone DDS reader of the same samples gets;
* receives ``/map`` pixel for pixel and ``/tf_static`` although it joined late (transient local);
* drives the car with ``/drive`` (commanded speed, steering sign) and places it with ``/initialpose``.

Needs cmake, g++, fastddsgen and Fast DDS 2.x (``scripts/install_fastdds.sh``); skips
without them unless ``ROBORACER_ARENA_REQUIRE_FASTDDS=1`` (CI), where it fails instead.
"""

from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest

NODE_SRC = Path(__file__).resolve().parent.parent / "interop" / "fastdds"
REQUIRED = os.environ.get("ROBORACER_ARENA_REQUIRE_FASTDDS") == "1"


def _unavailable(reason: str) -> None:
    msg = f"Fast DDS interop node cannot be built: {reason} (install with scripts/install_fastdds.sh)"
    if REQUIRED:
        pytest.fail(msg)
    pytest.skip(msg)


@pytest.fixture(scope="module")
def node_exe(request, tmp_path_factory) -> Path:
    """The interop node, built in pytest's cache folder when there is one (cmake then
    rebuilds only what changed), else in a temporary folder: about a minute on 2 cores."""
    missing = [t for t in ("cmake", "g++", "make", "fastddsgen") if shutil.which(t) is None]
    if missing:
        _unavailable(f"{', '.join(missing)} not on PATH")
    if not Path("/usr/include/fastdds/dds/domain/DomainParticipant.hpp").exists() and not os.environ.get(
        "CMAKE_PREFIX_PATH"
    ):
        _unavailable("Fast DDS headers not found (libfastrtps-dev)")
    cache = getattr(request.config, "cache", None)  # None under -p no:cacheprovider (CI)
    build = Path(cache.mkdir("fastdds-interop-node")) if cache else tmp_path_factory.mktemp("fastdds-interop-node")
    for cmd in (
        ["cmake", "-S", str(NODE_SRC), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release"],
        ["cmake", "--build", str(build), "-j", "2"],
    ):
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        if r.returncode != 0:
            pytest.fail(f"{' '.join(cmd)} failed:\n{(r.stdout + r.stderr)[-3000:]}")
    return build / "interop_node"


class FastNode:
    """The interop node in a subprocess: its JSON lines, by topic (and events)."""

    def __init__(self, exe: Path, domain_id: int, profile: Path | None) -> None:
        env = {k: v for k, v in os.environ.items() if not k.endswith("_DEFAULT_PROFILES_FILE")}
        if profile is not None:  # else Fast DDS' defaults (multicast discovery)
            env["FASTRTPS_DEFAULT_PROFILES_FILE"] = str(profile)
        self.started = time.monotonic()
        self.proc = subprocess.Popen(
            [str(exe), str(domain_id)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            env=env,
        )
        self.lines: dict[str, list[dict]] = {}
        self._lock = threading.Lock()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            rec = json.loads(line)
            with self._lock:
                self.lines.setdefault(rec["event"] if "event" in rec else rec["topic"], []).append(rec)

    def get(self, key: str) -> list[dict]:
        with self._lock:
            return list(self.lines.get(key, []))

    def wait_for(self, key: str, count: int = 1, timeout: float = 20.0, pred=None) -> list[dict]:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            got = [r for r in self.get(key) if pred is None or pred(r)]
            if len(got) >= count:
                return got
            if self.proc.poll() is not None:
                break
            time.sleep(0.01)
        err = self.proc.stderr.read() if self.proc.poll() is not None and self.proc.stderr else ""
        pytest.fail(
            f"Fast DDS node: timed out after {timeout} s waiting for {count} {key} ({len(self.get(key))}) {err}"
        )

    def send(self, cmd: str) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.write(cmd + "\n")
        self.proc.stdin.flush()
        self.wait_for("done", pred=lambda r: r["cmd"] == cmd.split()[0], count=self._sent(cmd.split()[0]))

    def _sent(self, name: str) -> int:
        self._count = getattr(self, "_count", {})
        self._count[name] = self._count.get(name, 0) + 1
        return self._count[name]

    def close(self) -> None:
        if self.proc.poll() is None:
            try:
                assert self.proc.stdin is not None
                self.proc.stdin.write("quit\n")
                self.proc.stdin.close()
            except (BrokenPipeError, OSError):
                pass
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
        self.proc.wait()


@pytest.fixture
def fast_node(node_exe, tmp_path):
    from roboracer_arena.ros2.dds import fastdds_loopback_profile

    profile = tmp_path / "fastdds_loopback.xml"
    profile.write_text(fastdds_loopback_profile())
    nodes: list[FastNode] = []

    def start(domain_id: int, shipped_profile: bool = True) -> FastNode:
        nodes.append(FastNode(node_exe, domain_id, profile if shipped_profile else None))
        return nodes[-1]

    yield start
    for n in nodes:
        n.close()


def _stamp(r) -> tuple[int, int]:
    return (r["sec"], r["nanosec"])


def _fnv1a(data: bytes) -> int:
    h = 1469598103934665603
    for b in data:
        h = ((h ^ b) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h


def _check_same_scans(fast: FastNode, ref) -> None:
    """Scans decoded by Fast DDS equal those Cyclone DDS decodes, stamp by stamp."""
    ref_scans = {(s.header.stamp.sec, s.header.stamp.nanosec): s for s in ref.wait_for("/scan", 3)}
    common = [r for r in fast.wait_for("/scan", 3) if _stamp(r) in ref_scans]
    assert common, "no scan stamp seen by both readers"
    for r in common:
        s = ref_scans[_stamp(r)]
        ranges = np.asarray(s.ranges, dtype=np.float32)
        assert r["n"] == len(ranges) == 1081 and r["frame"] == s.header.frame_id == "ego_racecar/laser"
        assert r["angle_min"] == pytest.approx(-0.75 * math.pi, abs=1e-6)
        for k in ("angle_min", "angle_max", "angle_increment", "scan_time", "range_min", "range_max"):
            assert r[k] == np.float32(getattr(s, k)), k
        assert (r["r0"], r["rmid"], r["rlast"]) == (ranges[0], ranges[540], ranges[-1])
        assert r["sum"] == pytest.approx(float(ranges.astype(np.float64).sum()), rel=1e-12)
        assert 0.1 < min(r["r0"], r["rmid"], r["rlast"]) and max(r["r0"], r["rmid"], r["rlast"]) <= r["range_max"]


def _check_same_odometry(fast: FastNode, ref) -> None:
    ref_odom = {(o.header.stamp.sec, o.header.stamp.nanosec): o for o in ref.wait_for("/ego_racecar/odom", 3)}
    common = [r for r in fast.wait_for("/ego_racecar/odom", 3) if _stamp(r) in ref_odom]
    assert common, "no odometry stamp seen by both readers"
    for r in common:
        o = ref_odom[_stamp(r)]
        p, q, t = o.pose.pose.position, o.pose.pose.orientation, o.twist.twist
        assert (r["frame"], r["child"]) == (o.header.frame_id, o.child_frame_id) == ("map", "ego_racecar/base_link")
        assert (r["x"], r["y"], r["z"]) == (p.x, p.y, p.z)
        assert (r["qx"], r["qy"], r["qz"], r["qw"]) == (q.x, q.y, q.z, q.w)
        assert (r["vx"], r["vy"], r["wz"]) == (t.linear.x, t.linear.y, t.angular.z)


def _check_latched(fast: FastNode, ref) -> None:
    """/map pixel for pixel and /tf_static, delivered to a reader however late it joined."""
    grid = ref.wait_for("/map")[0]
    m = fast.wait_for("/map")[0]
    assert (m["width"], m["height"], m["frame"]) == (grid.info.width, grid.info.height, "map")
    assert m["resolution"] == np.float32(grid.info.resolution)
    assert (m["ox"], m["oy"]) == (grid.info.origin.position.x, grid.info.origin.position.y)
    cells = bytes(v & 0xFF for v in grid.data)
    assert m["cells"] == len(cells) and int(m["fnv"]) == _fnv1a(cells)
    assert m["free"] > 0 and m["occupied"] > 0
    tf = fast.wait_for("/tf_static")[0]["transforms"]
    assert [(t["frame"], t["child"]) for t in tf] == [("ego_racecar/base_link", "ego_racecar/laser")]
    assert tf[0]["x"] == pytest.approx(0.12)


def _check_drive_and_initialpose(fast: FastNode, line: np.ndarray) -> None:
    from roboracer_arena.config.sim import SimConfig

    def after(t0: float, dt: float):
        return lambda r: r["sec"] + r["nanosec"] * 1e-9 > t0 + dt

    def now() -> float:
        o = fast.wait_for("/ego_racecar/odom")[-1]
        return o["sec"] + o["nanosec"] * 1e-9

    # Straight at 1.5 m/s: after 1.5 s the car moves at the commanded speed.
    fast.wait_for("matched", pred=lambda r: r["topic"] == "rt/drive")
    fast.send("drive 0 1.5")
    t0 = now()
    o = fast.wait_for("/ego_racecar/odom", pred=after(t0, 1.5))[-1]
    assert o["vx"] == pytest.approx(1.5, abs=0.1)
    # Steer +0.2 rad: the car turns left at about the kinematic yaw rate v tan(delta) / L.
    fast.send("drive 0.2 1.5")
    t1 = now()
    o = fast.wait_for("/ego_racecar/odom", pred=after(t1, 0.5))[-1]
    expected = o["vx"] * math.tan(0.2) / SimConfig().vehicle.wheelbase
    assert o["wz"] > 0 and o["wz"] == pytest.approx(expected, rel=0.3)
    # /initialpose: at rest where asked (half a lap round the centreline, facing along it).
    fast.send("stop")
    k = len(line) // 2
    x, y = (float(v) for v in line[k])
    yaw = math.atan2(float(line[k + 1, 1] - y), float(line[k + 1, 0] - x))
    fast.send(f"initialpose {x!r} {y!r} {yaw!r}")
    t2 = now()
    placed = fast.wait_for(
        "/ego_racecar/odom", pred=lambda r: after(t2, 0)(r) and abs(r["x"] - x) < 1e-3 and abs(r["y"] - y) < 1e-3
    )[0]
    assert 2 * math.atan2(placed["qz"], placed["qw"]) == pytest.approx(yaw, abs=1e-3)
    assert abs(placed["vx"]) < 1e-3


@pytest.mark.parametrize("order", ["node_first", "bridge_first"])
def test_fastdds_node_talks_to_the_bridge(order, ellipse_map, domain_id, ros_node, fast_node, bridge_process):
    from roboracer_arena.ros2.topics import TYPE_OF

    for name, typename in (
        ("/scan", TYPE_OF["scan"]),
        ("/ego_racecar/odom", TYPE_OF["odom"]),
        ("/map", TYPE_OF["/map"]),
        ("/centreline", TYPE_OF["/centreline"]),
    ):
        ros_node.subscribe(name, typename)
    if order == "node_first":
        fast = fast_node(domain_id)
        fast.wait_for("ready")
        proc = bridge_process([str(ellipse_map), "--domain-id", str(domain_id)])
    else:
        proc = bridge_process([str(ellipse_map), "--domain-id", str(domain_id)])
        ros_node.wait_for("/scan", 2, timeout=30)  # the bridge runs and publishes
        fast = fast_node(domain_id)
        found = fast.wait_for("/scan", timeout=30)[0]["t"]
        assert found < 5.0, f"a late-joining Fast DDS node found the bridge after {found:.1f} s"
    _check_latched(fast, ros_node)
    _check_same_scans(fast, ros_node)
    _check_same_odometry(fast, ros_node)
    marker = ros_node.wait_for("/centreline")[0]
    _check_drive_and_initialpose(fast, np.array([[p.x, p.y] for p in marker.points]))
    code, out, err = proc.stop()
    assert code == 0, err


@pytest.mark.slow
def test_late_joiners_after_the_prune_delay(ellipse_map, domain_id, ros_node, node_factory, fast_node, bridge_process):
    """Nodes that start long after the bridge find it: Fast DDS with the shipped profile
    and Cyclone DDS with ``loopback_config`` in < 5 s. Even a Fast DDS node left at its
    defaults (multicast only, which loopback does not carry) finds it, because the bridge
    keeps announcing itself to the loopback participant ports (Cyclone DDS stops after
    30 s by default: such a node then never found it)."""
    from roboracer_arena.ros2.topics import TYPE_OF

    ros_node.subscribe("/scan", TYPE_OF["scan"])
    ros_node.subscribe("/map", TYPE_OF["/map"])
    proc = bridge_process([str(ellipse_map), "--domain-id", str(domain_id)], duration=120)
    ros_node.wait_for("/scan", timeout=30)
    time.sleep(35)
    t0 = time.perf_counter()  # the clock RosNode stamps arrivals with
    late = node_factory(domain_id)
    late.subscribe("/scan", TYPE_OF["scan"])
    fast = fast_node(domain_id)
    default = fast_node(domain_id, shipped_profile=False)
    late.wait_for("/scan", timeout=30)
    cyclone_found = late.arrival["/scan"][0] - t0
    fast_found = fast.wait_for("/scan", timeout=30)[0]["t"]
    default_found = default.wait_for("/scan", timeout=30)[0]["t"]
    print(
        f"late joiners found the bridge after: cyclone {cyclone_found:.2f} s, fastdds {fast_found:.2f} s, "
        f"fastdds defaults {default_found:.2f} s"
    )
    assert fast_found < 5.0, f"the late Fast DDS node found the bridge after {fast_found:.1f} s"
    assert cyclone_found < 5.0, f"the late Cyclone DDS node found the bridge after {cyclone_found:.1f} s"
    assert default_found < 15.0, f"the late Fast DDS node at its defaults found the bridge after {default_found:.1f} s"
    _check_latched(fast, ros_node)
    proc.stop()
