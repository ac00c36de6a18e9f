"""``tracks sheet``: a contact sheet of every catalog track: thumbnail, id, kind, lap
length, extent in metres and a scale bar per thumbnail (thumbnails are each fitted to
their cell, so the scale differs; the bar and the extent say by how much)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from ..catalog.catalog_file import Catalog
from ..catalog.entry import TrackEntry
from ..maps.occupancy import load_map
from ..render.formats import image_format
from ..render.frame import LegendEntry, draw_legend, scale_length, wrap_items
from ..render.topdown import font, save_image
from ..render.topdown import font as text_font
from .recorded import corridor_grid

KIND_COLOUR = {"circuit": (200, 40, 40), "recorded": (40, 90, 200), "generated": (30, 140, 60)}

# Thumbnail classes, in the order that wins when a thumbnail pixel covers several map cells:
# a corridor a few cells wide stays visible on a big circuit, and a wall one cell thick
# stays visible on an open floor plan.
UNKNOWN, FLOOR, WALLS, CORRIDOR = 0, 1, 2, 3
SHADE = {
    UNKNOWN: (255, 255, 255),
    FLOOR: (226, 226, 214),
    WALLS: (45, 45, 50),
    CORRIDOR: (60, 170, 90),  # the previews' corridor colour
}
#: Margin kept around an open map's walls when it is cropped (m).
OPEN_MARGIN_M = 1.0


def thumbnail(yaml_path: Path, size: tuple[int, int]) -> tuple[Image.Image, tuple[float, float]]:
    """The map as an RGB thumbnail and the (width, height) in metres that it shows.

    A map with a closed corridor shows the corridor (green) and the walls bordering it
    (dark), cropped to them; a map without one (an open floor plan) shows its free floor
    (light) and walls (dark), cropped to the walls. Unknown cells are white."""
    m = load_map(yaml_path)
    data = np.asarray(m.data, np.uint8)
    iso, _, _ = corridor_grid(yaml_path, data)
    if iso is not None:
        # Walls not bordering the corridor (thin-line maps' far side, clutter) are left out.
        from scipy import ndimage

        near = ndimage.binary_dilation(iso == 254, iterations=max(2, int(round(0.3 / m.resolution))))
        classes = np.where(iso == 254, CORRIDOR, np.where((iso == 0) & near, WALLS, UNKNOWN))
        keep = classes != UNKNOWN
    else:
        classes = np.where(data == 254, FLOOR, np.where(data == 0, WALLS, UNKNOWN))
        keep = _grow(classes == WALLS, int(round(OPEN_MARGIN_M / m.resolution)))
        if not keep.any():
            keep = classes != UNKNOWN
    if keep.any():
        rows, cols = np.nonzero(keep.any(axis=1))[0], np.nonzero(keep.any(axis=0))[0]
        classes = classes[rows[0] : rows[-1] + 1, cols[0] : cols[-1] + 1]
    extent = (classes.shape[1] * float(m.resolution), classes.shape[0] * float(m.resolution))
    f = max(1, int(np.ceil(max(classes.shape[1] / size[0], classes.shape[0] / size[1]))))
    if f > 1:  # block maximum of the class: the priority order above
        h, w = -(-classes.shape[0] // f) * f, -(-classes.shape[1] // f) * f
        padded = np.zeros((h, w), classes.dtype)
        padded[: classes.shape[0], : classes.shape[1]] = classes
        classes = padded.reshape(h // f, f, w // f, f).max(axis=(1, 3))
    lut = np.array([SHADE[k] for k in (UNKNOWN, FLOOR, WALLS, CORRIDOR)], np.uint8)
    img = Image.fromarray(lut[classes], "RGB")
    img.thumbnail(size, Image.Resampling.LANCZOS)
    return img, extent


def _grow(mask: np.ndarray, cells: int) -> np.ndarray:
    """``mask``'s bounding box grown by ``cells`` on each side (a box mask), cheaply."""
    out = np.zeros_like(mask)
    if mask.any():
        rows, cols = np.nonzero(mask.any(axis=1))[0], np.nonzero(mask.any(axis=0))[0]
        out[max(0, rows[0] - cells) : rows[-1] + cells + 1, max(0, cols[0] - cells) : cols[-1] + cells + 1] = True
    return out


