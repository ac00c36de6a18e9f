"""Type stubs for the Rust extension ``roboracer_arena._core``."""

import os
from collections.abc import Mapping, Sequence
from typing import Any, Literal, Protocol, TypeAlias, final

import numpy as np
import numpy.typing as npt

# The extension's own ``__all__`` (same order), checked by stubtest.
__all__ = [
    "__version__",
    "ArenaError",
    "MapIOError",
    "MapFormatError",
    "CorridorError",
    "InvalidArgumentError",
    "ConfigError",
    "SpecError",
    "SimulationError",
    "InternalError",
    "_boundary_self_test",
    "distance_transform",
    "rasterise_centreline",
    "screen",
    "derived_geometry",
    "Derived",
    "generate_lattice",
    "LatticeOutcome",
    "construct_lattice",
    "Construction",
    "nearest_specs",
    "NearestFound",
    "NearestSuggestion",
    "validate_map",
    "analyse_curve",
    "polyline_length",
    "cumulative_length",
    "signed_area",
    "resample_closed",
    "resample_closed_values",
    "curvature",
    "min_radius",
    "self_intersections",
    "load_map",
    "save_map",
    "build_geometry",
    "build_open_geometry",
    "config_defaults",
    "check_config",
    "measure_map",
    "RasterMeasurement",
    "Geometry",
    "Simulator",
    "FreeSpace",
    "stadium_track",
    "check_sim_size",
    "SIM_MAX_VEHICLES",
    "SIM_MAX_SCAN_VALUES",
    "STATE_FIELDS",
    "ProgressTracker",
    "EpisodeConfig",
    "EpisodeBuffers",
    "EVENT_WALL",
    "EVENT_VEHICLE",
    "EVENT_LAP",
    "EVENT_FAULT",
    "StartGrid",
    "StartSpec",
]

__version__: str

# Specs and configs cross as objects, never as JSON text: a mapping of the schema's fields
# (``model.model_dump()``) or the pydantic model itself (the binding dumps it); the core
# reads it into its serde type and checks the schema's ranges (``SpecError`` /
# ``ConfigError`` naming the field). Results cross as dicts and lists of plain values
# (the core's serde structs, via pythonize); ``roboracer_arena.generate.report`` holds the
# typed models built from them (``extra="forbid"``: a field the core adds or drops fails).
class _Dumps(Protocol):
    def model_dump(self) -> dict[str, Any]: ...

_Doc: TypeAlias = Mapping[str, Any] | _Dumps
_Result: TypeAlias = dict[str, Any]

# Closed domains, converted to the core's enums at the signature (InvalidArgumentError
# naming the allowed values for any other value); save_map also takes them in any case.
_ConfigKind: TypeAlias = Literal["sim", "build", "constructor", "spec"]
_ImageFormat: TypeAlias = Literal["png", "pgm"]

# The bad-value errors are ValueErrors too (as pydantic's ValidationError is).
class ArenaError(Exception): ...
class MapIOError(ArenaError): ...
class MapFormatError(ArenaError, ValueError): ...
class CorridorError(ArenaError): ...
class InvalidArgumentError(ArenaError, ValueError): ...
class ConfigError(ArenaError, ValueError): ...
class SpecError(ArenaError, ValueError): ...
class SimulationError(ArenaError): ...

class InternalError(ArenaError):
    """A caught Rust panic: the core failed on an input it should have refused."""

def distance_transform(feature: npt.NDArray[np.bool_]) -> npt.NDArray[np.float32]:
    """Exact Euclidean distance (cells) from every cell to the nearest True cell.
    InvalidArgumentError above the pixel budget (``ROBORACER_ARENA_MAX_PIXELS``)."""

# --- requirements → track: generate.rs (screen, constructors), grid.rs (rasteriser), track.rs (validator, curve analysis)
def rasterise_centreline(
    xy: npt.NDArray[np.float64],
    widths: npt.NDArray[np.float64],
    resolution: float = 0.05,
    wall_thickness: float = 0.15,
    margin: float = 0.5,
) -> tuple[npt.NDArray[np.uint8], tuple[float, float, float]]:
    """Eq. 3 with per-vertex full widths; returns (data (H, W) uint8, origin (x, y, yaw))."""

