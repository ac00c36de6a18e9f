"""The loopback discovery profiles a ROS 2 node needs to find a ``--loopback`` bridge:
shipped in the package and printed by ``roboracer-arena ros2 --print-profile``."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest

from roboracer_arena.cli import main
from roboracer_arena.ros2 import dds


def test_cyclone_profile_keeps_announcing_to_loopback_peers():
    root = ET.fromstring(dds.loopback_config())
    disc = root.find("Domain/Discovery")
    assert disc is not None
    assert disc.findtext("SPDPInterval") == "1s"
    assert float(disc.findtext("InitialLocatorPruneDelay").rstrip("s")) > 1e5  # never drop the peers
    assert [p.get("address") for p in disc.findall("Peers/Peer")] == ["127.0.0.1"]
    assert root.find("Domain/General/AllowMulticast").text == "false"


def test_fastdds_profile_is_a_default_participant_on_loopback():
    ns = {"p": "http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles"}
    root = ET.fromstring(dds.fastdds_loopback_profile().encode())
    part = root.find("p:participant", ns)
    assert part is not None and part.get("is_default_profile") == "true"
    assert part.findtext("p:rtps/p:useBuiltinTransports", namespaces=ns) == "false"
    peers = part.findall("p:rtps/p:builtin/p:initialPeersList/p:locator/p:udpv4/p:address", ns)
    assert [p.text for p in peers] == ["127.0.0.1"]
    t = root.find("p:transport_descriptors/p:transport_descriptor", ns)
    assert t.findtext("p:interfaceWhiteList/p:address", namespaces=ns) == "127.0.0.1"
    assert int(t.findtext("p:maxInitialPeersRange", namespaces=ns)) > dds.MAX_PARTICIPANTS


@pytest.mark.parametrize("vendor", dds.PROFILE_VENDORS)
def test_cli_prints_each_profile(vendor, capsys):
    assert main(["ros2", "--print-profile", vendor]) == 0
    assert capsys.readouterr().out == dds.profile(vendor)


def test_cli_without_a_track_says_so(capsys):
    assert main(["ros2"]) != 0
    err = capsys.readouterr().err
    assert "a TRACK (map YAML or catalog id) is needed" in err and "Traceback" not in err
