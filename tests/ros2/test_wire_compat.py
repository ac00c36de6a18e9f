"""Wire compatibility: for every message type, our CDR bytes equal what ``rosbags``'
ROS 2 (Humble) typestore produces for the same message, field for field.

``ackermann_msgs`` is not in rosbags' store; it is registered from the upstream
``.msg`` text (ros-drivers/ackermann_msgs), written here independently of our table.
"""

from __future__ import annotations

import dataclasses
import random
import string

import numpy as np
import pytest

from roboracer_arena.ros2 import msgs
from roboracer_arena.ros2 import state_msgs as sm
from roboracer_arena.ros2.topics import car_names

rosbags_typesys = pytest.importorskip("rosbags.typesys")

ACKERMANN_UPSTREAM = {
    "ackermann_msgs/msg/AckermannDrive": (
        "float32 steering_angle\nfloat32 steering_angle_velocity\nfloat32 speed\nfloat32 acceleration\nfloat32 jerk\n"
    ),
    "ackermann_msgs/msg/AckermannDriveStamped": "std_msgs/Header header\nAckermannDrive drive\n",
}


@pytest.fixture(scope="module")
def typestore():
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    ts = get_typestore(Stores.ROS2_HUMBLE)
    types = {}
    for name, text in ACKERMANN_UPSTREAM.items():
        types.update(get_types_from_msg(text, name))
    ts.register(types)
    return ts


def _random_value(ftype: str, rng: random.Random):
    if ftype == "bool":
        return rng.random() < 0.5
    if ftype == "string":
        return "".join(rng.choice(string.ascii_letters + "/_") for _ in range(rng.randint(0, 13)))
    if ftype.startswith("float"):
        v = rng.uniform(-1e3, 1e3)
        return float(np.float32(v)) if ftype == "float32" else v
    bits = int(ftype.lstrip("uint")) if ftype.startswith(("int", "uint")) else 8
    lo, hi = (0, 2**bits - 1) if ftype.startswith("uint") else (-(2 ** (bits - 1)), 2 ** (bits - 1) - 1)
    return rng.randint(lo, hi)


def random_msg(typename: str, rng: random.Random):
    """A message of ``typename`` with every field random (odd sequence lengths and string
    sizes to exercise CDR alignment)."""
    cls = msgs.msg_class(typename)
    kwargs = {}
    for f in msgs.parse_fields(typename):

        def one(f=f):
            return random_msg(f.type, rng) if f.type in msgs.DEFINITIONS else _random_value(f.type, rng)

        if f.array is None:
            kwargs[f.name] = one()
        else:
            kwargs[f.name] = [one() for _ in range(f.array if f.array >= 0 else rng.choice([0, 1, 3, 5]))]
    return cls(**kwargs)


def _same(ours, theirs, where: str) -> None:
    """Field-by-field equality of our message and rosbags' (names and values)."""
    their_fields = [
        f.name for f in dataclasses.fields(theirs) if not f.name.startswith("__") and not f.name.isupper()
    ]  # constants
    our_fields = [f.name for f in dataclasses.fields(ours)]
    assert our_fields == their_fields, f"{where}: fields differ"
    for name in their_fields:
        a, b = getattr(ours, name), getattr(theirs, name)
        if dataclasses.is_dataclass(b):
            _same(a, b, f"{where}.{name}")
        elif isinstance(b, np.ndarray):
            assert np.array_equal(np.asarray(a, dtype=b.dtype), b), f"{where}.{name}"
        elif isinstance(b, list):
            assert len(a) == len(b), f"{where}.{name}"
            for k, (x, y) in enumerate(zip(a, b)):
                _same(x, y, f"{where}.{name}[{k}]")
        elif isinstance(b, float) and a != b:  # a float32 field holds our float64 rounded
            assert float(np.float32(a)) == b, f"{where}.{name}: {a!r} != {b!r}"
        else:
            assert a == b, f"{where}.{name}: {a!r} != {b!r}"


def _check(msg, typename: str, typestore) -> None:
    ours = msgs.serialize(msg)
    assert ours[:4] == b"\x00\x01\x00\x00"  # CDR little endian, no options
    decoded = typestore.deserialize_cdr(ours, typename)
    _same(msg, decoded, typename)  # rosbags reads back exactly the values we wrote
    assert typestore.serialize_cdr(decoded, typename) == ours  # and writes exactly our bytes


@pytest.mark.parametrize("typename", sorted(msgs.DEFINITIONS))
def test_every_type_serialises_like_rosbags(typename, typestore):
    rng = random.Random(typename)
    for _ in range(5):
        _check(random_msg(typename, rng), typename, typestore)


