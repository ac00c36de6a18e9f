"""ROS 2 interface without a ROS install (optional extra ``[ros2]``).

* :class:`Bridge` — the simulator behind ROS 2 topics over DDS (``cyclonedds``), with
  ``start()`` / ``stop()``; what ``roboracer-arena ros2`` runs.
* :class:`McapRecorder` — ROS 2 messages to an MCAP file Foxglove and ``ros2 bag`` open.
* :class:`McapEpisodeRecorder` — a gymnasium wrapper recording an env's episodes.
* :class:`BridgeConfig` / :class:`RatesConfig` — rates and simulator configuration.

One module per job: :mod:`.msgs` (message IDL types), :mod:`.qos`, :mod:`.topics`,
:mod:`.dds` (participant, loopback profiles for Cyclone DDS and Fast DDS), :mod:`.clock`
(rates, schedule, pacing), :mod:`.state_msgs` (messages from simulator state),
:mod:`.source`, :mod:`.start` (the env's start, ``--start``), :mod:`.graph`
(``ros_discovery_info``), :mod:`.bridge`, :mod:`.recorder`, :mod:`.episode_recorder`.
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

_LAZY = {
    "Bridge": "bridge",
    "BridgeConfig": "clock",
    "RatesConfig": "clock",
    "McapRecorder": "recorder",
    "McapEpisodeRecorder": "episode_recorder",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(import_module(f"{__name__}.{_LAZY[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["Bridge", "BridgeConfig", "McapEpisodeRecorder", "McapRecorder", "RatesConfig"]
