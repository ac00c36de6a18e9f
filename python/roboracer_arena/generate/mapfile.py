"""ROS map files (PNG + YAML) for generated tracks, with atomic writes.

Writing uses the ROS map_saver trinary conventions (254 free, 0 occupied, 205 unknown,
``occupied_thresh 0.65``, ``free_thresh 0.196``). Reading prefers the builder's
``roboracer_arena.maps.load_map`` and falls back to a small nav2-compatible reader for
the flat ROS map YAML, so ``validate`` works on any ROS map either way.
"""

from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np
from PIL import Image

from ..errors import MapFormatError, MapIOError
from ..fileio import atomic_write_bytes, atomic_write_text
from .outcomes import GeneratedMap


def save_ros_map(m: GeneratedMap, yaml_path: str | Path) -> Path:
    """Write ``NAME.png`` beside ``NAME.yaml``; returns the YAML path."""
    yaml_path = Path(yaml_path)
    png_path = yaml_path.with_suffix(".png")
    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(m.data, dtype=np.uint8), mode="L").save(buf, format="PNG")
    atomic_write_bytes(png_path, buf.getvalue())
    ox, oy, yaw = m.origin
    atomic_write_text(
        yaml_path,
        f"image: {png_path.name}\nmode: trinary\nresolution: {m.resolution}\n"
        f"origin: [{ox!r}, {oy!r}, {yaw!r}]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    )
    return yaml_path


def load_ros_map(yaml_path: str | Path) -> GeneratedMap:
    """Load a ROS map as a trinary grid (254/0/205), honouring mode, negate and thresholds."""
    try:  # the builder's loader, once it is on main
        from ..maps import load_map as _builder_load  # type: ignore[attr-defined]
    except ImportError:
        return _load_flat_yaml(Path(yaml_path))
    m = _builder_load(yaml_path)
    return GeneratedMap(np.asarray(m.data, dtype=np.uint8), float(m.resolution), tuple(m.origin))  # type: ignore[arg-type]


def _parse_flat_yaml(path: Path) -> dict[str, object]:
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise MapIOError(f"{path}: cannot read map YAML: {e.strerror or e}") from e
    out: dict[str, object] = {}
    for lineno, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if ":" not in line:
            raise MapFormatError(f"{path}:{lineno}: expected 'key: value', got {raw!r}")
        key, value = (s.strip() for s in line.split(":", 1))
        value = value.strip("'\"")
        if value.startswith("["):
            try:
                out[key] = [float(v) for v in value.strip("[]").split(",")]
            except ValueError as e:
                raise MapFormatError(f"{path}:{lineno}: {key} must be a list of numbers") from e
        else:
            out[key] = value
    return out


def _load_flat_yaml(path: Path) -> GeneratedMap:
    y = _parse_flat_yaml(path)
    for key in ("image", "resolution", "origin"):
        if key not in y:
            raise MapFormatError(f"{path}: missing required key '{key}'")
    try:
        res = float(y["resolution"])  # type: ignore[arg-type]
        occ_t = float(y.get("occupied_thresh", 0.65))  # type: ignore[arg-type]
        free_t = float(y.get("free_thresh", 0.196))  # type: ignore[arg-type]
        negate = int(float(y.get("negate", 0)))  # type: ignore[arg-type]
    except ValueError as e:
        raise MapFormatError(f"{path}: resolution/thresholds/negate must be numbers ({e})") from e
    origin = y["origin"]
    if not (isinstance(origin, list) and len(origin) == 3 and all(math.isfinite(v) for v in origin)):
        raise MapFormatError(f"{path}: origin must be [x, y, yaw]")
    if not (res > 0 and math.isfinite(res)):
        raise MapFormatError(f"{path}: resolution must be > 0, got {res}")
    mode = str(y.get("mode", "trinary"))
    img_path = (path.parent / str(y["image"])).resolve()
    try:
        with Image.open(img_path) as im:
            img = np.asarray(im.convert("LA") if im.mode in ("LA", "RGBA", "PA") else im.convert("L"), dtype=np.float64)
    except OSError as e:
        raise MapIOError(f"{img_path}: cannot read map image: {e}") from e
    shade = img[..., 0] if img.ndim == 3 else img
    occ = shade / 255.0 if negate else (255.0 - shade) / 255.0
    data = np.full(shade.shape, 205, np.uint8)
    data[occ > occ_t] = 0
    data[occ < free_t] = 254
    if mode not in ("trinary", "scale", "raw"):
        raise MapFormatError(f"{path}: unknown mode {mode!r} (trinary, scale or raw)")
    # scale/raw maps are thresholded like trinary ones: the validator needs free vs not.
    return GeneratedMap(data, res, (origin[0], origin[1], origin[2]))
