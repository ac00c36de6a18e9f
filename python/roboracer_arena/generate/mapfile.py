"""ROS map files (PNG + YAML) for generated tracks, with atomic writes.

Both directions go through :mod:`roboracer_arena.maps` (the one reader and writer):
writing uses the ROS map_saver trinary conventions (254 free, 0 occupied, 205 unknown,
``occupied_thresh 0.65``, ``free_thresh 0.196``), reading follows nav2's rules.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..maps import load_map, save_map
from .outcomes import GeneratedMap


def save_ros_map(m: GeneratedMap, yaml_path: str | Path) -> Path:
    """Write ``NAME.png`` beside ``NAME.yaml`` (atomically); returns the YAML path."""
    save_map(m.data, m.resolution, m.origin, yaml_path, "png")
    return Path(yaml_path)


def load_ros_map(yaml_path: str | Path) -> GeneratedMap:
    """Load a ROS map as a trinary grid (254/0/205), honouring mode, negate and thresholds
    (the one reader, :func:`roboracer_arena.maps.load_map`)."""
    m = load_map(yaml_path)
    return GeneratedMap(np.asarray(m.data, dtype=np.uint8), m.resolution, m.origin)
