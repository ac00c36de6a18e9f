"""QoS profiles as ROS 2 nodes expect them.

ROS 2's default profile (``rmw_qos_profile_default``) is reliable, volatile, keep last 10;
latched topics (``/map``, ``/tf_static``) are transient local so a node that joins late
still gets them. ROS 2 serialises with XCDR1 (plain CDR), so every writer and reader here
pins the data representation to XCDR1; a ROS 2 node would otherwise see XCDR2 samples
from a ``cyclonedds`` Python writer, which it cannot read.
"""

from __future__ import annotations

from typing import Any

from ._deps import require

#: History depth of every topic (ROS 2 default).
DEPTH = 10
#: ROS 2 topics that are latched (transient local).
LATCHED = ("/map", "/tf_static", "/centreline", "/global_path")


def ros_qos(latched: bool = False) -> Any:
    """The cyclonedds ``Qos`` of a ROS 2 topic: reliable, keep last 10, volatile (or
    transient local when ``latched``), XCDR1 data representation."""
    require("cyclonedds")
    from cyclonedds.core import Policy, Qos
    from cyclonedds.util import duration

    return Qos(
        Policy.Reliability.Reliable(max_blocking_time=duration(milliseconds=100)),
        Policy.History.KeepLast(DEPTH),
        Policy.Durability.TransientLocal if latched else Policy.Durability.Volatile,
        Policy.DataRepresentation(use_cdrv0_representation=True),
    )


def qos_for(ros_topic: str) -> Any:
    """The QoS the bridge uses for ``ros_topic``."""
    return ros_qos(latched=ros_topic in LATCHED)
