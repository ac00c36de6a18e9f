"""How long a lap a rectilinear double spiral holds in each missed sweep spec's hall.

Evidence for issue 15's acceptance sweep (BENCHMARKS.md, "Where it still fails"): the
laps the generator misses are longer than a rounded rectangle in the hall holds, so they
need passes folded back and forth. The densest folded loop we know is a double spiral:
the boundary of a "snake" of width p wound inwards with gaps of p, so neighbouring passes
are exactly one pitch apart everywhere except at its three folds (the snake's two ends
and the innermost gap). This script builds that spiral for every miss and reports the
longest lap it reaches, in two variants:

* ``ideal``: the longest over fold widths from 2 r_c (the tightest a fold with corners of
  radius r_c can be) to 3.6 r_c, unchecked. A fold under about 3.5 r_c is a hairpin to
  the curvature detector, so this bounds the family from above; it is not a valid track
  for a spec with fewer hairpins than folds.
* ``valid``: the folds widened to 3.6 r_c (two separate 90° corners) by making the
  snake's first and last bands that wide; every spiral counted here is featureless and
  clears itself by p under ``_core.analyse_curve``, the validator's own detector.

Usage: ``python -m benchmarks constructors --sweep --json SWEEP.json`` then
``python -m benchmarks.spiral_capacity SWEEP.json``. (Not in the wheel.)
"""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from benchmarks.constructor_sweep import sweep_specs
from roboracer_arena import _core
from roboracer_arena.config.constructor import ConstructorConfig
from roboracer_arena.generate import derived_geometry
from roboracer_arena.spec import TrackSpec

Rect = tuple[float, float, float, float]  # x0, x1, y0, y1


def union_boundary(rects: list[Rect]) -> list[tuple[float, float]] | None:
    """Counter-clockwise boundary of a union of axis-aligned rectangles, or None unless
    the union is one simply connected region without diagonal contacts."""
    xs = sorted({v for r in rects for v in r[:2]})
    ys = sorted({v for r in rects for v in r[2:]})
    fill = np.zeros((len(xs) + 1, len(ys) + 1), bool)
    for i in range(len(xs) - 1):
        cx = 0.5 * (xs[i] + xs[i + 1])
        for j in range(len(ys) - 1):
            cy = 0.5 * (ys[j] + ys[j + 1])
            fill[i + 1, j + 1] = any(r[0] < cx < r[1] and r[2] < cy < r[3] for r in rects)
    nxt: dict[tuple[int, int], tuple[int, int]] = {}
    for i, j in zip(*np.nonzero(fill), strict=True):
        sides = (
            (0, -1, (i, j), (i + 1, j)),
            (1, 0, (i + 1, j), (i + 1, j + 1)),
            (0, 1, (i + 1, j + 1), (i, j + 1)),
            (-1, 0, (i, j + 1), (i, j)),
        )
        for di, dj, a, b in sides:
            if not fill[i + di, j + dj]:
                if a in nxt:
                    return None
                nxt[a] = b
    start = next(iter(nxt))
    loop, cur = [start], nxt[start]
    while cur != start and len(loop) <= len(nxt):
        loop.append(cur)
        cur = nxt[cur]
    if len(loop) != len(nxt):
        return None
    pts = [(xs[i - 1], ys[j - 1]) for i, j in loop]
    n = len(pts)
    turn = lambda a, b, c: (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0])
    return [pts[k] for k in range(n) if turn(pts[k - 1], pts[k], pts[(k + 1) % n]) != 0]


def fillet(poly: list[tuple[float, float]], r: float, step: float = 0.02) -> np.ndarray | None:
    """Round every (90°) corner with radius r; None if two fillets overlap on a side."""
    p = np.asarray(poly, float)
    n = len(p)
    if any(np.linalg.norm(p[(k + 1) % n] - p[k]) < 2 * r for k in range(n)):
        return None
    out = []
    for k in range(n):
        din = (p[k] - p[k - 1]) / np.linalg.norm(p[k] - p[k - 1])
        dout = (p[(k + 1) % n] - p[k]) / np.linalg.norm(p[(k + 1) % n] - p[k])
        turn = math.atan2(din[0] * dout[1] - din[1] * dout[0], din @ dout)
        start = p[k] - din * r * math.tan(abs(turn) / 2)
        centre = start + math.copysign(r, turn) * np.array([-din[1], din[0]])
        a0 = math.atan2(start[1] - centre[1], start[0] - centre[0])
        m = max(2, math.ceil(abs(turn) * r / step))
        a = a0 + turn * np.arange(m + 1) / m
        out.append(centre + r * np.column_stack([np.cos(a), np.sin(a)]))
    return np.vstack(out)