def screen(spec: _Doc, config: _Doc | None = None) -> _Result:
    """Admissibility screen (Eqs. 1–2): passed, violations, r_min_m, pitch_m, l_max_m, … (``ScreenResult``)."""

def derived_geometry(spec: _Doc, config: _Doc | None = None) -> Derived:
    """Derived geometry: r_min, pitch, l_max, s_min, corner_radius."""

@final
class Derived:
    """Lengths derived from a spec (m), read-only: r_min and pitch p (Eq. 1), L_max, the
    lattice pitch bound s_min = max(p, 2 r_min) and the corner radius r_c = s_min / 2."""

    @property
    def r_min(self) -> float: ...
    @property
    def pitch(self) -> float: ...
    @property
    def l_max(self) -> float: ...
    @property
    def s_min(self) -> float: ...
    @property
    def corner_radius(self) -> float: ...

def nearest_specs(spec: _Doc, config: _Doc | None, seed: int, timeout: float) -> NearestFound:
    """Nearest specs that build after a failure; ``timeout`` seconds bound the search."""

@final
class NearestSuggestion:
    """One changed spec that builds (read-only)."""

    @property
    def field(self) -> Literal["lap_length_m", "hall", "corridor_width_m", "features"]:
        """What was changed."""
    @property
    def spec(self) -> _Result:
        """The changed spec (a ``TrackSpec`` document; every other field as requested)."""
    @property
    def seed(self) -> int: ...
    @property
    def candidate_index(self) -> int:
        """The accepted candidate (a full run with ``seed`` accepts it again)."""

@final
class NearestFound:
    """What :func:`nearest_specs` found (read-only)."""

    @property
    def suggestions(self) -> list[NearestSuggestion]: ...
    @property
    def probes(self) -> int:
        """Changed specs tried."""
    @property
    def exhausted(self) -> bool:
        """The deadline cut the search short."""

def generate_lattice(spec: _Doc, config: _Doc | None, seed: int, timeout: float | None = None) -> LatticeOutcome:
    """Algorithm 1 (screen once, then lattice + ring candidates, each rasterised and
    validated). ``timeout`` seconds (None = unbounded) bounds the loop (``stopped ==
    "timeout"``); Ctrl-C stops it between candidates and raises KeyboardInterrupt."""

@final
class LatticeOutcome:
    """What :func:`generate_lattice` found (read-only): ``kind`` "accepted" (``map``,
    ``centreline``, ``report``, ``candidate_index``, ``pitch_m``), "rejected" by the
    screen (``screen``) or "failed" (``reasons``, ``stopped``); the others are None (empty
    ``reasons``). ``tried``: candidates tried (0 when rejected)."""

    @property
    def kind(self) -> Literal["accepted", "rejected", "failed"]: ...
    @property
    def tried(self) -> int: ...
    @property
    def map(self) -> tuple[npt.NDArray[np.uint8], tuple[float, float, float]] | None:
        """The accepted map: (data (H, W) uint8, origin (x, y, yaw))."""
    @property
    def centreline(self) -> npt.NDArray[np.float64] | None:
        """The accepted closed centreline (N, 2)."""
    @property
    def report(self) -> _Result | None:
        """The accepted map's raster validation (``ValidationReport``)."""
    @property
    def candidate_index(self) -> int | None: ...
    @property
    def pitch_m(self) -> float | None: ...
    @property
    def screen(self) -> _Result | None:
        """The screen that rejected the spec (``ScreenResult``)."""
    @property
    def reasons(self) -> dict[str, int]:
        """Why candidates failed, each reason counted."""
    @property
    def stopped(self) -> Literal["timeout", "cancelled"] | None:
        """What stopped a failed search before its candidate cap."""

def construct_lattice(spec: _Doc, config: _Doc | None, seed: int, timeout: float | None = None) -> Construction:
    """Lattice constructor without raster validation in the loop (the paper's
    constructor-comparison protocol)."""

@final
class Construction:
    """What :func:`construct_lattice` found (read-only): the first candidate's
    ``centreline`` and ``pitch_m``, or (both None) the ``reasons`` no candidate passed the
    constructor's checks and what ``stopped`` the search early."""

    @property
    def tried(self) -> int: ...
    @property
    def centreline(self) -> npt.NDArray[np.float64] | None:
        """The first passing candidate's closed centreline (N, 2)."""
    @property
    def pitch_m(self) -> float | None: ...
    @property
    def reasons(self) -> dict[str, int]:
        """Why candidates failed, each reason counted (empty when one passed)."""
    @property
    def stopped(self) -> Literal["timeout", "cancelled"] | None: ...

