"""ROS 2 messages from simulator state: scan, odometry, transforms, clock, map, centreline.

Conventions (as ``f1tenth_gym_ros``): ``base_link`` is the car's reference point (the
simulator's CoM), odometry and ``/tf`` are in the ``map`` frame, the twist is in the body
frame (vx forward, vy left, yaw rate), the laser frame sits at the lidar mount offset.
Beam ``k`` of a scan points at ``angle_min + k * angle_increment`` with
``angle_min = -fov/2``, ``angle_increment = fov / (beams - 1)``: the simulator's layout.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from . import msgs
from .topics import MAP_FRAME, CarNames


def stamp(t: float) -> Any:
    """``builtin_interfaces/Time`` of ``t`` simulated seconds."""
    ns = int(round(t * 1e9))
    return msgs.Time(sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000)


def stamp_seconds(time_msg: Any) -> float:
    """Seconds of a ``builtin_interfaces/Time``."""
    return time_msg.sec + time_msg.nanosec * 1e-9


def yaw_quaternion(yaw: float) -> Any:
    return msgs.Quaternion(x=0.0, y=0.0, z=math.sin(yaw / 2), w=math.cos(yaw / 2))


def quaternion_yaw(q: Any) -> float:
    """Yaw (rad) of a quaternion (rotation about z; roll and pitch ignored)."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def header(t: float, frame_id: str) -> Any:
    return msgs.Header(stamp=stamp(t), frame_id=frame_id)


def laser_scan(
    names: CarNames, t: float, ranges: np.ndarray, fov: float, range_min: float, range_max: float, scan_time: float
) -> Any:
    """``sensor_msgs/LaserScan`` of one car's scan (ranges in metres, float32)."""
    n = len(ranges)
    return msgs.LaserScan(
        header=header(t, names.laser),
        angle_min=-fov / 2,
        angle_max=fov / 2,
        angle_increment=fov / (n - 1) if n > 1 else 0.0,
        time_increment=0.0,
        scan_time=scan_time,
        range_min=range_min,
        range_max=range_max,
        ranges=ranges.tolist(),
        intensities=[],
    )


def odometry(names: CarNames, t: float, x: float, y: float, yaw: float, vx: float, vy: float, yaw_rate: float) -> Any:
    """``nav_msgs/Odometry`` of one car (pose in ``map``, twist in ``base_link``)."""
    return msgs.Odometry(
        header=header(t, MAP_FRAME),
        child_frame_id=names.base_link,
        pose=msgs.PoseWithCovariance(
            pose=msgs.Pose(position=msgs.Point(x=x, y=y, z=0.0), orientation=yaw_quaternion(yaw))
        ),
        twist=msgs.TwistWithCovariance(
            twist=msgs.Twist(linear=msgs.Vector3(x=vx, y=vy, z=0.0), angular=msgs.Vector3(x=0.0, y=0.0, z=yaw_rate))
        ),
    )


def transform(t: float, parent: str, child: str, x: float, y: float, z: float, yaw: float) -> Any:
    return msgs.TransformStamped(
        header=header(t, parent),
        child_frame_id=child,
        transform=msgs.Transform(translation=msgs.Vector3(x=x, y=y, z=z), rotation=yaw_quaternion(yaw)),
    )


def tf_message(transforms: Sequence[Any]) -> Any:
    return msgs.TFMessage(transforms=list(transforms))


def clock(t: float) -> Any:
    return msgs.Clock(clock=stamp(t))


def occupancy_grid(occ_map: Any, t: float = 0.0) -> Any:
    """``nav_msgs/OccupancyGrid`` of an :class:`~roboracer_arena.maps.occupancy.OccupancyMap`:
    free 0, occupied 100, unknown -1; row 0 of the grid is the bottom row (ROS order)."""
    data = np.asarray(occ_map.data)
    grid = np.full(data.shape, -1, np.int8)
    grid[data == 254] = 0
    grid[data == 0] = 100
    h, w = data.shape
    ox, oy, oyaw = occ_map.origin
    info = msgs.MapMetaData(
        map_load_time=stamp(t),
        resolution=float(occ_map.resolution),
        width=w,
        height=h,
        origin=msgs.Pose(position=msgs.Point(x=ox, y=oy, z=0.0), orientation=yaw_quaternion(oyaw)),
    )
    return msgs.OccupancyGrid(header=header(t, MAP_FRAME), info=info, data=grid[::-1].ravel().tolist())


def centreline_marker(centreline: np.ndarray, t: float = 0.0) -> Any:
    """The closed centreline as a green ``visualization_msgs/Marker`` LINE_STRIP in ``map``."""
    c = np.asarray(centreline, dtype=np.float64)
    if len(c) > 1 and not np.allclose(c[0], c[-1]):
        c = np.vstack([c, c[:1]])
    return msgs.Marker(
        header=header(t, MAP_FRAME),
        ns="centreline",
        id=0,
        type=msgs.MARKER_LINE_STRIP,
        action=msgs.MARKER_ADD,
        pose=msgs.Pose(orientation=msgs.Quaternion(w=1.0)),
        scale=msgs.Vector3(x=0.05),
        color=msgs.ColorRGBA(r=0.1, g=0.8, b=0.2, a=1.0),
        points=[msgs.Point(x=float(x), y=float(y), z=0.0) for x, y in c],
    )


def global_path(xy: np.ndarray, t: float = 0.0) -> Any:
    """A closed raceline (M, 2) as ``nav_msgs/Path`` in ``map``: one pose per point, its yaw
    along the line (the direction of travel), the first point repeated at the end."""
    p = np.asarray(xy, dtype=np.float64)
    nxt = np.roll(p, -1, axis=0)
    yaw = np.arctan2(nxt[:, 1] - p[:, 1], nxt[:, 0] - p[:, 0])
    if len(p) > 1:
        p, yaw = np.vstack([p, p[:1]]), np.append(yaw, yaw[0])
    h = header(t, MAP_FRAME)
    poses = [
        msgs.PoseStamped(
            header=h,
            pose=msgs.Pose(
                position=msgs.Point(x=float(x), y=float(y), z=0.0),
                orientation=msgs.Quaternion(z=float(np.sin(a / 2)), w=float(np.cos(a / 2))),
            ),
        )
        for (x, y), a in zip(p, yaw)
    ]
    return msgs.Path(header=h, poses=poses)


def drive_command(t: float, frame_id: str, steer: float, speed: float) -> Any:
    """``ackermann_msgs/AckermannDriveStamped`` (what the bridge records of a command)."""
    return msgs.AckermannDriveStamped(
        header=header(t, frame_id), drive=msgs.AckermannDrive(steering_angle=steer, speed=speed)
    )
