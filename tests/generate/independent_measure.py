"""An independent re-measurement of a written ROS map, sharing no code with the Rust
validator: the PNG/YAML pair is read with Pillow/numpy, topology is counted with
``scipy.ndimage.label`` and geometry is estimated from areas and a distance transform.

* free corridor: 4-connected components of free (254) pixels;
* infields: components of non-free pixels (8-connected, so a one-pixel wall gap does not
  split them) that do not touch the image border;
* width: twice the median of the free-space distance transform on its ridge (pixels that
  are a local maximum of the transform), i.e. the inscribed-circle diameter;
* lap length: free area / (width − Δ/2): Eq. 3 frees the cells whose centres lie in a band
  of width w − Δ, whose area lies between (w − Δ) L and w L with the grid's alignment (a
  rectangle at full hall size frees ≈ w L, an oblique leg ≈ (w − Δ) L); the midpoint bounds
  the error by Δ / (2 w − Δ), 3.2 % at w = 0.8 m;
* extent: bounding box of the known (non-205) pixels;
* widest spot: the largest inscribed circle, which exposes merged passes.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from PIL import Image
from scipy import ndimage


@dataclass
class Measurement:
    free_components: int
    infields: int
    width_m: float
    max_width_m: float
    lap_length_m: float
    extent_m: tuple[float, float]
    resolution: float


def read_map(yaml_path: Path) -> tuple[np.ndarray, float]:
    """Pixels (row 0 = top) and resolution from a flat ROS map YAML written by the package."""
    meta = {}
    for line in Path(yaml_path).read_text().splitlines():
        key, _, value = line.partition(":")
        meta[key.strip()] = value.strip()
    assert meta["mode"] == "trinary" and meta["negate"] == "0"
    pixels = np.asarray(Image.open(Path(yaml_path).parent / meta["image"]).convert("L"))
    return pixels, float(meta["resolution"])


def measure(yaml_path: Path) -> Measurement:
    pixels, res = read_map(yaml_path)
    free = pixels == 254
    _, n_free = ndimage.label(free)
    solid, n_solid = ndimage.label(~free, structure=np.ones((3, 3), int))
    border = np.unique(np.r_[solid[0], solid[-1], solid[:, 0], solid[:, -1]])
    infields = len(set(range(1, n_solid + 1)) - set(border.tolist()))
    dist = ndimage.distance_transform_edt(free)
    ridge = free & (dist == ndimage.maximum_filter(dist, size=3)) & (dist > 1)
    width = 2 * float(np.median(dist[ridge])) * res if ridge.any() else 0.0
    known = np.argwhere(pixels != 205)
    (r0, c0), (r1, c1) = known.min(0), known.max(0)
    area = float(free.sum()) * res * res
    return Measurement(
        free_components=n_free,
        infields=infields,
        width_m=width,
        max_width_m=2 * float(dist.max()) * res,
        lap_length_m=area / max(width - res / 2, res),
        extent_m=((c1 - c0 + 1) * res, (r1 - r0 + 1) * res),
        resolution=res,
    )


def problems(spec, yaml_path: Path) -> list[str]:
    """What the independent re-measurement of a written map finds wrong with it (empty:
    independently valid) against its TrackSpec."""
    from roboracer_arena.config.constructor import ConstructorConfig

    cfg = ConstructorConfig()
    m = measure(yaml_path)
    w, out = spec.corridor_width_m, []
    if m.free_components != 1:
        out.append(f"{m.free_components} free components, not one corridor")
    if m.infields != 1:
        out.append(f"{m.infields} enclosed infields, not one")
    if abs(m.width_m - w) > 0.05 * w + m.resolution:
        out.append(f"width {m.width_m:.3f} m vs {w} m")
    # No merged passes: nowhere is the corridor much wider than requested.
    if m.max_width_m > w + 2 * m.resolution:
        out.append(f"widest spot {m.max_width_m:.3f} m vs {w} m")
    if abs(m.lap_length_m - spec.lap_length_m) > 0.04 * spec.lap_length_m:
        out.append(f"lap {m.lap_length_m:.2f} m vs {spec.lap_length_m} m")
    ux, uy = spec.hall_x_m - 2 * cfg.hall_margin_m, spec.hall_y_m - 2 * cfg.hall_margin_m
    ex, ey = m.extent_m
    r = m.resolution
    if not ((ex <= ux + r and ey <= uy + r) or (ey <= ux + r and ex <= uy + r)):
        out.append(f"extent {ex:.2f} x {ey:.2f} m outside the {ux} x {uy} m hall")
    return out


def assert_independently_valid(acc, outdir: Path) -> None:
    """Write an Acceptance's outputs to ``outdir`` and re-measure them independently."""
    from roboracer_arena.generate import write_outputs

    found = problems(acc.spec, write_outputs(acc, outdir)["map_yaml"])
    assert not found, found
