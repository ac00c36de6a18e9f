"""``tracks sheet``: a contact sheet of every catalog track: thumbnail, id, kind, lap
length, extent in metres and a scale bar per thumbnail (thumbnails are each fitted to
their cell, so the scale differs; the bar and the extent say by how much)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from .catalog import Catalog
from .entry import TrackEntry

KIND_COLOUR = {"circuit": (200, 40, 40), "recorded": (40, 90, 200), "generated": (30, 140, 60)}


def thumbnail(yaml_path: Path, size: tuple[int, int]) -> tuple[Image.Image, tuple[float, float]]:
    """The map's corridor (free space elsewhere blanked), cropped to its known cells, as a
    greyscale thumbnail, and the (width, height) in metres that the thumbnail shows."""
    from ..maps import load_map
    from .recorded import corridor_grid

    m = load_map(yaml_path)
    data = np.asarray(m.data, np.uint8)
    iso, _, _ = corridor_grid(yaml_path, data)
    if iso is not None:
        data = iso
        # Walls not bordering the corridor (thin-line maps' far side, clutter) are blanked too.
        from scipy import ndimage

        near = ndimage.binary_dilation(data == 254, iterations=max(2, int(round(0.3 / m.resolution))))
        data = np.where((data == 0) & ~near, 205, data).astype(np.uint8)
    known = data != 205
    if known.any():
        rows, cols = np.nonzero(known.any(axis=1))[0], np.nonzero(known.any(axis=0))[0]
        data = data[rows[0] : rows[-1] + 1, cols[0] : cols[-1] + 1]
    # Drivable space dark, walls mid-grey, unknown white; shrink by block minimum first so
    # a corridor a few cells wide stays visible at thumbnail size.
    shade = np.where(data == 254, 30, np.where(data == 0, 150, 255)).astype(np.uint8)
    f = max(1, int(min(shade.shape[1] / size[0], shade.shape[0] / size[1])))
    if f > 1:
        h, w = (shade.shape[0] // f) * f, (shade.shape[1] // f) * f
        shade = shade[:h, :w].reshape(h // f, f, w // f, f).min(axis=(1, 3))
    extent = (data.shape[1] * float(m.resolution), data.shape[0] * float(m.resolution))
    img = Image.fromarray(shade, "L")
    img.thumbnail(size, Image.Resampling.LANCZOS)
    return img, extent


def contact_sheet(
    cat: Catalog,
    entries: list[TrackEntry],
    out: Path,
    sources: Path | None = None,
    columns: int = 12,
    cell: tuple[int, int] = (180, 150),
    progress=None,
) -> Path:
    """Draw every entry as a thumbnail with its id, lap length, extent and scale bar; write
    the picture (PNG or JPEG by the extension of ``out``) atomically."""
    from ..render.formats import image_format
    from ..render.topdown import save_image

    image_format(out)  # before any work
    rows = (len(entries) + columns - 1) // columns
    label_h = 44
    sheet = Image.new("RGB", (columns * cell[0], rows * (cell[1] + label_h)), "white")
    draw = ImageDraw.Draw(sheet)
    font = ImageFont.load_default()
    it = progress(entries, len(entries)) if progress else entries
    for k, e in enumerate(it):
        x0, y0 = (k % columns) * cell[0], (k // columns) * (cell[1] + label_h)
        extent = None
        try:
            th, extent = thumbnail(cat.map_path(e, sources), (cell[0] - 8, cell[1] - 22))
            th = th.convert("RGB")
            sheet.paste(th, (x0 + (cell[0] - th.width) // 2, y0 + 4 + (cell[1] - 22 - th.height) // 2))
            _scale_bar(draw, x0 + 6, y0 + cell[1] - 12, th.width / extent[0], cell[0] // 2, font)
        except Exception as ex:  # a broken map still gets its cell, with the error
            draw.text((x0 + 4, y0 + cell[1] // 2), f"cannot load: {type(ex).__name__}", fill=(200, 0, 0), font=font)
        colour = KIND_COLOUR.get(e.kind, (0, 0, 0))
        draw.rectangle([x0 + 1, y0 + 1, x0 + cell[0] - 2, y0 + cell[1] + label_h - 2], outline=colour)
        draw.text((x0 + 4, y0 + cell[1]), e.id[:28], fill=(0, 0, 0), font=font)
        kind = f"{e.kind}, lap {e.lap_length_m:.1f} m"
        draw.text((x0 + 4, y0 + cell[1] + 13), kind, fill=colour, font=font)
        if extent is not None:
            draw.text(
                (x0 + 4, y0 + cell[1] + 26), f"extent {extent[0]:.0f} x {extent[1]:.0f} m", fill=(60, 60, 60), font=font
            )
    return save_image(sheet, out)


def _scale_bar(draw: ImageDraw.ImageDraw, x: int, y: int, px_per_m: float, max_px: int, font) -> None:
    """A 1-2-5 scale bar of the thumbnail at (x, y) with its length beside it."""
    from ..render.frame import scale_length

    metres, px = scale_length(px_per_m, max_px)
    draw.rectangle([x, y, x + px, y + 4], fill=(0, 0, 0))
    draw.text((x + px + 4, y - 4), f"{metres:g} m", fill=(0, 0, 0), font=font)