def validate_map(
    data: npt.NDArray[np.uint8],
    resolution: float,
    origin: tuple[float, float, float],
    spec: _Doc,
    config: _Doc | None = None,
) -> tuple[_Result, npt.NDArray[np.float64]]:
    """Raster validator: (report (``ValidationReport``), measured centreline (N, 2) in the driving direction)."""

def config_defaults(kind: _ConfigKind) -> _Result:
    """The core's defaults for ``kind`` ("sim", "build", "constructor"; "spec" has none:
    InvalidArgumentError)."""

def check_config(kind: _ConfigKind, config: _Doc) -> _Result:
    """Read and validate a document as the core does (``kind`` "sim", "build", "constructor"
    or "spec"; raises ConfigError, SpecError for a spec); returns it normalised."""

def analyse_curve(xy: npt.NDArray[np.float64], corner_radius: float, exclude_m: float) -> _Result:
    """Curvature analysis of a closed curve (``CurveAnalysis``: turns, features, min radius, self_clearance_m).
    InvalidArgumentError unless ≥ 3 finite points span a length in (0, 5000] m and
    ``corner_radius`` / ``exclude_m`` are finite and in range."""

# --- grid (grid.rs): ROS map YAML + PGM/PNG, nav2 rules, distance transform ---------
def load_map(path: str | os.PathLike[str]) -> tuple[npt.NDArray[np.uint8], float, tuple[float, float, float], _Result]:
    """Load a ROS map: ``(data (H, W) uint8 254/0/205, resolution, origin (x, y, yaw), meta)``.
    The YAML and image must be regular files; the image size is checked against the pixel
    budget from its header, resolution and origin against ``arena_core::limits``."""

def save_map(
    data: npt.NDArray[np.uint8],
    resolution: float,
    origin: tuple[float, float, float],
    yaml_path: str | os.PathLike[str],
    image_format: _ImageFormat = "png",
) -> str:
    """Write a trinary map image (png/pgm) beside ``yaml_path`` and the YAML, atomically; returns the image path."""

# --- track (track.rs): map → walls, ducts, centreline, meshes, round-trip check ------
@final
class Geometry:
    """The geometry of one built map (``roboracer_arena.maps.corridor.CorridorGeometry`` is its
    public view; read-only)."""

    @property
    def walls(self) -> list[npt.NDArray[np.float64]]:
        """Closed wall polylines (N, 2), map metres."""
    @property
    def ducts(self) -> list[npt.NDArray[np.float64]]:
        """Air-duct centre polylines (N, 2)."""
    @property
    def centreline(self) -> npt.NDArray[np.float64]:
        """The closed centreline (N, 2); empty for an open map."""
    @property
    def meshes(self) -> dict[str, tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]]:
        """name ("floor", "walls", "ducts", "rings") -> (vertices (V, 3), triangles (T, 3))."""
    @property
    def duct_st(self) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]:
        """Duct texture coordinates: (st (U, 2), one index per triangle corner)."""
    @property
    def iou(self) -> float:
        """Raster round-trip intersection over union."""
    @property
    def max_wall_deviation_cells(self) -> float:
        """Largest wall deviation of the round trip (cells)."""
    @property
    def corridor_mask(self) -> npt.NDArray[np.bool_]:
        """The corridor's free cells (H, W)."""
    @property
    def border_contact_cells(self) -> int:
        """Corridor cells touching the map border."""
    @property
    def timings(self) -> dict[str, float]:
        """Seconds per build stage."""
    @property
    def params(self) -> dict[str, Any]:
        """The build parameters used (``GeometryConfig`` fields)."""
    @property
    def start_pose(self) -> tuple[float, float, float] | None:
        """An open map's start pose (the given start, else the free cell farthest from the walls); None for a track."""
    @property
    def start_clearance_m(self) -> float | None:
        """Clearance (m) of that default start (NaN for a given start); None for a track."""

def build_geometry(
    data: npt.NDArray[np.uint8],
    resolution: float,
    origin: tuple[float, float, float],
    params: _Doc | None = None,
    start: Sequence[float] | None = None,
) -> Geometry:
    """Corridor isolation and geometry of a map (see ``roboracer_arena.maps.corridor``)."""

