"""Top-down pictures in the ROS map frame, drawn with PIL.

:class:`TopDown` is a canvas that knows the map frame (resolution, origin incl. yaw, raster
size) and a pixel scale; everything else draws in world metres: rasters, tinted masks,
polylines, filled triangles, points and text labels. It knows nothing about tracks, so the
builder preview and the simulation's renderer share it.
"""

from __future__ import annotations

import io
import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from ..foundation.fileio import atomic_write_bytes
from .formats import image_format

RGB = tuple[int, int, int]
RGBA = tuple[int, int, int, int]
#: A pixel box (left, top, right, bottom), right and bottom exclusive.
Box = tuple[int, int, int, int]


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
        #: Text and pixel box of every label placed (see :meth:`label`).
        self.label_boxes: list[tuple[str, Box]] = []
        #: Labels left out for want of a free spot.
        self.dropped_labels: list[str] = []
        #: Pixel boxes labels keep clear of (see :meth:`reserve`).
        self.reserved: list[Box] = []

    # --- construction ----------------------------------------------------------------

    @classmethod
    def for_raster(
        cls, data: np.ndarray, resolution: float, origin: Sequence[float], max_px: int = 2048, min_px: int = 1024
    ) -> TopDown:
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
    ) -> TopDown:
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

    def polyline(
        self, xy: np.ndarray, colour: RGB | RGBA, width_m: float = 0.0, closed: bool = False, min_px: int = 1
    ) -> None:
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

    def polygon(self, xy: np.ndarray, fill: RGB | RGBA, outline: RGB | None = None) -> None:
        """A filled polygon with corners ``xy`` (N, 2) in world metres."""
        self.draw.polygon([tuple(p) for p in self.to_px(xy)], fill=fill, outline=outline)

    def reserve(self, xy: np.ndarray, pad_px: int = 3) -> Box:
        """Keep labels clear of the pixel box around the world points ``xy`` (N, 2), e.g. a
        marking a label would hide; returns the box."""
        p = self.to_px(xy)
        lo, hi = np.floor(p.min(axis=0)) - pad_px, np.ceil(p.max(axis=0)) + pad_px
        box = (int(lo[0]), int(lo[1]), int(hi[0]), int(hi[1]))
        self.reserved.append(box)
        return box

    def label(
        self, xy: Sequence[float], text: str, colour: RGB = (0, 0, 0), marker: bool = True, size_px: int = 14
    ) -> Box | None:
        """Text near a world point, with a small marker and a white halo for legibility.

        The text goes to the first spot around the point (nearest first, with a leader line
        when it had to move away) where it lies inside the picture and clear of every label
        placed before; its box is kept in :attr:`label_boxes`. If there is no such spot the
        text is left out (its marker stays), recorded in :attr:`dropped_labels`, and None
        is returned."""
        ((x, y),) = self.to_px(np.asarray(xy, dtype=np.float64)[None, :2])
        if marker:
            self.points(np.asarray(xy, dtype=np.float64)[None, :2], colour, radius_px=max(3, size_px // 4))
        face = font(size_px)
        left, top, right, bottom = self.draw.textbbox((0, 0), text, font=face, stroke_width=2)
        w, h = int(right - left), int(bottom - top)  # typed float by Pillow, ints in practice
        box = self._free_spot(x, y, w, h)
        if box is None:
            self.dropped_labels.append(text)
            return None
        if math.dist((x, y), _nearest_in_box(box, x, y)) > size_px:
            self.draw.line([(x, y), _nearest_in_box(box, x, y)], fill=colour, width=1)
        self.draw.text(
            (box[0] - left, box[1] - top), text, fill=colour, font=face, stroke_width=2, stroke_fill=(255, 255, 255)
        )
        self.label_boxes.append((text, box))
        return box

    def _free_spot(self, x: float, y: float, w: int, h: int, pad: int = 2) -> Box | None:
        """Top-left-anchored box (w × h plus ``pad``) near (x, y), inside the image and clear
        of :attr:`label_boxes` and :attr:`reserved`: tried right, above, left, below and the
        diagonals, nearest first."""
        W, H = self.image.size
        for d in (6, 14, 28, 48, 80, 130, 200):
            for px, py in (
                (x + d, y - h / 2),
                (x + d, y - d - h),
                (x - d - w, y - d - h),
                (x - w / 2, y - d - h),
                (x - d - w, y - h / 2),
                (x + d, y + d),
                (x - d - w, y + d),
                (x - w / 2, y + d),
            ):
                box = (math.floor(px) - pad, math.floor(py) - pad, math.ceil(px + w) + pad, math.ceil(py + h) + pad)
                if (
                    box[0] >= 0
                    and box[1] >= 0
                    and box[2] <= W
                    and box[3] <= H
                    and not any(boxes_overlap(box, b) for _, b in self.label_boxes)
                    and not any(boxes_overlap(box, b) for b in self.reserved)
                ):
                    return box
        return None

    # --- output ----------------------------------------------------------------------

    def save(self, path: str | Path) -> Path:
        """Write the picture atomically, as PNG or JPEG by the extension of ``path``."""
        return save_image(self.image, path)


def save_image(image: Image.Image, path: str | Path) -> Path:
    """Write ``image`` atomically in the format of the extension of ``path`` (PNG or JPEG)."""
    fmt = image_format(path)
    buf = io.BytesIO()
    if fmt == "JPEG":
        image.convert("RGB").save(buf, format="JPEG", quality=92)
    else:
        image.save(buf, format=fmt, optimize=True)
    atomic_write_bytes(path, buf.getvalue())
    return Path(path)


def boxes_overlap(a: Box, b: Box) -> bool:
    """Whether two pixel boxes share any pixel."""
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def _nearest_in_box(box: Box, x: float, y: float) -> tuple[float, float]:
    return min(max(x, box[0]), box[2]), min(max(y, box[1]), box[3])


def fit_scale(longest: int, max_px: int, min_px: int) -> float:
    """Pixels per cell: shrink to ``max_px``, or enlarge small grids towards ``min_px`` (≤ 4x)."""
    if longest >= min_px:
        return min(1.0, max_px / longest)
    return min(4.0, min_px / longest, max_px / longest)


def font(size_px: int) -> ImageFont.ImageFont | ImageFont.FreeTypeFont:
    try:
        return ImageFont.load_default(size=size_px)
    except TypeError:  # Pillow < 10.1 has no sized default font
        return ImageFont.load_default()
