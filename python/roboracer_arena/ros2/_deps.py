"""The optional ``[ros2]`` extra: a clear error naming the missing package."""

from __future__ import annotations

from importlib import import_module
from typing import Any

from ..errors import ConfigError

_PIP = {"cyclonedds": "cyclonedds", "mcap": "mcap", "mcap_ros2": "mcap-ros2-support"}


def require(module: str) -> Any:
    """Import ``module`` or raise :class:`ConfigError` saying how to install it."""
    try:
        return import_module(module)
    except ImportError as e:
        pip = _PIP.get(module.split(".")[0], module)
        raise ConfigError(
            f"the ROS 2 interface needs the Python package {pip!r} ({e}); "
            "install it with: pip install 'roboracer-arena[ros2]'"
        ) from e
