"""ROS 2 message types as DDS IDL structs, without a ROS install.

Each message is written once, below, in ROS 2 ``.msg`` syntax (field for field the
definition ROS 2 Humble/Jazzy ship; constants left out, they are not on the wire). From
that text this module builds

* a ``cyclonedds`` :class:`~cyclonedds.idl.IdlStruct` class per type, registered under the
  DDS type name ROS 2 uses (``<pkg>::msg::dds_::<Type>_``), whose XCDR1 serialisation is
  what a ROS 2 node sends and expects (checked byte for byte against ``rosbags``);
* the full ``ros2msg`` schema text (the type followed by its dependencies) that MCAP
  files carry so Foxglove and ``ros2 bag`` can decode them.

Use :func:`msg_class` (``msg_class("sensor_msgs/msg/LaserScan")``) or the module
attributes (``LaserScan``, ``Odometry``, ...). Every field has a zero default.
"""

from __future__ import annotations

import dataclasses
import re
from functools import cache
from typing import Any, cast

from ._deps import require

# ROS 2 definitions (ros2/common_interfaces, ros2/rcl_interfaces, ros-drivers/ackermann_msgs,
# ros2/rmw_dds_common).
DEFINITIONS: dict[str, str] = {
    "builtin_interfaces/msg/Time": "int32 sec\nuint32 nanosec",
    "builtin_interfaces/msg/Duration": "int32 sec\nuint32 nanosec",
    "std_msgs/msg/Header": "builtin_interfaces/Time stamp\nstring frame_id",
    "std_msgs/msg/ColorRGBA": "float32 r\nfloat32 g\nfloat32 b\nfloat32 a",
    "geometry_msgs/msg/Point": "float64 x\nfloat64 y\nfloat64 z",
    "geometry_msgs/msg/Vector3": "float64 x\nfloat64 y\nfloat64 z",
    "geometry_msgs/msg/Quaternion": "float64 x\nfloat64 y\nfloat64 z\nfloat64 w",
    "geometry_msgs/msg/Pose": "Point position\nQuaternion orientation",
    "geometry_msgs/msg/PoseWithCovariance": "Pose pose\nfloat64[36] covariance",
    "geometry_msgs/msg/PoseStamped": "std_msgs/Header header\nPose pose",
    "geometry_msgs/msg/PoseWithCovarianceStamped": "std_msgs/Header header\nPoseWithCovariance pose",
    "geometry_msgs/msg/Twist": "Vector3 linear\nVector3 angular",
    "geometry_msgs/msg/TwistWithCovariance": "Twist twist\nfloat64[36] covariance",
    "geometry_msgs/msg/Transform": "Vector3 translation\nQuaternion rotation",
    "geometry_msgs/msg/TransformStamped": "std_msgs/Header header\nstring child_frame_id\nTransform transform",
    "tf2_msgs/msg/TFMessage": "geometry_msgs/TransformStamped[] transforms",
    "rosgraph_msgs/msg/Clock": "builtin_interfaces/Time clock",
    "sensor_msgs/msg/LaserScan": (
        "std_msgs/Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n"
        "float32 time_increment\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max\n"
        "float32[] ranges\nfloat32[] intensities"
    ),
    "sensor_msgs/msg/CompressedImage": "std_msgs/Header header\nstring format\nuint8[] data",
    "nav_msgs/msg/Odometry": (
        "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
        "geometry_msgs/TwistWithCovariance twist"
    ),
    "nav_msgs/msg/MapMetaData": (
        "builtin_interfaces/Time map_load_time\nfloat32 resolution\nuint32 width\nuint32 height\n"
        "geometry_msgs/Pose origin"
    ),
    "nav_msgs/msg/OccupancyGrid": "std_msgs/Header header\nMapMetaData info\nint8[] data",
    "nav_msgs/msg/Path": "std_msgs/Header header\ngeometry_msgs/PoseStamped[] poses",
    "ackermann_msgs/msg/AckermannDrive": (
        "float32 steering_angle\nfloat32 steering_angle_velocity\nfloat32 speed\nfloat32 acceleration\nfloat32 jerk"
    ),
    "ackermann_msgs/msg/AckermannDriveStamped": "std_msgs/Header header\nAckermannDrive drive",
    "visualization_msgs/msg/UVCoordinate": "float32 u\nfloat32 v",
    "visualization_msgs/msg/MeshFile": "string filename\nuint8[] data",
    "visualization_msgs/msg/Marker": (
        "std_msgs/Header header\nstring ns\nint32 id\nint32 type\nint32 action\ngeometry_msgs/Pose pose\n"
        "geometry_msgs/Vector3 scale\nstd_msgs/ColorRGBA color\nbuiltin_interfaces/Duration lifetime\n"
        "bool frame_locked\ngeometry_msgs/Point[] points\nstd_msgs/ColorRGBA[] colors\nstring texture_resource\n"
        "sensor_msgs/CompressedImage texture\nUVCoordinate[] uv_coordinates\nstring text\nstring mesh_resource\n"
        "MeshFile mesh_file\nbool mesh_use_embedded_materials"
    ),
    # ros2/rmw_dds_common (Humble: 24-byte gids; bounded strings are plain strings on the wire).
    "rmw_dds_common/msg/Gid": "uint8[24] data",
    "rmw_dds_common/msg/NodeEntitiesInfo": (
        "string node_namespace\nstring node_name\nGid[] reader_gid_seq\nGid[] writer_gid_seq"
    ),
    "rmw_dds_common/msg/ParticipantEntitiesInfo": "Gid gid\nNodeEntitiesInfo[] node_entities_info_seq",
}

