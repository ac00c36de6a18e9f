"""Type stubs for the Rust extension ``roboracer_arena._core``."""

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

# --- library (circuits, catalog): raster measurement ---------------------------------
def measure_map(
    data: npt.NDArray[np.uint8],
    resolution: float,
    origin: tuple[float, float, float],
) -> tuple[str, npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """(info_json, closed CCW medial centreline (N, 2), local free widths (N,)); CorridorError if no loop."""
