"""Issue 38, class E: the open-map containment test's wall-crossing check is vectorised
(every wall edge indexed once, each move tested against the edges near it in numpy), so
a floor plan speckled with thousands of one-pixel islands (a SLAM artefact) costs about
what a clean one does: the PhysX check's default run (12 stations x 24 probes, a check
every 2 steps over 2 s) stays within seconds, where the per-wall Python loop took minutes."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
from PIL import Image

from roboracer_arena.maps.corridor import extract_corridor
from roboracer_arena.physx.open_probes import WallSegments, crosses_walls


def _speckled(tmp_path: Path, islands: int = 3000) -> Path:
    rng = np.random.default_rng(38)
    img = np.full((400, 400), 254, np.uint8)
    img[:3, :] = img[-3:, :] = img[:, :3] = img[:, -3:] = 0
    rows, cols = rng.integers(5, 395, islands), rng.integers(5, 395, islands)
    img[rows, cols] = 0  # one-pixel islands
    Image.fromarray(img).save(tmp_path / "speckled.png")
    y = tmp_path / "speckled.yaml"
    y.write_text(
        "image: speckled.png\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    return y


def _loop_per_wall(walls, a, b):
    """The former implementation: a Python loop over walls (the oracle)."""
    hit = np.zeros(len(a), dtype=bool)
    ax, ay, bx, by = (v[:, None] for v in (a[:, 0], a[:, 1], b[:, 0], b[:, 1]))
    for w in walls:
        p, q = w, np.roll(w, -1, axis=0)
        px, py, qx, qy = (v[None, :] for v in (p[:, 0], p[:, 1], q[:, 0], q[:, 1]))

        def side(x0, y0, x1, y1, x, y):
            return np.sign((x1 - x0) * (y - y0) - (y1 - y0) * (x - x0))

        hit |= (
            (side(ax, ay, bx, by, px, py) * side(ax, ay, bx, by, qx, qy) < 0)
            & (side(px, py, qx, qy, ax, ay) * side(px, py, qx, qy, bx, by) < 0)
        ).any(axis=1)
    return hit


def test_speckled_map_crossing_checks_are_fast_and_exact(tmp_path):
    geo = extract_corridor(_speckled(tmp_path), open=True)
    walls = [np.asarray(w, np.float64) for w in geo.walls]
    assert len(walls) > 1000  # every island is a wall ring
    rng = np.random.default_rng(0)
    probes = 12 * 8 * 3  # the default plan
    a = rng.uniform(0, 20, (probes, 2))
    b = a + rng.normal(0, 0.15, (probes, 2))
    t0 = time.perf_counter()
    segments = WallSegments(walls)
    index_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    for _ in range(100):  # 2 s at 10 ms steps, a check every 2 steps
        got = segments.crossed(a, b)
    per_run = time.perf_counter() - t0
    assert index_s < 5 and per_run < 20, (index_s, per_run)
    sample = slice(0, 40)
    assert np.array_equal(got[sample], _loop_per_wall(walls, a[sample], b[sample]))
    assert np.array_equal(crosses_walls(walls, a, b), got)


def test_crossings_exact_against_the_loop_on_long_and_short_walls():
    rng = np.random.default_rng(1)
    walls = [np.array([[0, 0], [20, 0], [20, 20], [0, 20.0]])]  # long edges, cut into pieces for the index
    for _ in range(300):
        c, r, n = rng.uniform(1, 19, 2), rng.uniform(0.02, 0.8), rng.integers(3, 9)
        t = np.sort(rng.uniform(0, 2 * np.pi, n))
        walls.append(np.c_[c[0] + r * np.cos(t), c[1] + r * np.sin(t)])
    a = rng.uniform(-1, 21, (500, 2))
    b = a + rng.normal(0, 0.5, (500, 2))
    b[:5] = np.nan  # a lost body: no crossing, no error
    got = WallSegments(walls).crossed(a, b)
    want = _loop_per_wall(walls, a, b)
    assert np.array_equal(got, want) and 20 < got.sum() < 500
    assert not WallSegments([]).crossed(a, b).any()