#: Marker.type / Marker.action values used here (visualization_msgs/Marker constants).
MARKER_LINE_STRIP, MARKER_ADD = 4, 0

_PRIMITIVES = ("bool", "int8", "uint8", "int32", "uint32", "int64", "uint64", "float32", "float64", "string")
_FIELD = re.compile(r"^(?P<type>[\w/]+)(?P<arr>\[(?P<n>\d*)\])?\s+(?P<name>\w+)$")


@dataclasses.dataclass(frozen=True)
class Field:
    """One field of a message: ``type`` is a primitive or a full ``pkg/msg/Type`` name;
    ``array`` is None (scalar), -1 (unbounded sequence) or the fixed length."""

    name: str
    type: str
    array: int | None


def parse_fields(typename: str) -> list[Field]:
    """The fields of ``typename`` (``pkg/msg/Type``), with nested types fully qualified."""
    pkg = typename.split("/")[0]
    out = []
    for line in DEFINITIONS[typename].splitlines():
        m = _FIELD.match(line.strip())
        if not m:
            raise ValueError(f"{typename}: cannot parse field line {line!r}")
        t = m["type"]
        if t not in _PRIMITIVES:
            parts = t.split("/")
            t = f"{pkg}/msg/{t}" if len(parts) == 1 else f"{parts[0]}/msg/{parts[-1]}"
        arr = None if m["arr"] is None else (int(m["n"]) if m["n"] else -1)
        out.append(Field(m["name"], t, arr))
    return out


def dds_type_name(typename: str) -> str:
    """``sensor_msgs/msg/LaserScan`` → ``sensor_msgs::msg::dds_::LaserScan_`` (ROS 2's DDS name)."""
    pkg, _, name = typename.split("/")
    return f"{pkg}::msg::dds_::{name}_"


def dependencies(typename: str) -> list[str]:
    """Every message type ``typename`` uses, depth first, each once (itself excluded)."""
    seen: list[str] = []

    def walk(t: str) -> None:
        for f in parse_fields(t):
            if f.type not in _PRIMITIVES and f.type not in seen:
                walk(f.type)
                seen.append(f.type)

    walk(typename)
    return seen


def schema_text(typename: str) -> str:
    """The ``ros2msg`` schema MCAP stores: the type's definition, then each dependency
    after a ``=====`` separator and ``MSG: pkg/Type`` line (what ``ros2 bag`` writes)."""
    parts = [DEFINITIONS[typename]]
    for dep in dependencies(typename):
        pkg, _, name = dep.split("/")
        parts.append("=" * 80 + f"\nMSG: {pkg}/{name}\n" + DEFINITIONS[dep])
    return "\n".join(parts) + "\n"


