"""The reference path for narrow maps keeps the most clearance: started from a loop that
hugs a wall (as a centreline pulled aside by an obstacle or a bulge does), it slides to
the ridge of the distance field — midway between the walls of a ring — and the speed cap
follows the clearance."""

from __future__ import annotations

import numpy as np
from PIL import Image

from roboracer_arena.maps.clearance_path import clearance_path
from roboracer_arena.maps.corridor import extract_corridor
from roboracer_arena.track.drivable import Track


def _ring(tmp_path):
    n = 200
    yy, xx = np.mgrid[0:n, 0:n]
    r = np.hypot(xx - n / 2, yy - n / 2)
    img = np.zeros((n, n), np.uint8)
    img[(r > 40) & (r < 90)] = 255  # 2.5 m wide corridor, middle radius 65 cells = 3.25 m
    Image.fromarray(img).save(tmp_path / "ring.png")
    y = tmp_path / "ring.yaml"
    y.write_text(
        "image: ring.png\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    return y


def test_clearance_path_climbs_to_the_middle_of_the_corridor(tmp_path):
    geo = extract_corridor(_ring(tmp_path))
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    centre = np.array([5.0, 5.0])
    hugging = centre + 4.2 * np.column_stack([np.cos(t), np.sin(t)])  # 0.3 m from the outer wall
    cp = clearance_path(geo, hugging)
    radius = np.hypot(*(cp.line - centre).T)
    assert abs(np.median(radius) - 3.25) < 0.1 and radius.std() < 0.05
    walls = Track.from_polylines(geo.walls, cp.line)
    assert float(walls.clearance(cp.line).min()) > 1.1  # half the width, less a cell or two
    assert np.allclose(cp.clearance_m, walls.clearance(cp.line), atol=0.08)
    assert cp.speed_cap.min() > 4.0  # 1.2 m clearance: a fast cap
    tight = clearance_path(geo, hugging, half_width_m=1.2)
    assert tight.speed_cap.max() <= 0.8 + 1e-9  # no clearance beyond the car: the slowest cap