def sheet_legend() -> list:
    """The sheet's legend: what a frame's colour says (the track's kind) and what a
    thumbnail's colours are."""
    kinds = [LegendEntry(f"frame: {k} track", c, "line") for k, c in KIND_COLOUR.items()]
    return [
        *kinds,
        LegendEntry("drivable corridor", SHADE[CORRIDOR]),
        LegendEntry("walls", SHADE[WALLS]),
        LegendEntry("open floor (no closed corridor)", SHADE[FLOOR]),
    ]


def contact_sheet(
    cat: Catalog,
    entries: list[TrackEntry],
    out: Path,
    sources: Path | None = None,
    columns: int = 12,
    cell: tuple[int, int] = (180, 150),
    progress=None,
) -> Path:
    """Draw every entry as a thumbnail with its id, lap length, extent and scale bar under
    a legend of the frame and map colours; write the picture (PNG or JPEG by the extension
    of ``out``) atomically."""
    image_format(out)  # before any work
    rows = (len(entries) + columns - 1) // columns
    label_h = 44
    width = columns * cell[0]
    probe = ImageDraw.Draw(Image.new("RGB", (1, 1)))
    title_font = text_font(15)
    title = f"{len(entries)} tracks; each thumbnail is fitted to its cell, so its scale bar and extent give its size"
    title_lines = wrap_items(title, lambda line: probe.textlength(line, font=title_font) <= width - 16)
    legend_y = 6 + 20 * len(title_lines)
    header = draw_legend(probe, sheet_legend(), 8, legend_y, width - 16)[3] + 10
    sheet = Image.new("RGB", (width, header + rows * (cell[1] + label_h)), "white")
    draw = ImageDraw.Draw(sheet)
    font = ImageFont.load_default()
    for i, line in enumerate(title_lines):
        draw.text((8, 4 + 20 * i), line, fill=(0, 0, 0), font=title_font)
    draw_legend(draw, sheet_legend(), 8, legend_y, width - 16)
    it = progress(entries, len(entries)) if progress else entries
    for k, e in enumerate(it):
        x0, y0 = (k % columns) * cell[0], header + (k // columns) * (cell[1] + label_h)
        extent = None
        try:
            th, extent = thumbnail(cat.map_path(e, sources), (cell[0] - 8, cell[1] - 22))
            th = th.convert("RGB")
            sheet.paste(th, (x0 + (cell[0] - th.width) // 2, y0 + 4 + (cell[1] - 22 - th.height) // 2))
            _scale_bar(draw, x0 + 6, y0 + cell[1] - 12, th.width / extent[0], cell[0] // 2, font)
        except Exception as ex:  # a broken map still gets its cell, with the error
            draw.text((x0 + 4, y0 + cell[1] // 2), f"cannot load: {type(ex).__name__}", fill=(200, 0, 0), font=font)
        colour = KIND_COLOUR.get(e.kind, (0, 0, 0))
        draw.rectangle([x0 + 1, y0 + 1, x0 + cell[0] - 2, y0 + cell[1] + label_h - 2], outline=colour, width=2)
        draw.text((x0 + 4, y0 + cell[1]), e.id, fill=(0, 0, 0), font=_fitting_font(draw, e.id, cell[0] - 8))
        kind = e.kind + (f", lap {e.lap_length_m:.1f} m" if e.lap_length_m is not None else "")
        draw.text((x0 + 4, y0 + cell[1] + 13), kind, fill=colour, font=font)
        if extent is not None:
            draw.text(
                (x0 + 4, y0 + cell[1] + 26), f"extent {extent[0]:.0f} x {extent[1]:.0f} m", fill=(60, 60, 60), font=font
            )
    return save_image(sheet, out)


def _fitting_font(draw: ImageDraw.ImageDraw, text: str, width: int):
    """The default font at the largest size from 10 px down to 6 px at which ``text``
    fits ``width`` px: an id is shown whole, never cut."""
    for size in range(10, 5, -1):
        f = font(size)
        if draw.textlength(text, font=f) <= width:
            break
    return f


def _scale_bar(draw: ImageDraw.ImageDraw, x: int, y: int, px_per_m: float, max_px: int, font) -> None:
    """A 1-2-5 scale bar of the thumbnail at (x, y) with its length beside it."""
    metres, px = scale_length(px_per_m, max_px)
    draw.rectangle([x, y, x + px, y + 4], fill=(0, 0, 0))
    draw.text((x + px + 4, y - 4), f"{metres:g} m", fill=(0, 0, 0), font=font)