@cache
def msg_class(typename: str) -> type:
    """The IdlStruct class of ``typename`` (``pkg/msg/Type``), built once."""
    if typename not in DEFINITIONS:
        raise KeyError(f"unknown message type {typename!r}")
    require("cyclonedds")
    from cyclonedds.idl import IdlMeta, IdlStruct
    from cyclonedds.idl import types as idl_types

    # The field types are built at runtime (``sequence[base]``, ``array[base, n]`` through
    # ``__class_getitem__``), which static typing cannot follow: treat the module as dynamic.
    t: Any = idl_types

    prim = {
        "bool": bool,
        "int8": t.int8,
        "uint8": t.uint8,
        "int32": t.int32,
        "uint32": t.uint32,
        "int64": t.int64,
        "uint64": t.uint64,
        "float32": t.float32,
        "float64": t.float64,
        "string": str,
    }
    name = typename.split("/")[-1]
    # __prepare__ is typed as a read-only Mapping but returns the mutable class namespace dict.
    ns = cast(dict[str, Any], IdlMeta.__prepare__(name, (IdlStruct,), typename=dds_type_name(typename)))
    for f in parse_fields(typename):
        base = prim[f.type] if f.type in prim else msg_class(f.type)
        if f.array is None:
            ns["__annotations__"][f.name] = base
            ns[f.name] = dataclasses.field(default_factory=_default_factory(f.type, base))
        elif f.array < 0:
            ns["__annotations__"][f.name] = t.sequence[base]
            ns[f.name] = dataclasses.field(default_factory=list)
        else:
            ns["__annotations__"][f.name] = t.array[base, f.array]
            ns[f.name] = dataclasses.field(default_factory=_array_factory(f.type, base, f.array))
    cls: type = IdlMeta(name, (IdlStruct,), ns)
    return dataclasses.dataclass(cls)


def _default_factory(ftype: str, base: Any):
    if ftype == "string":
        return str
    if ftype == "bool":
        return bool
    if ftype in _PRIMITIVES:
        return float if ftype.startswith("float") else int
    return base


def _array_factory(ftype: str, base: Any, n: int):
    zero = _default_factory(ftype, base)
    return lambda: [zero() for _ in range(n)]


def serialize(msg: Any) -> bytes:
    """XCDR1 little-endian bytes with the 4-byte encapsulation header, as ROS 2 sends them."""
    return msg.serialize(use_version_2=False)


# Short names for the types the bridge uses.
_EXPORTS = {
    "Time": "builtin_interfaces/msg/Time",
    "Header": "std_msgs/msg/Header",
    "ColorRGBA": "std_msgs/msg/ColorRGBA",
    "Point": "geometry_msgs/msg/Point",
    "Vector3": "geometry_msgs/msg/Vector3",
    "Quaternion": "geometry_msgs/msg/Quaternion",
    "Pose": "geometry_msgs/msg/Pose",
    "PoseStamped": "geometry_msgs/msg/PoseStamped",
    "PoseWithCovariance": "geometry_msgs/msg/PoseWithCovariance",
    "PoseWithCovarianceStamped": "geometry_msgs/msg/PoseWithCovarianceStamped",
    "Twist": "geometry_msgs/msg/Twist",
    "TwistWithCovariance": "geometry_msgs/msg/TwistWithCovariance",
    "Transform": "geometry_msgs/msg/Transform",
    "TransformStamped": "geometry_msgs/msg/TransformStamped",
    "TFMessage": "tf2_msgs/msg/TFMessage",
    "Clock": "rosgraph_msgs/msg/Clock",
    "LaserScan": "sensor_msgs/msg/LaserScan",
    "Odometry": "nav_msgs/msg/Odometry",
    "MapMetaData": "nav_msgs/msg/MapMetaData",
    "OccupancyGrid": "nav_msgs/msg/OccupancyGrid",
    "Path": "nav_msgs/msg/Path",
    "AckermannDrive": "ackermann_msgs/msg/AckermannDrive",
    "AckermannDriveStamped": "ackermann_msgs/msg/AckermannDriveStamped",
    "Marker": "visualization_msgs/msg/Marker",
}


def __getattr__(name: str) -> type:
    if name in _EXPORTS:
        return msg_class(_EXPORTS[name])
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
