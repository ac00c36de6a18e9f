"""The DDS participant: domain id and network configuration of ``cyclonedds``, and the
discovery profiles a ROS 2 node uses to find the bridge on loopback.

``cyclonedds`` reads its configuration from ``CYCLONEDDS_URI``. When that is unset and
``loopback=True`` (the CLI's ``--loopback``, the tests), :func:`participant` configures
the domain for the loopback interface only, multicast off and unicast discovery to
127.0.0.1 (participant indices 0..``MAX_PARTICIPANTS``): the setup of a sandbox or CI
machine where multicast does not reach other processes. The bridge keeps announcing
itself to every one of those peer ports every ``SPDP_INTERVAL_S`` for as long as it runs
(Cyclone otherwise drops unanswered peer addresses after 30 s), so a node that starts
later finds it within a few seconds. That node needs the matching profile of its RMW:

* ``rmw_cyclonedds_cpp``: ``CYCLONEDDS_URI`` = :func:`loopback_config` (inline XML);
* ``rmw_fastrtps_cpp`` (ROS 2's default): ``FASTRTPS_DEFAULT_PROFILES_FILE`` (Humble;
  ``FASTDDS_DEFAULT_PROFILES_FILE`` from Fast DDS 2.12 / Jazzy) = a file holding
  :func:`fastdds_loopback_profile` (initial peers on 127.0.0.1, UDP on loopback only).

``roboracer-arena ros2 --print-profile cyclonedds|fastdds`` prints them. On a normal
network the default (multicast discovery) needs neither.
"""

from __future__ import annotations

import os
from typing import Any

from ..errors import InvalidArgumentError
from ._deps import require

#: Largest participant index probed by unicast discovery on loopback.
MAX_PARTICIPANTS = 32
#: Seconds between two participant announcements (SPDP) to the loopback peers: bounds
#: how long a node that starts after the bridge waits to find it.
SPDP_INTERVAL_S = 1.0
#: Participant ids a Fast DDS node probes on each initial peer (Fast DDS' default is 4).
FASTDDS_PEER_RANGE = MAX_PARTICIPANTS + 1

#: USER_DATA of a ROS 2 participant (the root security enclave), as rmw implementations set it.
ENCLAVE_USER_DATA = b"enclave=/;"

#: The profiles ``--print-profile`` prints, by RMW vendor.
PROFILE_VENDORS = ("cyclonedds", "fastdds")


def loopback_config(domain_id: int | str = "any") -> str:
    """A ``cyclonedds`` XML configuration for loopback-only DDS (what ``CYCLONEDDS_URI``
    may hold verbatim): loopback interface, no multicast, unicast discovery to the
    participant ports of 127.0.0.1, announced every ``SPDP_INTERVAL_S`` and never pruned
    (``InitialLocatorPruneDelay``), so late joiners are found."""
    return (
        f'<CycloneDDS><Domain id="{domain_id}"><General>'
        '<Interfaces><NetworkInterface name="lo" multicast="false"/></Interfaces>'
        "<AllowMulticast>false</AllowMulticast></General>"
        "<Discovery><ParticipantIndex>auto</ParticipantIndex>"
        f"<MaxAutoParticipantIndex>{MAX_PARTICIPANTS}</MaxAutoParticipantIndex>"
        f"<SPDPInterval>{SPDP_INTERVAL_S:g}s</SPDPInterval>"
        "<InitialLocatorPruneDelay>1000000s</InitialLocatorPruneDelay>"
        '<Peers><Peer address="127.0.0.1"/></Peers></Discovery></Domain></CycloneDDS>'
    )