def build_open_geometry(
    data: npt.NDArray[np.uint8],
    resolution: float,
    origin: tuple[float, float, float],
    params: _Doc | None = None,
    unknown_free: bool = False,
    start: Sequence[float] | None = None,
) -> Geometry:
    """An open map's geometry: walls around every non-drivable region, no centreline (empty),
    plus ``start_pose`` (the free cell farthest from the walls unless ``start`` is given) and its clearance (m)."""

# --- track (track.rs): raster measurement for the library ---------------------------
@final
class RasterMeasurement:
    """What :func:`measure_map` found (read-only)."""

    @property
    def corridor_components(self) -> int:
        """Free components holding at least 0.5 % of the largest one's cells."""
    @property
    def infields(self) -> int:
        """Enclosed regions inside the corridor (1 for a plain ring)."""
    @property
    def mean_width_m(self) -> float:
        """Mean free width of the corridor (m)."""
    @property
    def extent_m(self) -> tuple[float, float]:
        """Extent (x, y) of the known (walls and free) cells (m)."""
    @property
    def centreline_length_m(self) -> float:
        """Length of the closed medial centreline (m)."""
    @property
    def centreline(self) -> npt.NDArray[np.float64]:
        """The closed medial centreline, counter-clockwise, map metres (N, 2)."""
    @property
    def widths(self) -> npt.NDArray[np.float64]:
        """Local free width at each centreline vertex (N,)."""

def measure_map(
    data: npt.NDArray[np.uint8],
    resolution: float,
    origin: tuple[float, float, float],
) -> RasterMeasurement:
    """Measure a trinary grid as the validator does; CorridorError if it holds no closed corridor."""

# --- sim (batched vehicle simulation) -------------------------------------------------
STATE_FIELDS: tuple[str, ...]

