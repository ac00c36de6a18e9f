"""Recorded-map assessment on small maps written here."""

from __future__ import annotations

import numpy as np
from PIL import Image

from roboracer_arena.library.recorded import assess_map


def _ring(n: int = 120, thin_line: bool = False) -> np.ndarray:
    yy, xx = np.mgrid[0:n, 0:n]
    r = np.hypot(xx - n / 2, yy - n / 2)
    if thin_line:  # white everywhere, two black circles
        img = np.full((n, n), 255, np.uint8)
        img[(np.abs(r - 20) < 1.5) | (np.abs(r - 45) < 1.5)] = 0
        return img
    img = np.zeros((n, n), np.uint8)
    img[(r > 21.5) & (r < 43.5)] = 255
    return img


def _write(tmp_path, name: str, img: np.ndarray, image_name: str | None = None):
    d = tmp_path / "cps-tuwien-f1tenth-maps" / "maps"
    d.mkdir(parents=True, exist_ok=True)
    Image.fromarray(img).save(d / f"{name}.png")
    (d / f"{name}.yaml").write_text(
        f"image: {image_name or name + '.png'}\nresolution: 0.05\norigin: [0, 0, 0]\n"
        "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    return d / f"{name}.yaml"


def test_filled_and_thin_line_rings_are_usable(tmp_path):
    for name, thin in (("filled", False), ("thin", True)):
        y = _write(tmp_path, name, _ring(thin_line=thin))
        r = assess_map(tmp_path, y)
        assert r.usable and r.reason is None, r
        assert r.id == f"cps-{name}" and r.raster is not None and r.raster.width_px == 120
        mid_r = (21.5 + 43.5) / 2 * 0.05 if not thin else (20 + 45) / 2 * 0.05
        assert r.lap_length_m is not None and abs(r.lap_length_m - 2 * np.pi * mid_r) / (2 * np.pi * mid_r) < 0.05


def test_open_and_broken_maps_are_left_out_with_a_reason(tmp_path):
    r = assess_map(tmp_path, _write(tmp_path, "blank", np.full((60, 60), 255, np.uint8)))
    assert not r.usable and r.reason and r.corridor_check == "corridor.extract_corridor"
    r = assess_map(tmp_path, _write(tmp_path, "broken", _ring(), image_name="missing.pgm"))
    assert not r.usable and r.reason and "broken YAML or image" in r.reason and str(tmp_path) not in r.reason
    assert r.raster is None and r.lap_length_m is None  # the assessment stopped at the load