def fastdds_loopback_profile() -> str:
    """A Fast DDS XML profiles file (Fast DDS 2.x, as ``rmw_fastrtps_cpp`` reads from
    ``FASTRTPS_DEFAULT_PROFILES_FILE``) for loopback-only DDS: the default participant
    uses UDPv4 on 127.0.0.1 only (no shared memory, so it also talks to the bridge's
    Cyclone DDS) and announces itself to the participant ports of 127.0.0.1 (initial
    peers, ids 0..``MAX_PARTICIPANTS``) every ``SPDP_INTERVAL_S``. With ``rmw_fastrtps_cpp``
    leave ``RMW_FASTRTPS_USE_QOS_FROM_XML`` unset (the default): only the participant is
    configured here."""
    period = f"<sec>{int(SPDP_INTERVAL_S)}</sec><nanosec>{int(SPDP_INTERVAL_S % 1 * 1e9)}</nanosec>"
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<profiles xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <transport_descriptors>
    <transport_descriptor>
      <transport_id>roboracer_loopback_udp</transport_id>
      <type>UDPv4</type>
      <interfaceWhiteList><address>127.0.0.1</address></interfaceWhiteList>
      <maxInitialPeersRange>{FASTDDS_PEER_RANGE}</maxInitialPeersRange>
    </transport_descriptor>
  </transport_descriptors>
  <participant profile_name="roboracer_arena_loopback" is_default_profile="true">
    <rtps>
      <userTransports><transport_id>roboracer_loopback_udp</transport_id></userTransports>
      <useBuiltinTransports>false</useBuiltinTransports>
      <builtin>
        <discovery_config>
          <leaseAnnouncement>{period}</leaseAnnouncement>
        </discovery_config>
        <metatrafficUnicastLocatorList>
          <locator><udpv4><address>127.0.0.1</address></udpv4></locator>
        </metatrafficUnicastLocatorList>
        <initialPeersList>
          <locator><udpv4><address>127.0.0.1</address></udpv4></locator>
        </initialPeersList>
      </builtin>
    </rtps>
  </participant>
</profiles>
"""


def profile(vendor: str, domain_id: int | str = "any") -> str:
    """The loopback profile of ``vendor`` (``PROFILE_VENDORS``) as text."""
    if vendor == "cyclonedds":
        return loopback_config(domain_id) + "\n"
    if vendor == "fastdds":
        return fastdds_loopback_profile()
    raise InvalidArgumentError(f"profile vendor must be one of {', '.join(PROFILE_VENDORS)}, got {vendor!r}")


def check_domain_id(domain_id: int) -> int:
    """ROS 2 domain ids are 0..232 (RTPS port arithmetic); others fail with a typed error."""
    if not isinstance(domain_id, int) or not 0 <= domain_id <= 232:
        raise InvalidArgumentError(f"--domain-id must be an integer in 0..232, got {domain_id!r}")
    return domain_id


_DOMAINS: dict[int, Any] = {}


def participant(domain_id: int, loopback: bool = False) -> Any:
    """A ``DomainParticipant`` on ``domain_id``; with ``loopback`` (and no ``CYCLONEDDS_URI``
    set) the domain is first created with :func:`loopback_config`."""
    check_domain_id(domain_id)
    require("cyclonedds")
    from cyclonedds.domain import Domain, DomainParticipant

    if loopback and not os.environ.get("CYCLONEDDS_URI") and domain_id not in _DOMAINS:
        # The Domain object must outlive its participants: keep it for the process.
        _DOMAINS[domain_id] = Domain(domain_id, loopback_config(domain_id))
    from cyclonedds.core import Policy, Qos

    # ROS 2 participants carry their security enclave in USER_DATA; tools read it.
    return DomainParticipant(domain_id, qos=Qos(Policy.Userdata(ENCLAVE_USER_DATA)))


def raw_writer(writer: Any, msg_class: Any) -> Any:
    """A function ``write(data)`` that publishes already serialised CDR ``data`` (with its
    encapsulation header) on ``writer``, exactly as ``writer.write(sample)`` would after
    serialising (same padding to 4 bytes, same C call). Falls back to deserialising and
    ``writer.write`` if this cyclonedds build lacks the raw call."""
    try:
        from cyclonedds._clayer import ddspy_write
    except ImportError:  # pragma: no cover - other cyclonedds builds
        return lambda data: writer.write(msg_class.deserialize(data))
    ref = writer._ref

    def write(data: bytes) -> None:
        pad = (-len(data)) % 4
        ret = ddspy_write(ref, data + b"\0" * pad if pad else data)
        if ret < 0:
            from cyclonedds.core import DDSException

            raise DDSException(ret, f"writing a sample on {writer.topic.name}")

    return write
