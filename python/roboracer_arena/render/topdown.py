"""Top-down pictures in the ROS map frame, drawn with PIL.

:class:`TopDown` is a canvas that knows the map frame (resolution, origin incl. yaw, raster
size) and a pixel scale; everything else draws in world metres: rasters, tinted masks,
polylines, filled triangles, points and text labels. It knows nothing about tracks, so the
builder preview and the simulation's renderer share it.
"""

from __future__ import annotations

import io
import math
from pathlib import Path
from typing import Iterable, Sequence

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from ..fileio import atomic_write_bytes

RGB = tuple[int, int, int]
RGBA = tuple[int, int, int, int]


class TopDown:
    """An RGB canvas over a map-frame grid.

    The grid has ``height`` × ``width`` cells of ``resolution`` metres, row 0 at the top, its
    lower-left corner at ``origin`` (x, y, yaw) as in a ROS map YAML. ``scale`` is output
    pixels per cell (below 1 shrinks big maps)."""

    def __init__(
        self,
        width: int,
        height: int,
        resolution: float,
        origin: Sequence[float] = (0.0, 0.0, 0.0),
        scale: float = 1.0,
        background: RGB = (255, 255, 255),
    ) -> None:
        self.cells = (int(height), int(width))
        self.resolution = float(resolution)
        ox, oy, *rest = (float(v) for v in origin)
        self.origin = (ox, oy, rest[0] if rest else 0.0)
        self.scale = float(scale)
        size = (max(1, round(width * scale)), max(1, round(height * scale)))
        self.image = Image.new("RGB", size, background)
        self.draw = ImageDraw.Draw(self.image, "RGBA")

    # --- construction ----------------------------------------------------------------

    @classmethod
    def for_raster(
        cls, data: np.ndarray, resolution: float, origin: Sequence[float], max_px: int = 2048, min_px: int = 1024
    ) -> "TopDown":
        """A canvas showing an occupancy raster (254 free white, 0 occupied black, 205 grey),
        scaled so its longer side is at most ``max_px`` and, for small maps, enlarged
        towards ``min_px`` (at most 4x) so labels stay legible."""
        h, w = data.shape
        scale = fit_scale(max(h, w), max_px, min_px)
        canvas = cls(w, h, resolution, origin, scale)
        canvas.raster(data)
        return canvas

    @classmethod
    def for_bounds(
        cls, lo: Sequence[float], hi: Sequence[float], resolution: float = 0.05, margin: float = 0.5, max_px: int = 2048
    ) -> "TopDown":
        """A blank canvas covering the world box ``lo``–``hi`` (m) plus ``margin``."""
        x0, y0 = lo[0] - margin, lo[1] - margin
        w = max(1, math.ceil((hi[0] - lo[0] + 2 * margin) / resolution))
        h = max(1, math.ceil((hi[1] - lo[1] + 2 * margin) / resolution))
        return cls(w, h, resolution, (x0, y0, 0.0), fit_scale(max(h, w), max_px, max_px // 2))

    # --- coordinates -----------------------------------------------------------------

    def to_px(self, xy: np.ndarray) -> np.ndarray:
        """World metres (N, 2) → image pixel coordinates (N, 2) (x right, y down)."""
        p = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
        ox, oy, yaw = self.origin
        c, s = math.cos(yaw), math.sin(yaw)
        dx, dy = p[:, 0] - ox, p[:, 1] - oy
        u = (c * dx + s * dy) / self.resolution  # cells from the left edge
        v = (-s * dx + c * dy) / self.resolution  # cells from the bottom edge
        return np.c_[u * self.scale, (self.cells[0] - v) * self.scale]

    def px_per_m(self) -> float:
        return self.scale / self.resolution

    # --- drawing ---------------------------------------------------------------------

    def raster(self, data: np.ndarray) -> None:
        """Paint an occupancy raster (row 0 = top) as grey levels: the value itself, so
        254 is white, 0 black and 205 the map_server grey."""
        img = Image.fromarray(np.ascontiguousarray(data, dtype=np.uint8), mode="L").convert("RGB")
        if img.size != self.image.size:
            img = img.resize(self.image.size, Image.Resampling.BOX if self.scale < 1 else Image.Resampling.NEAREST)
        self.image.paste(img)

    def tint(self, mask: np.ndarray, colour: RGBA) -> None:
        """Blend ``colour`` over the cells where ``mask`` (grid-shaped) is true."""
        m = Image.fromarray(np.where(np.asarray(mask, bool), colour[3], 0).astype(np.uint8), mode="L")
        if m.size != self.image.size:
            m = m.resize(self.image.size, Image.Resampling.BOX if self.scale < 1 else Image.Resampling.NEAREST)
        self.image.paste(Image.new("RGB", self.image.size, colour[:3]), (0, 0), m)

    def polyline(self, xy: np.ndarray, colour: RGB | RGBA, width_m: float = 0.0, closed: bool = False, min_px: int = 1) -> None:
        """A polyline in world metres; ``width_m`` 0 draws it ``min_px`` wide."""
        pts = self.to_px(xy)
        if len(pts) < 2:
            return
        if closed:
            pts = np.r_[pts, pts[:1]]
        width = max(min_px, round(width_m * self.px_per_m()))
        self.draw.line([tuple(p) for p in pts], fill=colour, width=width, joint="curve" if width > 2 else None)

    def segments(self, a: np.ndarray, b: np.ndarray, colour: RGB | RGBA, width_px: int = 1) -> None:
        """Independent segments a[i]–b[i] (world metres)."""
        pa, pb = self.to_px(a), self.to_px(b)
        for p, q in zip(pa, pb):
            self.draw.line([tuple(p), tuple(q)], fill=colour, width=width_px)

    def triangles(self, tri_xy: np.ndarray, fill: RGB | RGBA) -> None:
        """Filled triangles (T, 3, 2) in world metres."""
        t = np.asarray(tri_xy, dtype=np.float64).reshape(-1, 3, 2)
        if not len(t):
            return
        px = self.to_px(t.reshape(-1, 2)).reshape(-1, 3, 2)
        for tri in px:
            self.draw.polygon([tuple(p) for p in tri], fill=fill)

    def points(self, xy: np.ndarray, colour: RGB | RGBA, radius_px: float = 3.0) -> None:
        for x, y in self.to_px(xy):
            self.draw.ellipse([x - radius_px, y - radius_px, x + radius_px, y + radius_px], fill=colour)

    def label(self, xy: Sequence[float], text: str, colour: RGB = (0, 0, 0), marker: bool = True, size_px: int = 14) -> None:
        """Text at a world point, with a small marker and a white halo for legibility."""
        (x, y), = self.to_px(np.asarray(xy, dtype=np.float64)[None, :2])
        if marker:
            self.points(np.asarray(xy, dtype=np.float64)[None, :2], colour, radius_px=max(3, size_px // 4))
        font = _font(size_px)
        self.draw.text((x + size_px // 2, y - size_px), text, fill=colour, font=font, stroke_width=2, stroke_fill=(255, 255, 255))

    def legend(self, entries: Iterable[tuple[str, RGB]], size_px: int = 14) -> None:
        """A key in the top-left corner: coloured squares and their names."""
        font = _font(size_px)
        y = 6
        for name, colour in entries:
            self.draw.rectangle([6, y, 6 + size_px, y + size_px], fill=colour, outline=(0, 0, 0))
            self.draw.text((12 + size_px, y), name, fill=(0, 0, 0), font=font, stroke_width=2, stroke_fill=(255, 255, 255))
            y += size_px + 6

    # --- output ----------------------------------------------------------------------

    def png_bytes(self) -> bytes:
        buf = io.BytesIO()
        self.image.save(buf, format="PNG")
        return buf.getvalue()

    def save(self, path: str | Path) -> Path:
        """Write the picture as PNG, atomically."""
        atomic_write_bytes(path, self.png_bytes())
        return Path(path)


def fit_scale(longest: int, max_px: int, min_px: int) -> float:
    """Pixels per cell: shrink to ``max_px``, or enlarge small grids towards ``min_px`` (≤ 4x)."""
    if longest >= min_px:
        return min(1.0, max_px / longest)
    return min(4.0, min_px / longest, max_px / longest)


def _font(size_px: int) -> ImageFont.ImageFont | ImageFont.FreeTypeFont:
    try:
        return ImageFont.load_default(size=size_px)
    except TypeError:  # Pillow < 10.1 has no sized default font
        return ImageFont.load_default()
