"""The paper's two baseline constructors (Table "Constructor comparison"), with scipy.

Both share one parameter vector and its bounds:

* ``n_links`` *links*, each a straight (0.3 m … L/4), then a turn of angle in
  [−137°, 137°] at radius [r_c, 1.4 r_c];
* one *feature block* per requested feature, spread evenly between the links: a hairpin
  turn of 160°–200° at [r_c, 1.5 r_c]; a chicane as two opposite turns of 60°–110°
  (second/first ratio 0.8–1.2) at [r_c, 1.5 r_c]; a sweeper turn of 70°–110° at
  [1.6 r_c, 2.5 r_c].

The vector is integrated into a curvature profile (piecewise constant: 0 on straights,
±1/ρ on turns) and then into a centreline.

* **DE** (``scipy.optimize.differential_evolution``) projects every integrated curve
  globally — link turns shifted equally so the total turn is exactly 2π, then the link
  straights changed by the least-norm correction that closes the loop (arcs stay exact;
  a gap left by the straights' bounds is spread linearly along the arc length) — and
  minimises the sum of penalties for lap length, minimum radius, self-clearance, hall
  fit and squared feature-count error, each scaled to its validator tolerance (corridor
  width is imposed by the rasteriser, so its curve-level penalty is zero). It
  emits its best curve unless that curve crosses itself. Budget: ``maxiter=30``,
  ``popsize=5`` (≈ 4 k evaluations of ~1–2 ms), ``tol=0.01``, no polishing — several
  seconds per trial on one core, comparable to the paper's 5.1 s. Link radii are bounded
  to [r_c, 1.4 r_c], below the detector's sweeper band, so only feature blocks make
  sweepers (with [r_c, 3 r_c] most DE results grew unrequested sweepers).
* **Random** draws the vector uniformly once, integrates it, and emits it: no
  optimisation, no projection (the rasteriser closes the loop with a straight segment).
  It is the performance floor.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import differential_evolution

from roboracer_arena import _core
from roboracer_arena.config.constructor import ConstructorConfig
from roboracer_arena.generate.report import CurveAnalysis
from roboracer_arena.spec import TrackSpec

LINK_TURN_DEG = 137.0
# Link radii stay below the detector's sweeper band (1.5 r_c): only feature blocks make sweepers.
LINK_RADIUS_MAX = 1.4
DE_MAXITER = 30
DE_POPSIZE = 5
STEP_M = 0.1  # integration step along the centreline
STRAIGHT_MIN_M = 0.3  # shortest link straight


def _geometry(spec: TrackSpec, config: ConstructorConfig) -> tuple[float, float, float]:
    w = spec.corridor_width_m
    r_min = spec.min_radius_m if spec.min_radius_m > 0 else max(0.9, 0.75 * w)
    p = config.pitch(w)
    rc = max(p, 2 * r_min) / 2
    return r_min, p, rc


def _features(spec: TrackSpec) -> list[str]:
    if spec.feature_order:
        return list(spec.feature_order)
    return ["hairpin"] * spec.hairpins + ["chicane"] * spec.chicanes + ["sweeper"] * spec.sweepers


def _layout(spec: TrackSpec, config: ConstructorConfig) -> tuple[list[str], int, list[tuple[float, float]]]:
    """Block sequence ('link' or a feature name) and the box bounds of the vector."""
    feats = _features(spec)
    n_links = max(4, 8 - len(feats))
    _, _, rc = _geometry(spec, config)
    L = spec.lap_length_m
    seq: list[str] = []
    # Spread features evenly between links.
    for i in range(n_links):
        seq.append("link")
        lo, hi = i * len(feats) // n_links, (i + 1) * len(feats) // n_links
        seq.extend(feats[lo:hi])
    bounds: list[tuple[float, float]] = []
    rad = math.radians
    for b in seq:
        if b == "link":
            bounds += [(STRAIGHT_MIN_M, L / 4), (-rad(LINK_TURN_DEG), rad(LINK_TURN_DEG)), (rc, LINK_RADIUS_MAX * rc)]
        elif b == "hairpin":
            bounds += [(rad(160), rad(200)), (rc, 1.5 * rc), (0.0, 1.0)]
        elif b == "chicane":
            bounds += [(rad(60), rad(110)), (rc, 1.5 * rc), (0.8, 1.2)]
        else:
            bounds += [(rad(70), rad(110)), (1.6 * rc, 2.5 * rc), (0.0, 1.0)]
    return seq, n_links, bounds


def _segments(seq: list[str], x: np.ndarray, sense: float, turn_shift: float = 0.0) -> list[tuple[float, float]]:
    """(length, curvature) pieces; ``turn_shift`` is added to every link turn (projection)."""
    out: list[tuple[float, float]] = []

    def arc(angle: float, radius: float) -> None:
        if abs(angle) > 1e-9:
            out.append((abs(angle) * radius, math.copysign(1.0 / radius, angle)))

    for i, b in enumerate(seq):
        a, r, c = x[3 * i : 3 * i + 3]
        if b == "link":
            out.append((a, 0.0))
            arc(r + turn_shift, c)
        elif b == "hairpin" or b == "sweeper":
            arc(sense * a, r)
        else:
            arc(sense * a, r)
            arc(-sense * a * c, r)
    return out


def _integrate(segs: list[tuple[float, float]]) -> tuple[np.ndarray, np.ndarray]:
    """Points (and their arc length) of the curve starting at 0 heading +x (exact arcs)."""
    xs: list[np.ndarray] = [np.zeros(1)]
    ys: list[np.ndarray] = [np.zeros(1)]
    ss: list[np.ndarray] = [np.zeros(1)]
    x = y = th = s = 0.0
    for length, k in segs:
        n = max(1, int(math.ceil(length / STEP_M)))
        h = np.arange(1, n + 1) * (length / n)
        if k == 0.0:
            px, py, th2 = x + h * math.cos(th), y + h * math.sin(th), th
        else:
            t = th + k * h
            px, py, th2 = x + (np.sin(t) - math.sin(th)) / k, y - (np.cos(t) - math.cos(th)) / k, th + k * length
        xs.append(px)
        ys.append(py)
        ss.append(s + h)
        x, y, th, s = float(px[-1]), float(py[-1]), th2, s + length
    return np.column_stack([np.concatenate(xs), np.concatenate(ys)]), np.concatenate(ss)


def _endpoint(segs: list[tuple[float, float]]) -> tuple[np.ndarray, np.ndarray]:
    """Heading at the start of every piece and the end point of the curve (closed form)."""
    lk = np.array(segs, float).reshape(-1, 2)
    turn = lk[:, 0] * lk[:, 1]
    th = np.concatenate([[0.0], np.cumsum(turn)[:-1]])
    straight = lk[:, 1] == 0.0
    k = np.where(straight, 1.0, lk[:, 1])
    dx = np.where(straight, lk[:, 0] * np.cos(th), (np.sin(th + turn) - np.sin(th)) / k)
    dy = np.where(straight, lk[:, 0] * np.sin(th), -(np.cos(th + turn) - np.cos(th)) / k)
    return th, np.array([dx.sum(), dy.sum()])


def _project(seq: list[str], n_links: int, x: np.ndarray, sense: float, max_straight: float) -> np.ndarray:
    """DE's global projection. Total turn: every link turn shifted equally so the curve
    turns exactly 2π. Closure: the link straights (the only free lengths once headings
    are fixed) change by the least-norm correction that closes the loop, kept within
    [0.3 m, ``max_straight``];
    any gap left by that floor is spread linearly along the arc length."""
    segs = _segments(seq, x, sense)
    total = sum(length * k for length, k in segs)
    segs = _segments(seq, x, sense, (sense * 2 * math.pi - total) / n_links)
    for _ in range(3):
        th, gap = _endpoint(segs)
        free = [
            i
            for i, (length, k) in enumerate(segs)
            if k == 0.0 and (length > STRAIGHT_MIN_M + 1e-9 or gap @ [math.cos(th[i]), math.sin(th[i])] < 0)
        ]
        if np.hypot(*gap) < 1e-6 or len(free) < 2:
            break
        u = np.column_stack([np.cos(th[free]), np.sin(th[free])])
        gram = u.T @ u
        if abs(np.linalg.det(gram)) < 1e-9:
            break
        delta = -u @ np.linalg.solve(gram, gap)
        for i, d in zip(free, delta):
            segs[i] = (min(max_straight, max(STRAIGHT_MIN_M, segs[i][0] + d)), 0.0)
    pts, s = _integrate(segs)
    gap = pts[-1] - pts[0]
    pts = pts - np.outer(s / s[-1], gap)
    return pts[:-1]


def _raw(seq: list[str], x: np.ndarray, sense: float) -> np.ndarray:
    pts, _ = _integrate(_segments(seq, x, sense))
    return pts[:-1] if np.hypot(*(pts[-1] - pts[0])) < 1e-9 else pts


def _penalty(pts: np.ndarray, spec: TrackSpec, config: ConstructorConfig) -> float:
    r_min, p, rc = _geometry(spec, config)
    L = spec.lap_length_m
    a = CurveAnalysis.of(pts, rc, math.pi * p / 2)
    length = _core.polyline_length(pts, True)
    clearance = math.inf if a.self_clearance_m is None else a.self_clearance_m
    counts = {k: 0 for k in ("hairpin", "chicane", "sweeper")}
    for f in a.features:
        counts[f.kind] += 1
    feat = sum((counts[k] - getattr(spec, k + "s")) ** 2 for k in counts)
    # Each term is scaled so that reaching the validator's tolerance costs about as much
    # as one wrong feature count.
    pen = feat + ((length - L) / (0.02 * L)) ** 2
    pen += (max(0.0, r_min - a.min_radius_m) / (0.05 * r_min)) ** 2
    pen += (max(0.0, p - clearance) / (0.05 * p)) ** 2
    wall = spec.corridor_width_m + 2 * config.wall_thickness_m
    ux, uy = spec.hall_x_m - 2 * config.hall_margin_m - wall, spec.hall_y_m - 2 * config.hall_margin_m - wall
    ex, ey = np.ptp(pts[:, 0]), np.ptp(pts[:, 1])
    over = min(max(0, ex - ux) + max(0, ey - uy), max(0, ey - ux) + max(0, ex - uy))
    return pen + (over / 0.1) ** 2


def _orient(pts: np.ndarray, spec: TrackSpec) -> np.ndarray:
    return pts[::-1].copy() if spec.direction == "clockwise" else pts


def construct_baseline(spec: TrackSpec, config: ConstructorConfig, seed: int, kind: str) -> np.ndarray | None:
    """A centreline (N, 2) from the ``"de"`` or ``"random"`` baseline, or None."""
    seq, n_links, bounds = _layout(spec, config)
    sense = 1.0  # built counter-clockwise, reversed for clockwise laps
    if kind == "random":
        rng = np.random.default_rng(seed)
        x = np.array([rng.uniform(lo, hi) for lo, hi in bounds])
        return _orient(_raw(seq, x, sense), spec)
    if kind != "de":
        raise ValueError(f"unknown baseline {kind!r}")
    res = differential_evolution(
        lambda x: _penalty(_project(seq, n_links, x, sense, spec.lap_length_m / 2), spec, config),
        bounds,
        seed=seed,
        maxiter=DE_MAXITER,
        popsize=DE_POPSIZE,
        tol=0.01,
        polish=False,
        init="sobol",
    )
    pts = _project(seq, n_links, res.x, sense, spec.lap_length_m / 2)
    if len(_core.self_intersections(pts)[0]):  # a crossing curve is not a track
        return None
    return _orient(pts, spec)