# A pyo3 class: cannot be subclassed, and is constructed by __new__.
@final
class Simulator:
    """``num_envs`` independent rapier worlds with ``vehicles_per_env`` cars each.

    ``tracks``: list of ``(walls, centreline)`` or ``(walls, centreline, wall_height)``;
    walls = list of closed (N, 2) float64 polylines (map-frame metres), centreline = closed
    (M, 2) float64 polyline, wall_height (m, in (0, 10]; default the build geometry's 0.5) the
    height of the extruded collision walls (``Track.native()`` passes the build's own). A
    centreline of exactly two points is an open map's start anchor (start, heading towards
    the second point): length 0, no progress, no laps (``Track.open_map``).
    ``config``: a ``SimConfig`` or a mapping of its fields (None = defaults). Every env starts on track 0.
    ``seed`` (None = 0) and ``env_index_offset`` (None = 0; the index of env 0 in a larger
    batch, so that a shard draws the same per-env streams as the whole) are ints >= 0.

    State columns (``state_fields``): x, y (CoM), yaw, vx, vy (body frame), yaw_rate,
    steer (actual, rate limited), speed (planar, signed by vx), progress_s (arc length of
    the projection on the centreline), travel (signed distance along the centreline since
    reset), laps (full centreline lengths of travel since reset), lap_time, last_lap_time.
    Events bits: 1 wall contact, 2 vehicle contact (during the last step), 4 lap
    completed, 8 numerical fault (vehicle put back at its last finite pose; not expected).

    Actions ``[steering (rad), speed (m/s)]``: NaN/inf become 0; finite values are clipped
    to ±max_steer and [min_speed, max_speed]. Results are bit-identical for the same seed
    whatever num_envs and thread count. Every env has its own streams (lidar noise per
    vehicle, reset draws per env), seeded from (seed, env index): masked resets and
    observes never move another env's stream.

    Inputs are checked before anything changes (``InvalidArgumentError`` naming the
    argument): shapes; track ids integers in range (bools and floats such as 0.7 refused);
    poses finite, within 100 m of the tracks' bounding box and |yaw| <= 1e4; speeds finite
    within [min_speed, max_speed]. Rows of envs outside ``env_mask`` are ignored.
    """

    def __new__(
        cls,
        tracks: Sequence[
            tuple[list[npt.NDArray[np.float64]], npt.NDArray[np.float64]]
            | tuple[list[npt.NDArray[np.float64]], npt.NDArray[np.float64], float]
        ],
        num_envs: int,
        vehicles_per_env: int,
        config: _Doc | None = None,
        seed: int | None = None,
        env_index_offset: int | None = None,
    ) -> Simulator: ...
    @property
    def num_envs(self) -> int: ...
    @property
    def vehicles_per_env(self) -> int: ...
    @property
    def num_beams(self) -> int: ...
    @property
    def num_tracks(self) -> int: ...
    @property
    def state_fields(self) -> tuple[str, ...]: ...
    @property
    def dt(self) -> float: ...
    @property
    def config(self) -> _Result:
        """The validated configuration in use (``SimConfig`` fields)."""
    def track_ids(self) -> npt.NDArray[np.int64]: ...
    def step_counts(self) -> tuple[int, int]:
        """(world steps through the rapier pipeline, contact-free shortcut steps), summed over envs."""
    def set_tracks(self, track_ids: npt.ArrayLike) -> None:
        """Track of each env, shape (num_envs,); reset the env afterwards."""
    def set_start_spec(self, spec: StartSpec) -> None:
        """Configure ``reset_drawn`` (``InvalidArgumentError`` unless ``spec`` has one ``s0``,
        and one weight if any, per track)."""
    def reset_drawn(
        self,
        env_mask: npt.NDArray[np.bool_],
        out_track_ids: npt.NDArray[np.int64],
        out_poses: npt.NDArray[np.float64],
        out_speeds: npt.NDArray[np.float64],
        track_ids: npt.ArrayLike | None = None,
        poses: npt.NDArray[np.float64] | None = None,
        speeds: npt.NDArray[np.float64] | None = None,
    ) -> None:
        """Reset the envs where ``env_mask`` is True, each drawing from its own stream its
        track (weighted), start poses (random or grid slot, staggered grid behind, lateral
        and heading noise), rolling-start speeds and lidar randomisation, except what
        ``track_ids`` (E,), ``poses`` (E, V, 3) or ``speeds`` (E, V) fix. Writes what each
        reset env got into ``out_track_ids`` (E,), ``out_poses`` (E, V, 3), ``out_speeds``
        (E, V) (other rows untouched). Needs ``set_start_spec``."""
    def reset(self, env_mask: npt.NDArray[np.bool_], poses: npt.NDArray[np.float64]) -> None:
        """Put the vehicles of envs where ``env_mask`` is True at rest at ``poses`` (E, V, 3)."""
    def set_speeds(self, env_mask: npt.NDArray[np.bool_], speeds: npt.NDArray[np.float64]) -> None:
        """Rolling start: forward speeds (E, V) in m/s for envs where ``env_mask`` is True, after ``reset``."""
    def set_vehicle_params(
        self,
        env_mask: npt.NDArray[np.bool_],
        friction: npt.NDArray[np.float64],
        mass: npt.NDArray[np.float64],
        steer_lag: npt.NDArray[np.float64],
        throttle_lag: npt.NDArray[np.float64],
    ) -> None:
        """Per-episode vehicle parameters (E,) each for envs where ``env_mask`` is True: tyre friction,
        mass (kg), steering and throttle time constants (s). They hold until set again."""
    def sanitise_actions(self, actions: npt.NDArray[np.float64]) -> None:
        """The action rule, in place on (E, V, 2) float64 ``[steer, speed]``: NaN becomes 0,
        every other value (±inf included) is clipped to ±max_steer and [min_speed,
        max_speed]; ``step`` applies the same rule to what it is given."""
    def step(
        self,
        actions: npt.NDArray[np.float64],
        substeps: int,
        scans: npt.NDArray[np.float32] | None,
        state: npt.NDArray[np.float64],
        events: npt.NDArray[np.uint8],
        episode: EpisodeBuffers | None = None,
    ) -> None:
        """Run ``substeps`` physics steps, then scan (if ``scans`` is not None) and, once
        ``set_episode`` was called, the episode step; outputs in place (the episode results
        into ``episode`` when given)."""
    def observe(
        self,
        scans: npt.NDArray[np.float32] | None,
        state: npt.NDArray[np.float64],
        events: npt.NDArray[np.uint8],
        env_mask: npt.NDArray[np.bool_] | None = None,
        episode: EpisodeBuffers | None = None,
    ) -> None:
        """Write the outputs without stepping: of every env, or only of the envs where
        ``env_mask`` is True (other rows untouched, their noise streams not advanced);
        with ``episode``, the same envs' episode results too."""
    def set_episode(self, config: EpisodeConfig) -> None:
        """Run the episode step in every step from now on; every reset restarts the reset
        envs' episodes. A later call changes the parameters and keeps the episodes."""
    def centreline_pose(self, track_id: int, s: float) -> tuple[float, float, float]:
        """Pose (x, y, heading) on the centreline at arc length ``s`` (finite; wrapped)."""
    def free_space(self, track_id: int) -> FreeSpace:
        """The track's free space (usable from any thread while the simulator steps)."""
    def centreline_length(self, track_id: int) -> float: ...
    def centreline(self, track_id: int) -> npt.NDArray[np.float64]: ...
    def wall_mesh(self, track_id: int) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]:
        """The collision wall mesh as the physics engine holds it (shared by every env on the track)."""

