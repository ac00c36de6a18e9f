"""The DDS participant: domain id and network configuration of ``cyclonedds``.

``cyclonedds`` reads its configuration from ``CYCLONEDDS_URI``. When that is unset and
``loopback=True`` (the CLI's ``--loopback``, the tests), :func:`participant` configures
the domain for the loopback interface only, multicast off and unicast discovery to
127.0.0.1 (participant indices 0..``MAX_PARTICIPANTS``): the setup of a sandbox or CI
machine whose only interface is ``lo``. A ROS 2 node on the same machine must then use
the same ``CYCLONEDDS_URI`` (see :func:`loopback_config`); on a normal network the
default (multicast discovery) needs nothing.
"""

from __future__ import annotations

import os
from typing import Any

from ..errors import InvalidArgumentError
from ._deps import require

#: Largest participant index probed by unicast discovery on loopback.
MAX_PARTICIPANTS = 32


def loopback_config(domain_id: int | str = "any") -> str:
    """A ``cyclonedds`` XML configuration for loopback-only DDS (what ``CYCLONEDDS_URI``
    may hold verbatim)."""
    return (
        f'<CycloneDDS><Domain id="{domain_id}"><General>'
        '<Interfaces><NetworkInterface name="lo" multicast="false"/></Interfaces>'
        "<AllowMulticast>false</AllowMulticast></General>"
        "<Discovery><ParticipantIndex>auto</ParticipantIndex>"
        f"<MaxAutoParticipantIndex>{MAX_PARTICIPANTS}</MaxAutoParticipantIndex>"
        '<Peers><Peer address="127.0.0.1"/></Peers></Discovery></Domain></CycloneDDS>'
    )


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
    return DomainParticipant(domain_id)


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
