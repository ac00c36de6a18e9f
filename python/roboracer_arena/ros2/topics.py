"""Topic and frame names, following ``f1tenth_gym_ros`` so existing stacks connect unchanged.

Car 0 (the ego) uses ``/scan``, ``/ego_racecar/odom``, ``/drive`` and frames
``ego_racecar/base_link`` / ``ego_racecar/laser``; car 1 (the opponent) ``/opp_scan``,
``/opp_racecar/odom``, ``/opp_drive`` and ``opp_racecar/...`` frames; every further car
``i`` is namespaced: ``/car<i>/scan``, ``/car<i>/odom``, ``/car<i>/drive``,
``car<i>/base_link``. Shared: ``/tf``, ``/tf_static``, ``/clock``, ``/map``,
``/initialpose`` (resets the ego) and ``/centreline`` (visualization_msgs/Marker).

On the wire a ROS 2 topic ``/a/b`` is the DDS topic ``rt/a/b`` (:func:`dds_topic`).
"""

from __future__ import annotations

from dataclasses import dataclass

MAP_FRAME = "map"
TF, TF_STATIC, CLOCK, MAP, INITIALPOSE, CENTRELINE, GLOBAL_PATH = (
    "/tf",
    "/tf_static",
    "/clock",
    "/map",
    "/initialpose",
    "/centreline",
    "/global_path",
)

# ROS 2 type of every topic the bridge uses (per-car topics by their role).
TYPE_OF = {
    "scan": "sensor_msgs/msg/LaserScan",
    "odom": "nav_msgs/msg/Odometry",
    "drive": "ackermann_msgs/msg/AckermannDriveStamped",
    TF: "tf2_msgs/msg/TFMessage",
    TF_STATIC: "tf2_msgs/msg/TFMessage",
    CLOCK: "rosgraph_msgs/msg/Clock",
    MAP: "nav_msgs/msg/OccupancyGrid",
    INITIALPOSE: "geometry_msgs/msg/PoseWithCovarianceStamped",
    CENTRELINE: "visualization_msgs/msg/Marker",
    GLOBAL_PATH: "nav_msgs/msg/Path",
}


@dataclass(frozen=True)
class CarNames:
    """Topic and frame names of one car."""

    scan: str
    odom: str
    drive: str
    base_link: str
    laser: str


def car_names(index: int) -> CarNames:
    """Names of car ``index`` (0 = ego, 1 = opponent, then ``car<i>``)."""
    if index < 0:
        raise ValueError(f"car index must be >= 0, got {index}")
    if index == 0:
        return CarNames("/scan", "/ego_racecar/odom", "/drive", "ego_racecar/base_link", "ego_racecar/laser")
    if index == 1:
        return CarNames("/opp_scan", "/opp_racecar/odom", "/opp_drive", "opp_racecar/base_link", "opp_racecar/laser")
    ns = f"car{index}"
    return CarNames(f"/{ns}/scan", f"/{ns}/odom", f"/{ns}/drive", f"{ns}/base_link", f"{ns}/laser")


def dds_topic(ros_topic: str) -> str:
    """``/scan`` → ``rt/scan``: the DDS topic name ROS 2 gives a topic."""
    if not ros_topic.startswith("/") or ros_topic.endswith("/") or "//" in ros_topic:
        raise ValueError(f"not a fully qualified ROS 2 topic name: {ros_topic!r}")
    return "rt" + ros_topic