@final
class FreeSpace:
    """One track's free space as the simulator holds it (``Simulator.free_space``)."""

    def contains(self, x: float, y: float) -> bool:
        """True when (x, y) is in the free space: enclosed by the same closed walls as the
        centreline's start (not inside a wall, an infield or beyond the outer wall)."""

@final
class ProgressTracker:
    """The simulator's progress and lap counting along a closed ``centreline`` (N, 2), fed
    positions from outside (a car the simulator does not step: the PhysX drive loop)."""

    def __new__(cls, centreline: npt.NDArray[np.float64], x: float, y: float) -> ProgressTracker: ...
    def update(self, x: float, y: float, elapsed: float, max_move: float) -> bool:
        """The car moved to (x, y) in ``elapsed`` s, at most ``max_move`` m; True when this
        completed a lap (``InvalidArgumentError`` for non-finite or negative inputs)."""
    @property
    def travel(self) -> float:
        """Metres travelled along the centreline since the start (negative backwards)."""
    @property
    def laps(self) -> int:
        """Start line crossings forwards minus backwards."""
    @property
    def length(self) -> float:
        """Lap length (m); 0 for an open map."""

def stadium_track(
    straight: float = 6.0, radius: float = 3.0, width: float = 2.0
) -> tuple[list[npt.NDArray[np.float64]], npt.NDArray[np.float64]]:
    """Analytic stadium track ``(walls [outer, inner], centreline)`` for tests and benchmarks."""

def check_sim_size(num_envs: int, vehicles_per_env: int, beams: int, frames: int) -> None:
    """The simulator's size budget (the one rule; ``Simulator`` applies it with one frame):
    ``ConfigError`` when envs x vehicles > SIM_MAX_VEHICLES or the scan values
    (vehicles x beams x frames) > SIM_MAX_SCAN_VALUES."""

SIM_MAX_VEHICLES: int
SIM_MAX_SCAN_VALUES: int

def _boundary_self_test(budgeted: bool = False) -> None:
    """Panics inside the boundary on purpose (tests): raises InternalError.

    ``budgeted`` panics on the worker thread of the generator's time-bounded door."""

# --- geometry (the one polyline toolbox: arena_core::geometry::polyline) -------------
# xy is (N, 2) float64 in metres. Closed polylines need N ≥ 3 (open ones N ≥ 2); one
# repeated closing point is dropped (cumulative_length keeps it). Non-finite points,
# N > 5e6, a spacing or span that is not a finite length > 0, or a spacing giving > 5e6
# points: InvalidArgumentError.
def polyline_length(xy: npt.NDArray[np.float64], closed: bool = True) -> float:
    """Length (m), counting the closing edge when ``closed``."""

def cumulative_length(xy: npt.NDArray[np.float64], closed: bool = True) -> npt.NDArray[np.float64]:
    """Arc length (m) at each vertex from point 0: (N,) open, (N + 1,) closed (last = lap length);
    a repeated closing point is kept here, so the output always matches the input."""

def signed_area(xy: npt.NDArray[np.float64]) -> float:
    """Signed area (m²) of a closed polyline: positive when counter-clockwise."""

def resample_closed(xy: npt.NDArray[np.float64], spacing: float) -> npt.NDArray[np.float64]:
    """(M, 2) points evenly spaced by arc length (~``spacing`` m, M ≥ 3) from point 0."""

