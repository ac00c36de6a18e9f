"""Small ROS maps the tests write themselves: a ring corridor in a filled or thin-line style."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image


def ring_raster(size: int = 200, r_in: float = 0.25, r_out: float = 0.42, style: str = "filled") -> np.ndarray:
    """A ``size``² 8-bit image (row 0 = top): free ring between radii ``r_in`` and ``r_out``
    (fractions of ``size``). ``filled``: black outside the ring; ``thin``: white everywhere
    with two 2-pixel black circles as walls."""
    yy, xx = np.mgrid[0:size, 0:size] + 0.5
    r = np.hypot(xx - size / 2, yy - size / 2) / size
    if style == "filled":
        img = np.where((r > r_in) & (r < r_out), 254, 0)
    elif style == "thin":
        img = np.full((size, size), 254)
        img[np.abs(r - r_in) < 2 / size] = 0
        img[np.abs(r - r_out) < 2 / size] = 0
    else:
        raise ValueError(style)
    return img.astype(np.uint8)


def write_map(
    folder: Path,
    img: np.ndarray,
    name: str = "ring",
    resolution: float = 0.05,
    origin: tuple[float, float, float] = (-5.0, -5.0, 0.0),
) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    Image.fromarray(img, mode="L").save(folder / f"{name}.png")
    yaml = folder / f"{name}.yaml"
    yaml.write_text(
        f"image: {name}.png\nresolution: {resolution}\norigin: [{origin[0]}, {origin[1]}, {origin[2]}]\n"
        "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    return yaml
