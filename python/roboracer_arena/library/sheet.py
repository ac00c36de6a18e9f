"""``tracks sheet``: a contact sheet of every catalog track (thumbnail, id, lap length)."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from ..fileio import atomic_write_bytes
from .catalog import Catalog

KIND_COLOUR = {"circuit": (200, 40, 40), "recorded": (40, 90, 200), "generated": (30, 140, 60)}


def thumbnail(yaml_path: Path, size: tuple[int, int]) -> Image.Image:
    """The map cropped to its known (non-unknown) cells, as a greyscale thumbnail."""
    from ..generate.mapfile import load_ros_map

    data = np.asarray(load_ros_map(yaml_path).data, np.uint8)
    known = data != 205
    if known.any():
        rows, cols = np.nonzero(known.any(axis=1))[0], np.nonzero(known.any(axis=0))[0]
        data = data[rows[0]: rows[-1] + 1, cols[0]: cols[-1] + 1]
    img = Image.fromarray(np.where(data == 254, 255, np.where(data == 0, 0, 215)).astype(np.uint8), "L")
    # Min-filter while shrinking so thin walls survive: reduce in integer steps first.
    factor = max(1, int(min(img.width / size[0], img.height / size[1]) // 2))
    if factor > 1:
        img = img.reduce(factor)
    img.thumbnail(size, Image.Resampling.LANCZOS)
    return img


def contact_sheet(cat: Catalog, entries: list[dict], out: Path, sources: Path | None = None, columns: int = 12,
                  cell: tuple[int, int] = (180, 150), progress=None) -> Path:
    """Draw every entry as a thumbnail with its id and lap length; write a PNG atomically."""
    rows = (len(entries) + columns - 1) // columns
    label_h = 28
    sheet = Image.new("RGB", (columns * cell[0], rows * (cell[1] + label_h)), "white")
    draw = ImageDraw.Draw(sheet)
    font = ImageFont.load_default()
    it = progress(entries, len(entries)) if progress else entries
    for k, e in enumerate(it):
        x0, y0 = (k % columns) * cell[0], (k // columns) * (cell[1] + label_h)
        try:
            th = thumbnail(cat.map_path(e, sources), (cell[0] - 8, cell[1] - 8)).convert("RGB")
            sheet.paste(th, (x0 + (cell[0] - th.width) // 2, y0 + (cell[1] - th.height) // 2))
        except Exception as ex:  # a broken map still gets its cell, with the error
            draw.text((x0 + 4, y0 + cell[1] // 2), f"cannot load: {type(ex).__name__}", fill=(200, 0, 0), font=font)
        colour = KIND_COLOUR.get(e["kind"], (0, 0, 0))
        draw.rectangle([x0 + 1, y0 + 1, x0 + cell[0] - 2, y0 + cell[1] + label_h - 2], outline=colour)
        lap = e.get("lap_length_m")
        draw.text((x0 + 4, y0 + cell[1]), e["id"][:28], fill=(0, 0, 0), font=font)
        draw.text((x0 + 4, y0 + cell[1] + 13), f"{e['kind']} · {lap:.1f} m" if lap else e["kind"], fill=colour, font=font)
    buf = io.BytesIO()
    sheet.save(buf, format="PNG", optimize=True)
    atomic_write_bytes(out, buf.getvalue())
    return out
