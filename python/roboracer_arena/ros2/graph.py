"""``ros_discovery_info``: how ROS 2 tools see the bridge as a node.

A ROS 2 node is not a DDS entity: each ROS 2 participant publishes on the DDS topic
``ros_discovery_info`` an ``rmw_dds_common/msg/ParticipantEntitiesInfo`` that lists its
nodes (namespace, name) and the gids of each node's readers and writers. ``ros2 node
list``, ``ros2 node info`` and rqt_graph build the graph from those samples plus DDS
discovery; without one, the bridge's topics are visible but no node owns them.

The gids are the entities' DDS GUIDs (16 bytes: prefix and entity id, as on the wire)
padded with zeros to the 24 bytes of ROS 2 Humble's ``rmw_gid_t``, as ``rmw_fastrtps_cpp``
and ``rmw_cyclonedds_cpp`` fill them, so the graph matches them to the endpoints it
discovered. The writer is reliable, transient local, keep last 1 (what rmw_dds_common
uses), so a tool that starts later still gets the sample.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from ._deps import require
from .msgs import msg_class

#: The DDS topic (no ``rt/`` prefix: it is not a ROS topic) and ROS 2 type.
TOPIC = "ros_discovery_info"
TYPE = "rmw_dds_common/msg/ParticipantEntitiesInfo"
#: Bytes of a gid in ROS 2 Humble (``RMW_GID_STORAGE_SIZE``).
GID_SIZE = 24
#: The bridge's node name and namespace (what ``ros2 node list`` shows: ``/roboracer_arena``).
NODE_NAME = "roboracer_arena"
NODE_NAMESPACE = "/"


def gid(guid: Any) -> list[int]:
    """The ROS 2 gid of an entity with DDS GUID ``guid`` (a ``uuid.UUID`` or 16 bytes)."""
    raw = guid.bytes if hasattr(guid, "bytes") else bytes(guid)
    if len(raw) != 16:
        raise ValueError(f"a DDS GUID has 16 bytes, got {len(raw)}")
    return list(raw) + [0] * (GID_SIZE - 16)


def participant_info(
    participant_guid: Any,
    reader_guids: Iterable[Any],
    writer_guids: Iterable[Any],
    node_name: str = NODE_NAME,
    node_namespace: str = NODE_NAMESPACE,
) -> Any:
    """The ``ParticipantEntitiesInfo`` of a participant holding one node with these readers
    and writers (their GUIDs)."""
    Gid = msg_class("rmw_dds_common/msg/Gid")
    Node = msg_class("rmw_dds_common/msg/NodeEntitiesInfo")
    node = Node(
        node_namespace=node_namespace,
        node_name=node_name,
        reader_gid_seq=[Gid(data=gid(g)) for g in reader_guids],
        writer_gid_seq=[Gid(data=gid(g)) for g in writer_guids],
    )
    return msg_class(TYPE)(gid=Gid(data=gid(participant_guid)), node_entities_info_seq=[node])


def discovery_qos() -> Any:
    """Reliable, transient local, keep last 1, XCDR1: the QoS of ``ros_discovery_info``."""
    require("cyclonedds")
    from cyclonedds.core import Policy, Qos

    return Qos(
        Policy.Reliability.Reliable(max_blocking_time=100_000_000),
        Policy.History.KeepLast(1),
        Policy.Durability.TransientLocal,
        Policy.DataRepresentation(use_cdrv0_representation=True),
    )


def announce(dp: Any, readers: Iterable[Any], writers: Iterable[Any]) -> Any:
    """Publish the bridge's ``ros_discovery_info`` on participant ``dp`` (its node owns
    ``readers`` and ``writers``); returns the writer, which must live as long as ``dp``
    for late joiners to receive the sample."""
    from cyclonedds.pub import DataWriter
    from cyclonedds.topic import Topic

    qos = discovery_qos()
    w: DataWriter[Any] = DataWriter(dp, Topic(dp, TOPIC, msg_class(TYPE), qos=qos), qos=qos)
    w.write(participant_info(dp.guid, (r.guid for r in readers), (x.guid for x in writers)))
    return w
