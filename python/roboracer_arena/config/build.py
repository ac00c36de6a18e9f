"""``BuildConfig``: every knob of the map → environment builder in one pydantic model,
loadable from TOML or JSON.

Three groups:

* ``geometry`` mirrors the Rust ``BuildParams`` field for field (names and defaults), and is
  passed unchanged to :func:`roboracer_arena.maps.corridor.extract_corridor`;
* ``materials`` — colours and procedural textures of the USD stage;
* ``physics`` — the physics material (friction, restitution) and the physics scene gravity.

Every default says why it was chosen. Unknown keys are errors, so a typo in a config file
never silently falls back to a default.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any, Literal

from pydantic import ConfigDict, Field, ValidationError, model_validator

from ..errors import ArenaError, ConfigError
from ..foundation.fileio import parse_json, read_text
from ..foundation.strict import NumbersAreNumbers, format_validation_error

Colour = tuple[float, float, float]

_STRICT = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


class GeometryConfig(NumbersAreNumbers):
    """Corridor extraction and mesh geometry (mirrors Rust ``BuildParams``)."""

    model_config = _STRICT

    wall_height_m: float = Field(
        0.5,
        ge=1e-3,
        le=10,
        description="Height of the extruded collision walls (m). 0.5 m is well above the 1:10 car's lidar (~0.1 m) and chassis, so nothing drives or scans over a wall.",
    )
    wall_offset_m: float = Field(
        0.0,
        ge=-1,
        le=1,
        description="Offset of the collision walls from the corridor border (m); positive moves them away from the free space, negative narrows the corridor. 0 puts them exactly on the mapped border, which keeps the round-trip IoU highest.",
    )
    tube_diameter_m: float = Field(
        0.33,
        ge=1e-3,
        le=2,
        description="Diameter of the visual air-duct tubes (m): the 33 cm air ducts that bound RoboRacer tracks (the paper's default).",
    )
    tube_segments: int = Field(
        12,
        ge=3,
        le=64,
        description="Vertices around each tube cross-section. 12 looks round at the 1:10 scale while keeping the USD small.",
    )
    ring_spacing_m: float = Field(
        1.0,
        ge=0,
        le=1000,
        description="Arc-length spacing of the rings drawn on the ducts (m); ~1 m matches the segment joints of real air ducts. 0 disables rings.",
    )
    ring_width_m: float = Field(
        0.05,
        ge=1e-3,
        le=10,
        description="Length of each ring band along the duct (m); 5 cm reads as a band without hiding the tube.",
    )
    ring_scale: float = Field(
        1.12,
        ge=0.1,
        le=3,
        description="Ring radius as a multiple of the tube radius; 1.12 makes the band stand just proud of the tube so it is visible without z-fighting.",
    )
    simplify_tolerance_m: float = Field(
        0.0,
        ge=0,
        le=10,
        description="Douglas-Peucker tolerance for walls and ducts (m); 0 means half a map cell, the raster's own uncertainty, so simplification never moves a wall by more than the map can resolve.",
    )
    smoothing_iterations: int = Field(
        2,
        ge=0,
        le=100,
        description="Taubin smoothing passes over the duct paths and the centreline; 2 removes the staircase of the raster without visibly cutting corners.",
    )
    centreline_spacing_m: float = Field(
        0.1,
        ge=1e-3,
        le=10,
        description="Sample spacing of the extracted centreline (m); 0.1 m is finer than the car's wheelbase (0.33 m).",
    )
    floor_margin_m: float = Field(
        0.5,
        ge=0,
        le=100,
        description="Margin of the floor quad around the ducts (m); 0.5 m keeps the ducts' footprint (0.33 m) on the floor.",
    )

    @model_validator(mode="after")
    def _rings_apart(self) -> GeometryConfig:
        if 0 < self.ring_spacing_m < self.ring_width_m:
            raise ValueError(
                f"ring_spacing_m must be 0 (no rings) or at least ring_width_m ({self.ring_width_m}), got {self.ring_spacing_m}"
            )
        return self


class MaterialsConfig(NumbersAreNumbers):
    """Colours (linear RGB in [0, 1]) and procedural textures of the visual materials."""

    model_config = _STRICT

    floor_colour: Colour = Field(
        (0.32, 0.33, 0.35),
        description="Floor base colour: the mid grey of a sports-hall or lab floor where RoboRacer events run.",
    )
    wall_colour: Colour = Field(
        (0.8, 0.2, 0.2),
        description="Colour of the (normally invisible) collision walls, shown only when guides are displayed; red reads as 'boundary'.",
    )
    duct_colour: Colour = Field(
        (0.85, 0.85, 0.82),
        description="Air-duct tube colour: the silver-white of aluminium-foil ducts.",
    )
    ring_colour: Colour = Field(
        (0.12, 0.12, 0.12),
        description="Ring colour: dark bands, as on the ducts' wire reinforcement, for contrast with the tube.",
    )
    textures: bool = Field(
        True,
        description="Write procedural PNG textures (floor speckle, duct ribs) beside the stage; off gives plain colours and a single-file stage.",
    )
    texture_size_px: int = Field(
        128,
        ge=8,
        le=4096,
        description="Edge length of the square procedural textures (px); 128 px over the 2 m floor tile is 1.6 cm per texel, finer than a car camera resolves the floor, for ~15 kB and a few ms.",
    )
    floor_texture_tile_m: float = Field(
        2.0,
        gt=0,
        description="Floor texture repeat (m per tile); 2 m hides tiling at car-camera distances.",
    )


class StagePhysicsConfig(NumbersAreNumbers):
    """Physics material and scene."""

    model_config = _STRICT

    static_friction: float = Field(
        0.83,
        ge=0,
        le=5,
        description="Static friction coefficient; 0.83 is the paper's measured tyre-surface friction.",
    )
    dynamic_friction: float = Field(
        0.83,
        ge=0,
        le=5,
        description="Dynamic friction coefficient; equal to the static one (0.83) as the paper gives one tyre-surface value.",
    )
    restitution: float = Field(
        0.1,
        ge=0,
        le=1,
        description="Restitution of walls and floor; 0.1 models soft air ducts that absorb most of an impact.",
    )
    gravity_m_s2: float = Field(9.81, gt=0, description="Gravity magnitude (m/s^2) along -Z; standard gravity.")
    # PhysX tuning, authored only when the `physx` extra (physx-usd-schemas) is installed.
    time_steps_per_second: int = Field(
        200,
        ge=30,
        le=2000,
        description="PhysX scene steps per second (PhysxSceneAPI); 200 = 1 / the simulator's 5 ms dt.",
    )
    contact_offset_m: float = Field(
        0.02,
        gt=0,
        le=0.5,
        description=(
            "PhysX contact offset of walls and floor (m): contacts are generated this far out. 2 cm is about a "
            "third of the 1:10 car's ground clearance and covers its 3.5 cm per-step travel at 7 m/s with the "
            "car's own offset."
        ),
    )
    rest_offset_m: float = Field(
        0.0,
        ge=0,
        le=0.1,
        description="PhysX rest offset (m): bodies come to rest touching the surface itself (0 = the mesh).",
    )

    @model_validator(mode="after")
    def _offsets(self) -> StagePhysicsConfig:
        if self.rest_offset_m >= self.contact_offset_m:
            raise ValueError(
                f"rest_offset_m ({self.rest_offset_m}) must be below contact_offset_m ({self.contact_offset_m})"
            )
        return self


class BuildConfig(NumbersAreNumbers):
    """Everything the map → environment builder can be told. All fields have defaults."""

    model_config = _STRICT

    geometry: GeometryConfig = Field(default_factory=GeometryConfig)
    materials: MaterialsConfig = Field(default_factory=MaterialsConfig)
    physics: StagePhysicsConfig = Field(default_factory=StagePhysicsConfig)
    usd_format: Literal["usdc", "usda"] = Field(
        "usdc",
        description="USD encoding; binary crate (usdc) is ~5x smaller and faster to load, usda is for reading by eye.",
    )

    def geometry_params(self) -> dict[str, Any]:
        """The ``params`` dict for the Rust corridor extractor (``BuildParams`` field names)."""
        return self.geometry.model_dump()

    @classmethod
    def from_dict(cls, data: object, source: str = "config") -> BuildConfig:
        """Validate a mapping; a bad field raises :class:`ConfigError` naming ``source`` and the field."""
        if not isinstance(data, dict):
            raise ConfigError(f"{source}: a build config must be a table/object, got {type(data).__name__}")
        try:
            return cls.model_validate(data)
        except ValidationError as e:
            raise ConfigError(f"{source}: {format_validation_error(e)}") from e

    @classmethod
    def from_file(cls, path: str | Path) -> BuildConfig:
        """Load from ``.toml`` or ``.json`` (chosen by suffix; other suffixes try JSON then TOML)."""
        p = Path(path)
        try:
            text = read_text(p, "build config")
        except ArenaError as e:
            raise ConfigError(str(e)) from None
        suffix = p.suffix.lower()
        if suffix == ".toml":
            data = _parse_toml(p, text)
        elif suffix == ".json":
            data = _parse_json(p, text)
        else:
            try:
                data = json.loads(text)
            except json.JSONDecodeError:
                data = _parse_toml(p, text)
            except (RecursionError, ValueError):
                data = _parse_json(p, text)  # the one JSON reader names the problem
        return cls.from_dict(data, source=str(p))


def _parse_toml(p: Path, text: str) -> dict[str, Any]:
    try:
        import tomllib  # Python >= 3.11
    except ImportError as e:  # pragma: no cover - Python 3.10
        raise ConfigError(f"{p}: reading TOML needs Python >= 3.11 (tomllib); use a JSON config") from e
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(f"{p}: not valid TOML: {e}") from e


def _parse_json(p: Path, text: str) -> Any:
    return parse_json(text, p, "build config", ConfigError)


__all__ = ["BuildConfig", "GeometryConfig", "MaterialsConfig", "StagePhysicsConfig"]
