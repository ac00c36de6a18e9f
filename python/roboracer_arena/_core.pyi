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
def screen(spec_json: str, config_json: str) -> str:
    """Admissibility screen (Eqs. 1–2) as JSON: passed, violations, r_min_m, pitch_m, l_max_m, …"""

def derived_geometry(spec_json: str, config_json: str) -> str:
    """Derived geometry as JSON: r_min, pitch, l_max, s_min, corner_radius."""

def generate_lattice(
    spec_json: str, config_json: str, seed: int
) -> tuple[
    str,
    str,
    tuple[npt.NDArray[np.uint8], tuple[float, float, float]] | None,
    npt.NDArray[np.float64] | None,
]:
    """Algorithm 1 (lattice): (kind "accepted"|"rejected"|"failed", info_json, map | None, centreline | None)."""

def construct_lattice(
    spec_json: str, config_json: str, seed: int
) -> tuple[str, npt.NDArray[np.float64] | None]:
    """Lattice constructor without raster validation in the loop: (info_json, centreline | None)."""

def validate_map(
    data: npt.NDArray[np.uint8],
    resolution: float,
    origin: tuple[float, float, float],
    spec_json: str,
    config_json: str,
) -> tuple[str, npt.NDArray[np.float64]]:
    """Raster validator: (report_json, measured centreline (N, 2) in the driving direction)."""

def analyse_curve(xy: npt.NDArray[np.float64], corner_radius: float, exclude_m: float) -> str:
    """Curvature analysis of a closed curve as JSON (turns, features, min radius, self_clearance_m)."""
