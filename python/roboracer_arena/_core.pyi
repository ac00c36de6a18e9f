"""Type stubs for the Rust extension ``roboracer_arena._core``."""

import os
from typing import Sequence, TypedDict

import numpy as np
import numpy.typing as npt

__version__: str

class ArenaError(Exception): ...
class MapIOError(ArenaError): ...
class MapFormatError(ArenaError): ...
class CorridorError(ArenaError): ...
class InvalidArgumentError(ArenaError): ...
class SpecError(ArenaError): ...
class SimulationError(ArenaError): ...

def distance_transform(feature: npt.NDArray[np.bool_]) -> npt.NDArray[np.float32]:
    """Exact Euclidean distance (cells) from every cell to the nearest True cell."""

# --- generate (requirements → track): rasteriser, screen, lattice, validator ---------
def rasterise_centreline(
    xy: npt.NDArray[np.float64],
    widths: npt.NDArray[np.float64],
    resolution: float = 0.05,
    wall_thickness: float = 0.15,
    margin: float = 0.5,
) -> tuple[npt.NDArray[np.uint8], tuple[float, float, float]]:
    """Eq. 3 with per-vertex full widths; returns (data (H, W) uint8, origin (x, y, yaw))."""

# --- maps (ROS map YAML + PGM/PNG, nav2 rules) ---------------------------------------
def load_map(path: str | os.PathLike[str]) -> tuple[npt.NDArray[np.uint8], float, tuple[float, float, float], str]:
    """Load a ROS map: ``(data (H, W) uint8 254/0/205, resolution, origin (x, y, yaw), meta_json)``."""

def save_map(
    data: npt.NDArray[np.uint8],
    resolution: float,
    origin: tuple[float, float, float],
    yaml_path: str | os.PathLike[str],
    image_format: str = "png",
) -> str:
    """Write a trinary map image (png/pgm) beside ``yaml_path`` and the YAML, atomically; returns the image path."""

# --- builder (map → walls, ducts, centreline, meshes, round-trip check) ---------------
class _Geometry(TypedDict):
    walls: list[npt.NDArray[np.float64]]
    ducts: list[npt.NDArray[np.float64]]
    centreline: npt.NDArray[np.float64]
    meshes: dict[str, tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]]
    iou: float
    max_wall_deviation_cells: float
    corridor_mask: npt.NDArray[np.bool_]
    timings: dict[str, float]
    params_json: str

def build_geometry(
    data: npt.NDArray[np.uint8],
    resolution: float,
    origin: tuple[float, float, float],
    params_json: str = "{}",
    start: Sequence[float] | None = None,
) -> _Geometry:
    """Corridor isolation and geometry of a map (see ``roboracer_arena.corridor``)."""

def default_build_params() -> str:
    """The default geometry parameters (``BuildParams``) as JSON."""

# --- library (circuits, catalog): raster measurement ---------------------------------
def measure_map(
    data: npt.NDArray[np.uint8],
    resolution: float,
    origin: tuple[float, float, float],
) -> tuple[str, npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """(info_json, closed CCW medial centreline (N, 2), local free widths (N,)); CorridorError if no loop."""