def snake(x: float, y: float, p: float, fold: float, bands: int, last: float) -> list[Rect] | None:
    """The snake's bands, wound counter-clockwise inwards from the bottom side of the box
    [0, x] × [0, y]: the first and last bands `fold` wide, the others p, gaps p; `bands`
    full bands then one of run length `last`. None when the last band leaves the box."""
    box = [0.0, x, 0.0, y]  # left, right, bottom, top
    before = list(box)  # each side's coordinate before its last shrink
    rects: list[Rect] = []
    for k in range(bands + 1):
        side = k % 4
        w = fold if k in (0, bands) else p
        end = k == bands
        if side == 0:
            x0 = p if k == 0 else before[0]
            r = (x0, min(box[1], x0 + last) if end else box[1], box[2], box[2] + w)
        elif side == 1:
            r = (box[1] - w, box[1], before[2], min(box[3], before[2] + last) if end else box[3])
        elif side == 2:
            r = (max(box[0], before[1] - last) if end else box[0], before[1], box[3] - w, box[3])
        else:
            r = (box[0], box[0] + w, max(box[2], before[3] - last) if end else box[2], before[3])
        # The band's inner edge must stay inside the box the earlier bands left.
        inside = (r[3] <= box[3], r[0] >= box[0], r[2] >= box[2], r[1] <= box[1])[side]
        if not inside or r[1] - r[0] <= 1e-9 or r[3] - r[2] <= 1e-9:
            return None
        rects.append(r)
        idx, sign = ((2, 1), (1, -1), (3, -1), (0, 1))[side]
        before[idx] = box[idx]
        box[idx] += sign * (w + p)
    return rects


def spirals(x: float, y: float, p: float, rc: float, fold: float) -> Iterator[np.ndarray]:
    """Every rounded spiral of the family in both orientations of the box."""
    for bx, by in ((x, y), (y, x)):
        for bands in range(1, 40):
            for last in np.linspace(0.5, max(bx, by), 25):
                rects = snake(bx, by, p, fold, bands, float(last))
                poly = union_boundary(rects) if rects else None
                line = fillet(poly, rc) if poly else None
                if line is not None:
                    yield line


def capacity(spec: TrackSpec, fold_rc: float, check: bool) -> float:
    """Longest spiral lap (m) in the spec's centreline box; with `check`, only spirals
    the detector reads as featureless and self-clearing by p."""
    cfg = ConstructorConfig()
    d = derived_geometry(spec, cfg)
    wall = spec.corridor_width_m + 2 * cfg.wall_thickness_m
    x = spec.hall_x_m - 2 * cfg.hall_margin_m - wall
    y = spec.hall_y_m - 2 * cfg.hall_margin_m - wall
    best = 0.0
    for line in spirals(x, y, d.pitch, d.corner_radius, fold_rc * d.corner_radius):
        length = _core.polyline_length(line, True)
        if length <= best:
            continue
        if check:
            a = _core.analyse_curve(line, d.corner_radius, math.pi * d.pitch / 2)
            clear = a.self_clearance_m
            if a.features or (clear is not None and clear < d.pitch - 1e-6):
                continue
        best = length
    return best


def main(sweep_json: str) -> None:
    specs = {s.name: s for s in sweep_specs()}
    misses = [specs[m["spec"]] for m in json.loads(Path(sweep_json).read_text())["misses"]]
    held = {"ideal": 0, "valid": 0}
    print(f"{'spec':36} {'L':>6} {'ideal':>7} {'valid':>7}")
    for spec in misses:
        ideal = max(capacity(spec, f, check=False) for f in (2.0, 2.4, 2.8, 3.2, 3.6))
        valid = capacity(spec, 3.6, check=True)
        held["ideal"] += ideal >= spec.lap_length_m
        held["valid"] += valid >= spec.lap_length_m
        print(f"{spec.name:36} {spec.lap_length_m:6.1f} {ideal:7.1f} {valid:7.1f}")
    n = len(misses)
    print(f"laps a spiral holds: ideal folds {held['ideal']}/{n}, valid folds {held['valid']}/{n}")


if __name__ == "__main__":
    main(sys.argv[1])
