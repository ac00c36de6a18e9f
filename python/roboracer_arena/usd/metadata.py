"""A built stage's metadata (``customLayerData["roboracerArena"]``), read as a typed model.

The one reader of stage metadata: whatever a stage file holds there (a foreign or edited
stage: text that is not JSON, a number where a string belongs, a 5000-digit integer,
nesting hundreds deep, a start that is not numbers), reading it gives a
:class:`StageMetadata` or a one-line :class:`~roboracer_arena.errors.MapFormatError`
naming the stage file and the field (CLI exit 2), never another exception.

A stage carries what a later check needs to rebuild its track: the source map by
**absolute path** and the **sha256** of its YAML and its image
(:func:`source_fingerprint`); :func:`checked_source` gives that map only when it is still
there with the same bytes, never a file of the same name elsewhere (the current folder
plays no part).
"""

from __future__ import annotations

import hashlib
import math
from pathlib import Path
from typing import Any, Literal

from pxr import Usd
from pydantic import ConfigDict, Field, field_validator

from ..config.build import BuildConfig
from ..errors import ConfigError, MapFormatError, MapIOError
from ..foundation.fileio import image_named_by, parse_json, read_regular_bytes, require_regular, validate_model
from ..foundation.strict import NumbersAreNumbers
from .readback import open_stage
from .stage import METADATA_KEY

_HEX64 = r"^[0-9a-f]{64}$"
#: Largest map YAML a stage's source may be (as the map loader reads it).
_MAX_YAML_BYTES = 1 << 20


def _finite(v: Any) -> Any:
    if v is not None and not all(math.isfinite(x) for x in v):
        raise ValueError(f"must be finite numbers, got {v!r:.80}")
    return v


class StageMetadata(NumbersAreNumbers):
    """The builder's metadata of a stage; unknown keys are ignored (a newer builder)."""

    model_config = ConfigDict(frozen=True, extra="ignore", allow_inf_nan=False)

    generator: str = ""
    source_map: str = Field(
        "", max_length=4096, description="The source map YAML (absolute path); empty for an in-memory map."
    )
    source_sha256: str | None = Field(None, pattern=_HEX64, description="sha256 of the source map YAML.")
    source_image_sha256: str | None = Field(None, pattern=_HEX64, description="sha256 of its image.")
    resolution: float | None = Field(None, gt=0, le=1)
    origin: tuple[float, float, float] | None = None
    raster_px: tuple[int, int] | None = None
    build_config: str | None = Field(None, max_length=1 << 20)
    geometry_params: str | None = Field(None, max_length=1 << 20)
    iou: float | None = None
    max_wall_deviation_cells: float | None = None
    border_contact_cells: int | None = None
    start: tuple[float, ...] | None = None
    map_kind: Literal["track", "open"] = "track"
    unknown_cells: Literal["occupied", "free"] = "occupied"
    open_reason: str | None = None
    closed_gaps: str | None = Field(None, max_length=1 << 20)
    car_pose: tuple[float, float, float] | None = None

    @field_validator("source_map")
    @classmethod
    def _printable(cls, v: str) -> str:
        if any(ord(c) < 32 for c in v):
            raise ValueError("must be a path without control characters (a newline, an escape code)")
        return v

    @field_validator("origin", "car_pose")
    @classmethod
    def _finite_pose(cls, v: Any) -> Any:
        return _finite(v)

    @field_validator("start")
    @classmethod
    def _start_pose(cls, v: Any) -> Any:
        if v is not None and len(v) not in (2, 3):
            raise ValueError(f"must be (x, y) or (x, y, yaw), got {len(v)} numbers")
        return _finite(v)

    def build_config_model(self, where: str | Path) -> BuildConfig:
        """The stage's :class:`BuildConfig` (its ``build_config`` JSON text)."""
        if not self.build_config:
            raise ConfigError(f"{where}: not a roboracer-arena stage (no build_config in its metadata)")
        data = parse_json(self.build_config, where, "stage metadata build_config", MapFormatError)
        if not isinstance(data, dict):
            raise MapFormatError(f"{where}: stage metadata build_config must be a JSON object")
        return BuildConfig.from_dict(data, source=f"{where} metadata")