def test_the_bridge_messages_serialise_like_rosbags(typestore):
    """The messages the bridge actually builds from simulator state."""
    n = car_names(0)
    ranges = np.random.default_rng(0).uniform(0.1, 30, 1081).astype(np.float32)
    occ = type(
        "Occ",
        (),
        {"data": np.array([[0, 254, 205], [254, 254, 0]], np.uint8), "resolution": 0.05, "origin": (-1.0, -2.0, 0.0)},
    )()
    cases = [
        (sm.laser_scan(n, 1.25, ranges, 1.5 * np.pi, 0.0, 30.0, 1 / 39.9), "sensor_msgs/msg/LaserScan"),
        (sm.odometry(n, 3.0, 1.0, -2.0, 0.3, 1.5, 0.01, 0.2), "nav_msgs/msg/Odometry"),
        (sm.tf_message([sm.transform(0.5, "map", n.base_link, 1, 2, 0, 0.1)]), "tf2_msgs/msg/TFMessage"),
        (sm.clock(123.456), "rosgraph_msgs/msg/Clock"),
        (sm.occupancy_grid(occ), "nav_msgs/msg/OccupancyGrid"),
        (sm.centreline_marker(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])), "visualization_msgs/msg/Marker"),
        (sm.drive_command(0.05, n.base_link, 0.1, 1.5), "ackermann_msgs/msg/AckermannDriveStamped"),
        (sm.global_path(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])), "nav_msgs/msg/Path"),
    ]
    for msg, typename in cases:
        _check(msg, typename, typestore)
    grid = typestore.deserialize_cdr(msgs.serialize(cases[4][0]), "nav_msgs/msg/OccupancyGrid")
    assert grid.data.tolist() == [0, 0, 100, 100, 0, -1]  # bottom row first, ROS values


def test_dds_type_and_topic_names():
    from roboracer_arena.ros2.topics import dds_topic

    assert msgs.dds_type_name("sensor_msgs/msg/LaserScan") == "sensor_msgs::msg::dds_::LaserScan_"
    assert msgs.msg_class("nav_msgs/msg/Odometry").__idl_typename__ == "nav_msgs::msg::dds_::Odometry_"
    assert dds_topic("/ego_racecar/odom") == "rt/ego_racecar/odom"
    with pytest.raises(ValueError):
        dds_topic("scan")


def test_schema_text_lists_every_dependency_once():
    text = msgs.schema_text("nav_msgs/msg/Odometry")
    deps = [line[5:] for line in text.splitlines() if line.startswith("MSG: ")]
    assert len(deps) == len(set(deps))
    assert {
        "std_msgs/Header",
        "builtin_interfaces/Time",
        "geometry_msgs/PoseWithCovariance",
        "geometry_msgs/Twist",
        "geometry_msgs/Quaternion",
    } <= set(deps)


def test_fast_packers_match_the_idl_serialisation(typestore):
    """The bridge publishes its high-rate messages with precompiled packers; their bytes
    equal the IdlStruct serialisation of the same message (and so rosbags')."""
    from roboracer_arena.ros2 import cdr

    rng = np.random.default_rng(1)
    for i in range(4):
        n = car_names(i)
        for t in (0.0, 0.02, 1.2345, 86400.5):
            x, y, yaw, vx, vy, wz = rng.normal(size=6) * 10
            got = cdr.OdometryPacker(n).pack(t, x, y, yaw, vx, vy, wz)
            msg = sm.odometry(n, t, x, y, yaw, vx, vy, wz)
            assert got == msgs.serialize(msg)
            _check(msg, "nav_msgs/msg/Odometry", typestore)
            ranges = rng.uniform(0, 30, 1081 if i < 2 else 7).astype(np.float32)
            assert cdr.LaserScanPacker(n, 4.7, 0.01, 30.0, 1 / 39.9).pack(t, ranges) == msgs.serialize(
                sm.laser_scan(n, t, ranges, 4.7, 0.01, 30.0, 1 / 39.9)
            )
            assert cdr.pack_clock(t) == msgs.serialize(sm.clock(t))
        children = [car_names(k).base_link for k in range(i + 1)]
        poses = [tuple(rng.normal(size=3)) for _ in children]
        tf = sm.tf_message([sm.transform(t, "map", c, px, py, 0.0, pyaw) for c, (px, py, pyaw) in zip(children, poses)])
        assert cdr.TfPacker(children).pack(t, poses) == msgs.serialize(tf)


def test_every_byte_the_bridge_sends_is_rosbags_serialisation(tmp_path, typestore):
    """Run the bridge (two cars, recording) and check every recorded payload — the exact
    bytes it hands to DDS — against rosbags: decode, re-encode, compare."""
    from mcap.reader import make_reader

    from roboracer_arena import _core
    from roboracer_arena.ros2 import Bridge
    from roboracer_arena.track.drivable import Track

    walls, centre = _core.stadium_track()
    bridge = Bridge(
        Track.from_polylines(walls, centre, "stadium"),
        cars=2,
        rate=None,
        lockstep=True,
        record=tmp_path / "b.mcap",
        dds=False,
    )
    bridge.start()
    for _ in range(10):
        bridge.drive(0, 0.1, 1.0)
        bridge.drive(1, -0.1, 1.0)
    while bridge.sim_time < 0.5 - 1e-9:
        bridge.wait(0.01)
    bridge.stop()
    seen = set()
    with open(tmp_path / "b.mcap", "rb") as f:
        for schema, channel, message in make_reader(f).iter_messages():
            decoded = typestore.deserialize_cdr(message.data, schema.name)
            assert typestore.serialize_cdr(decoded, schema.name) == message.data, channel.topic
            seen.add(channel.topic)
    assert {
        "/scan",
        "/opp_scan",
        "/ego_racecar/odom",
        "/opp_racecar/odom",
        "/tf",
        "/tf_static",
        "/clock",
        "/centreline",
        "/drive",
        "/opp_drive",
    } <= seen