def resample_closed_values(
    xy: npt.NDArray[np.float64], values: npt.NDArray[np.float64], spacing: float
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """:func:`resample_closed` plus one finite value per point (N,) interpolated in arc length;
    N + 1 values: the last is the value on returning to point 0 (an unwrapped parameter)."""

def curvature(xy: npt.NDArray[np.float64], span_m: float) -> npt.NDArray[np.float64]:
    """Signed curvature (1/m, + = left) per distinct vertex (a repeated closing point is
    dropped): the circle through the vertex and its neighbours ~``span_m`` of arc either side."""

def min_radius(xy: npt.NDArray[np.float64], span_m: float) -> float:
    """Smallest three-point circumradius (m) over chords of ~``span_m``; ``inf`` if straight."""

def self_intersections(
    xy: npt.NDArray[np.float64],
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]]:
    """Crossings of a closed polyline: ``(segments (K, 2) as i < j, points (K, 2))``,
    segment i running from point i to i + 1, sorted by (i, j)."""

# --- start grid and reset draws --------------------------------------------------------
@final
class StartGrid:
    """The start geometry of one track (``Track.start_grid``; ``start_grid.py`` is its
    typed view): wall edges (each wall closes back to its first point unless it has two
    points or already ends there), and the closed ``centreline`` ring in the racing
    direction without a repeated closing point, or with ``open_map`` an open map's start
    anchor (two distinct points: the start, and a point it heads to). ``source_start``:
    s = 0 is the source's own start line, kept whenever the grid is clear there. Bad
    geometry raises ``InvalidArgumentError``. Grid starts are cached per (slots, spacing)."""

    def __new__(
        cls,
        walls: Sequence[npt.NDArray[np.float64]],
        centreline: npt.NDArray[np.float64],
        *,
        open_map: bool = False,
        source_start: bool = False,
    ) -> StartGrid: ...
    @property
    def length(self) -> float:
        """Lap length (m); 0 for an open map."""
    def pose_at(self, s: float) -> tuple[float, float, float]:
        """(x, y, heading) on the centreline at arc length ``s`` (finite; wrapped at the lap);
        on an open map, ``s`` m along the start heading (behind it for ``s < 0``)."""
    def free_run_ahead(self, x: float, y: float, heading: float) -> float:
        """Distance (m) from (x, y) along ``heading`` to the first wall (inf if none)."""
    def clearance(self, points: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Distance (m) from each of ``points`` (N, 2) to the nearest wall, (N,)."""
    def grid_start_s(self, slots: int, spacing: float) -> float:
        """Arc length (m) of the first slot of a grid of ``slots`` (>= 1) cars ``spacing``
        (in [0, 1e4]) m apart: candidates every max(0.25 m, lap / 400); those whose slots
        all keep 75 % of the median candidate clearance qualify; the longest free run ahead
        wins (then the larger clearance, then the later candidate); none qualifying, the
        largest clearance. s = 0 when ``source_start`` and it qualifies; 0 on an open map."""
    def grid_poses(self, slots: int, spacing: float, offset: float, s0: float | None = None) -> npt.NDArray[np.float64]:
        """Poses (slots, 3) of the staggered grid: the first at ``s0`` (default
        ``grid_start_s(slots, spacing)``), each next ``spacing`` behind and, with more than
        one car, ``offset`` left and right of the centreline in turn."""

@final
class EpisodeConfig:
    """Reward weights and episode ends of ``Simulator.set_episode`` (mirrors
    ``envs.env_config.RewardConfig``). Per vehicle and step of ``dt`` s the reward is
    ``progress * ds - stall_penalty * dt [ds < stall_speed * dt] - time_penalty * dt
    - collision_penalty [contact] - wrong_way_penalty [wrong way]``. Keyword arguments;
    the core checks them (``InvalidArgumentError``): finite, penalties, ``stall_speed`` and
    ``wrong_way_distance`` >= 0, ``dt`` > 0, ``max_steps`` >= 1 or None (no limit)."""

    def __new__(
        cls,
        *,
        progress: float,
        collision_penalty: float,
        stall_penalty: float,
        stall_speed: float,
        time_penalty: float,
        wrong_way_penalty: float,
        wrong_way_distance: float,
        dt: float,
        collision_ends_episode: bool,
        wrong_way_ends_episode: bool,
        max_steps: int | None = None,
    ) -> EpisodeConfig: ...
    @property
    def max_steps(self) -> int | None: ...
    def __eq__(self, value: object, /) -> bool: ...

@final
class EpisodeBuffers:
    """The episode results of ``num_envs`` x ``vehicles_per_env`` as numpy arrays that
    ``Simulator.step`` / ``observe`` (``episode=``) write in place; zeroed at creation.
    Each attribute is always the same array (contiguous views of four blocks, so a step
    borrows four arrays); ``ConfigError`` over the simulator's size budget."""

    def __new__(cls, num_envs: int, vehicles_per_env: int) -> EpisodeBuffers: ...
    @property
    def reward(self) -> npt.NDArray[np.float64]:
        """(E,) each env's reward this step (the sum over its vehicles)."""
    @property
    def terminated(self) -> npt.NDArray[np.bool_]:
        """(E,) any vehicle's episode ended (a contact or wrong way, as configured)."""
    @property
    def truncated(self) -> npt.NDArray[np.bool_]:
        """(E,) the step limit was reached and the env did not terminate."""
    @property
    def elapsed(self) -> npt.NDArray[np.int64]:
        """(E,) steps since the env's reset."""
    @property
    def vehicle_reward(self) -> npt.NDArray[np.float64]:
        """(E, V) each vehicle's reward this step."""
    @property
    def vehicle_terminated(self) -> npt.NDArray[np.bool_]:
        """(E, V) each vehicle's end this step."""
    @property
    def progress(self) -> npt.NDArray[np.float64]:
        """(E, V) metres along the centreline since reset."""
    @property
    def wrong_way(self) -> npt.NDArray[np.int8]:
        """(E, V) 0, +1 driving the wrong way nose first, -1 reversing."""

#: Event bits of ``Simulator`` events (per vehicle, per step): a wall contact, a vehicle
#: contact, a completed lap, a physics fault (the car was put back at rest).
EVENT_WALL: int
EVENT_VEHICLE: int
EVENT_LAP: int
EVENT_FAULT: int

@final
class StartSpec:
    """How ``Simulator.reset_drawn`` places the cars (``start_grid.start_spec`` builds it
    as the env config says). Keyword arguments; the core checks the ranges
    (``InvalidArgumentError``): ``s0`` finite, ``track_weights`` finite, >= 0 and not all 0
    (None: uniform), distances and noises finite in [0, 1e4], ``noise_std`` low <= high,
    ``dropout`` in [0, 1). Read-only attributes; equal when every field is."""

    def __new__(
        cls,
        *,
        random_s: bool,
        s0: Sequence[float],
        grid_spacing: float,
        grid_offset: float,
        lateral_noise: float,
        heading_noise: float,
        side_clearance: float,
        speed_noise: float,
        noise_std: tuple[float, float],
        dropout: float,
        track_weights: Sequence[float] | None = None,
    ) -> StartSpec: ...
    @property
    def random_s(self) -> bool:
        """First grid slot at a uniformly random arc length (else at ``s0[track]``)."""
    @property
    def s0(self) -> list[float]:
        """Arc length (m) of the first grid slot, per track."""
    @property
    def track_weights(self) -> list[float]:
        """Track draw weights, per track (empty: uniform)."""
    @property
    def grid_spacing(self) -> float:
        """Longitudinal gap between grid slots (m)."""
    @property
    def grid_offset(self) -> float:
        """Lateral offset of the staggered grid slots (m)."""
    @property
    def lateral_noise(self) -> float:
        """Uniform lateral start offset in +-this (m), capped by the room to the wall."""
    @property
    def heading_noise(self) -> float:
        """Uniform heading offset in +-this (rad)."""
    @property
    def side_clearance(self) -> float:
        """Metres kept between the wall and the car's centre by the lateral noise."""
    @property
    def speed_noise(self) -> float:
        """Rolling start speed drawn from [0, this] (m/s)."""
    @property
    def noise_std(self) -> tuple[float, float]:
        """(low, high) per-episode extra lidar noise std (m)."""
    @property
    def dropout(self) -> float:
        """Probability a beam reads range_max."""
    def __eq__(self, value: object, /) -> bool: ...