def stage_metadata_of(stage: Usd.Stage, where: str | Path) -> StageMetadata:
    """The typed metadata of an open stage (``where``: its file, for messages)."""
    try:
        data = stage.GetRootLayer().customLayerData.get(METADATA_KEY)
    except Exception as e:  # a value usd-core cannot hand to Python
        raise MapFormatError(f"{where}: stage metadata cannot be read: {str(e)[:200]}") from None
    if data is None:
        raise ConfigError(f"{where}: not a roboracer-arena stage (no {METADATA_KEY} metadata)")
    if not isinstance(data, dict):
        raise MapFormatError(f"{where}: stage metadata {METADATA_KEY} must be a dictionary, not {type(data).__name__}")
    plain = {str(k): _plain(v) for k, v in data.items()}
    return validate_model(plain, StageMetadata, where, "stage metadata", MapFormatError)


def read_stage_metadata(path: str | Path) -> StageMetadata:
    """The typed metadata of the stage file ``path`` (see the module doc)."""
    return stage_metadata_of(open_stage(path), path)


def _plain(v: Any) -> Any:
    """A Vt array or Gf vector as a list (one level: the builder writes flat values)."""
    if isinstance(v, (str, bytes, dict, int, float)) or v is None:
        return v
    try:
        return list(v) if hasattr(v, "__len__") else v
    except Exception:
        return v


def sha256_bytes(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def source_fingerprint(yaml_path: str | Path, recorded_as: str | Path | None = None) -> dict[str, str]:
    """What a stage records of its source map: its absolute path and the sha256 of its
    YAML and of its image. ``recorded_as``: the path to record when the map is read from
    a staging copy that moves there afterwards (``generate --build`` builds its stage from
    the temporary output folder, which becomes ``-o``)."""
    p = Path(yaml_path).absolute()
    text = read_regular_bytes(p, "map YAML", _MAX_YAML_BYTES)
    where = Path(recorded_as).absolute() if recorded_as is not None else p
    out = {"source_map": str(where), "source_sha256": sha256_bytes(text)}
    image = _image_of(p, text)
    if image is not None:
        out["source_image_sha256"] = sha256_file(image)
    return out


def _image_of(yaml_path: Path, text: bytes) -> Path | None:
    try:
        name = image_named_by(text.decode("utf-8-sig"))
    except (UnicodeDecodeError, MapIOError, MapFormatError):
        return None
    return yaml_path.parent / name if name else None


def sha256_file(path: Path) -> str:
    h = hashlib.sha256()
    require_regular(path, "map image")
    try:
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                h.update(block)
    except OSError as e:
        raise MapIOError(f"{path}: cannot read map image: {e.strerror or e}") from None
    return h.hexdigest()


def checked_source(stage_path: str | Path, meta: StageMetadata) -> Path:
    """The stage's source map, only as it was built: recorded by absolute path, still a
    regular file, its YAML and image with the recorded sha256. Else a one-line
    :class:`MapIOError` naming the stage and the source (never a same-named file found
    from the current folder)."""
    where = Path(stage_path)
    if not meta.source_map:
        raise ConfigError(f"{where}: not a roboracer-arena stage built from a map file (no source_map in its metadata)")
    src = Path(meta.source_map)
    name = meta.source_map if len(meta.source_map) <= 240 else f"{meta.source_map[:160]}…{meta.source_map[-60:]}"
    if not src.is_absolute():
        raise MapIOError(
            f"{where}: the stage records its source map by the relative path {name} (an older build); "
            "rebuild the stage so it records the absolute path and checksum"
        )
    if meta.source_sha256 is None:
        raise MapIOError(
            f"{where}: the stage records no checksum of its source map {name} (an older build); rebuild it"
        )
    try:
        fresh = source_fingerprint(src)
    except MapIOError as e:
        raise MapIOError(f"{where}: the stage's source map is missing or unreadable: {e}") from None
    if fresh["source_sha256"] != meta.source_sha256:
        raise MapIOError(
            f"{where}: the stage's source map {name} has changed since the build "
            f"(sha256 {fresh['source_sha256'][:12]}…, recorded {meta.source_sha256[:12]}…); rebuild the stage"
        )
    image = fresh.get("source_image_sha256")
    if meta.source_image_sha256 is not None and image != meta.source_image_sha256:
        shown = f"sha256 {image[:12]}…" if image else "no image"
        raise MapIOError(
            f"{where}: the image of the stage's source map {name} has changed since the build "
            f"({shown}, recorded {meta.source_image_sha256[:12]}…); rebuild the stage"
        )
    return src


__all__ = [
    "StageMetadata",
    "checked_source",
    "read_stage_metadata",
    "source_fingerprint",
    "stage_metadata_of",
]
