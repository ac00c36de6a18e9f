"""``ros_discovery_info``: the bridge shows up as a ROS 2 node. A reader that joins after
the bridge (transient local) receives one ParticipantEntitiesInfo whose bytes are rosbags'
(ROS 2 Humble's rmw_dds_common definition) and whose gids are the DDS GUIDs of the
bridge's participant, readers and writers as DDS discovery reports them (what the ROS 2
graph matches them against)."""

from __future__ import annotations

import time
import uuid

import pytest

from roboracer_arena.ros2 import graph, msgs

rosbags_typesys = pytest.importorskip("rosbags.typesys")


@pytest.fixture(scope="module")
def typestore():
    from rosbags.typesys import Stores, get_typestore

    return get_typestore(Stores.ROS2_HUMBLE)  # holds rmw_dds_common's definitions


def test_gid_is_the_guid_padded_to_24_bytes():
    g = uuid.UUID("0110dcc3-c594-e9dc-f5e8-5f31000001c1")
    assert graph.gid(g) == list(g.bytes) + [0] * 8
    with pytest.raises(ValueError):
        graph.gid(b"short")


def test_participant_info_serialises_like_rosbags(typestore):
    ids = [uuid.uuid4() for _ in range(6)]
    msg = graph.participant_info(ids[0], ids[1:3], ids[3:])
    data = msgs.serialize(msg)
    decoded = typestore.deserialize_cdr(data, graph.TYPE)
    assert typestore.serialize_cdr(decoded, graph.TYPE) == data
    assert bytes(decoded.gid.data) == ids[0].bytes + bytes(8)
    (node,) = decoded.node_entities_info_seq
    assert (node.node_namespace, node.node_name) == ("/", "roboracer_arena")
    assert [bytes(g.data)[:16] for g in node.reader_gid_seq] == [i.bytes for i in ids[1:3]]
    assert [bytes(g.data)[:16] for g in node.writer_gid_seq] == [i.bytes for i in ids[3:]]


def _take_all(reader, want, timeout=20.0):
    """Samples of a reader until ``want(samples)`` holds."""
    got: list = []
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        got += [s for s in reader.take(N=256) if s.sample_info.valid_data]
        if want(got):
            return got
        time.sleep(0.02)
    pytest.fail(f"timed out: got {len(got)} samples")


def test_bridge_publishes_its_node_on_ros_discovery_info(ellipse_map, domain_id, typestore):
    from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsPublication, BuiltinTopicDcpsSubscription
    from cyclonedds.core import Policy
    from cyclonedds.sub import DataReader
    from cyclonedds.topic import Topic

    from roboracer_arena.ros2 import Bridge
    from roboracer_arena.ros2.dds import participant

    with Bridge(ellipse_map, domain_id=domain_id, loopback=True) as bridge:
        time.sleep(0.5)  # the sample is written at start: this reader joins late
        dp = participant(domain_id, loopback=True)
        qos = graph.discovery_qos()
        reader = DataReader(dp, Topic(dp, graph.TOPIC, msgs.msg_class(graph.TYPE), qos=qos), qos=qos)
        bridge_guid = bridge._dp.guid
        pubs = BuiltinDataReader(dp, BuiltinTopicDcpsPublication)
        subs = BuiltinDataReader(dp, BuiltinTopicDcpsSubscription)
        (info,) = _take_all(reader, lambda got: len(got) >= 1)

        # Every endpoint of the bridge as DDS discovery sees it (keyed by GUID).
        n_writers, n_readers = len(bridge._writers), len(bridge._readers)
        ours = lambda e: e.participant_key == bridge_guid
        writers = _take_all(pubs, lambda got: sum(map(ours, got)) >= n_writers + 1)
        readers = _take_all(subs, lambda got: sum(map(ours, got)) >= n_readers)

    data = msgs.serialize(info)
    assert typestore.serialize_cdr(typestore.deserialize_cdr(data, graph.TYPE), graph.TYPE) == data
    assert bytes(info.gid.data) == bridge_guid.bytes + bytes(8)
    (node,) = info.node_entities_info_seq
    assert (node.node_namespace, node.node_name) == ("/", "roboracer_arena")
    node_writers = {bytes(g.data) for g in node.writer_gid_seq}
    node_readers = {bytes(g.data) for g in node.reader_gid_seq}
    topic_writers = {e.key.bytes + bytes(8): e for e in writers if ours(e)}
    topic_readers = {e.key.bytes + bytes(8): e for e in readers if ours(e)}
    # The node's gids are exactly the discovered endpoints, less the ros_discovery_info writer.
    disc = [e for e in topic_writers.values() if e.topic_name == graph.TOPIC]
    assert len(disc) == 1
    assert node_writers == set(topic_writers) - {disc[0].key.bytes + bytes(8)}
    assert node_readers == set(topic_readers)
    assert {topic_writers[g].topic_name for g in node_writers} >= {"rt/scan", "rt/map", "rt/tf", "rt/clock"}
    assert {topic_readers[g].topic_name for g in node_readers} == {"rt/drive", "rt/initialpose"}
    # The discovery writer as ROS 2 tools expect it: type name and QoS of rmw_dds_common.
    d = disc[0]
    assert d.type_name == "rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_"
    assert isinstance(d.qos[Policy.Reliability], Policy.Reliability.Reliable)
    assert d.qos[Policy.Durability] == Policy.Durability.TransientLocal
    assert d.qos[Policy.History] == Policy.History.KeepLast(1)
