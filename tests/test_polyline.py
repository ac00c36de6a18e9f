"""The core's polyline toolbox through the binding (``_core.polyline_length`` …
``_core.self_intersections``): values against closed forms and an independent numpy
reference, typed results, and bad input refused as InvalidArgumentError."""

from __future__ import annotations

import numpy as np
import pytest

from roboracer_arena import _core
from roboracer_arena.errors import InvalidArgumentError


def _circle(n: int, r: float, ccw: bool = True) -> np.ndarray:
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    xy = np.column_stack([r * np.cos(t), r * np.sin(t)])
    return xy if ccw else xy[::-1].copy()


def _ellipse(n: int, a: float, b: float) -> np.ndarray:
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    return np.column_stack([a * np.cos(t), b * np.sin(t)])


def _zigzag(n: int) -> np.ndarray:
    """A loop running back and forth over the same metre n / 4 times (hostile input)."""
    x = np.abs(((np.arange(n) / 4.0) % 2.0) - 1.0)
    return np.column_stack([x, np.zeros(n)])


def _crossings_reference(p: np.ndarray) -> set[tuple[int, int]]:
    """O(n²) segment-pair test, half-open segments, written independently of the core."""
    n, out = len(p), set()
    for i in range(n):
        a, r = p[i], p[(i + 1) % n] - p[i]
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue
            c, s = p[j], p[(j + 1) % n] - p[j]
            den = r[0] * s[1] - r[1] * s[0]
            if abs(den) <= 1e-12 * np.hypot(*r) * np.hypot(*s):
                continue
            q = c - a
            t = (q[0] * s[1] - q[1] * s[0]) / den
            u = (q[0] * r[1] - q[1] * r[0]) / den
            if 0 <= t < 1 and 0 <= u < 1:
                out.add((i, j))
    return out


def test_lengths_match_numpy_and_closed_forms():
    rng = np.random.default_rng(3)
    p = rng.normal(size=(50, 2))
    seg = np.hypot(*np.diff(np.vstack([p, p[:1]]), axis=0).T)
    assert _core.polyline_length(p) == pytest.approx(seg.sum(), rel=1e-12)
    assert _core.polyline_length(p, closed=False) == pytest.approx(seg[:-1].sum(), rel=1e-12)
    cum = _core.cumulative_length(p)
    assert cum.dtype == np.float64 and cum.shape == (51,)
    assert np.allclose(cum, np.r_[0.0, np.cumsum(seg)])
    assert _core.cumulative_length(p, closed=False).shape == (50,)
    # A 1000-gon of radius 2: perimeter 2000 r sin(π/1000), area (1000/2) r² sin(2π/1000).
    c = _circle(1000, 2.0)
    assert _core.polyline_length(c) == pytest.approx(2000 * 2.0 * np.sin(np.pi / 1000), rel=1e-12)
    assert _core.signed_area(c) == pytest.approx(500 * 4.0 * np.sin(2 * np.pi / 1000), rel=1e-12)
    assert _core.signed_area(c[::-1].copy()) < 0
    # A repeated closing point changes no length; the arc lengths stay one per given point.
    assert _core.polyline_length(np.vstack([c, c[:1]])) == pytest.approx(_core.polyline_length(c), rel=1e-15)
    sq = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]])
    assert np.array_equal(_core.cumulative_length(sq), [0.0, 1.0, 2.0, 3.0, 4.0, 4.0])
    assert _core.curvature(sq, 1.0).shape == (4,)  # per distinct vertex


def test_resampling_is_even_on_the_input_and_carries_values():
    sq = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]])
    r = _core.resample_closed(sq, 0.5)
    assert r.shape == (32, 2) and r.dtype == np.float64
    steps = np.hypot(*np.diff(np.vstack([r, r[:1]]), axis=0).T)
    assert np.allclose(steps, 0.5)
    on_edge = np.isclose(r, 0.0) | np.isclose(r, 4.0)
    assert on_edge.any(axis=1).all()  # every point on the square's boundary
    pts, w = _core.resample_closed_values(sq, np.array([1.0, 2.0, 3.0, 4.0]), 1.0)
    assert np.array_equal(pts, _core.resample_closed(sq, 1.0))
    # Linear in arc length along each edge, and back to 1 on the closing edge.
    assert np.allclose(w, [1.0, 1.25, 1.5, 1.75, 2.0, 2.25, 2.5, 2.75, 3.0, 3.25, 3.5, 3.75, 4.0, 3.25, 2.5, 1.75])
    # One value more: the value on returning to point 0 (an unwrapped parameter).
    _, s = _core.resample_closed_values(sq, np.array([0.0, 4.0, 8.0, 12.0, 16.0]), 1.0)
    assert np.allclose(s, np.arange(16.0))


def test_curvature_and_min_radius_against_closed_forms():
    k = _core.curvature(_circle(2000, 3.0), 0.5)
    assert k.shape == (2000,) and np.allclose(k, 1 / 3.0, rtol=1e-9)
    assert np.allclose(_core.curvature(_circle(2000, 3.0, ccw=False), 0.5), -1 / 3.0, rtol=1e-9)
    # Ellipse with semi-axes a > b: smallest radius of curvature b²/a at the ends of the
    # major axis. Fine sampling and a short span keep the chord estimate within 0.1 %.
    a, b = 5.0, 2.0
    e = _core.resample_closed(_ellipse(4000, a, b), 0.01)
    assert _core.min_radius(e, 0.05) == pytest.approx(b * b / a, rel=1e-3)
    assert _core.min_radius(np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]]), 0.5) == np.inf


def test_self_intersections_match_a_brute_force_reference():
    t = np.linspace(0.0, 2 * np.pi, 600, endpoint=False) + 1e-3
    eight = np.column_stack([10 * np.sin(t), 5 * np.sin(2 * t)])
    seg, pts = _core.self_intersections(eight)
    assert seg.dtype == np.int64 and seg.shape == (1, 2) and pts.shape == (1, 2)
    assert np.allclose(pts[0], 0.0, atol=1e-6)
    assert len(_core.self_intersections(_circle(500, 4.0))[0]) == 0
    rng = np.random.default_rng(7)
    for _ in range(20):
        p = rng.uniform(-5, 5, size=(int(rng.integers(4, 40)), 2))
        seg, pts = _core.self_intersections(p)
        assert {tuple(s) for s in seg.tolist()} == _crossings_reference(p)
        assert [tuple(s) for s in seg.tolist()] == sorted(map(tuple, seg.tolist()))
        for (i, j), x in zip(seg, pts):  # each point lies on both of its segments
            for s in (i, j):
                a, b = p[s], p[(s + 1) % len(p)]
                d, e = b - a, x - a
                assert abs(d[0] * e[1] - d[1] * e[0]) < 1e-9 * (1 + np.hypot(*d))


def test_a_long_loop_is_handled_whole():
    # A 10 000-point wavy ring (radius 10 ± 0.5) does not cross itself, nor does a spike
    # from it into the empty middle and back.
    t = np.linspace(0.0, 2 * np.pi, 10_000, endpoint=False)
    r = 10 + 0.5 * np.sin(8 * t)
    loop = np.column_stack([r * np.cos(t), r * np.sin(t)])
    assert len(_core.self_intersections(loop)[0]) == 0
    assert len(_core.self_intersections(np.vstack([loop, [[0.0, 0.0]]]))[0]) == 0
    # A detour from the top (point 2500, at (0, 10)) straight down past the bottom of the
    # ring and back up beside itself crosses the bottom twice, at x = 0 and near x = -0.2.
    detour = np.vstack([loop[:2501], [[0.0, -12.0], [-0.2, -12.0]], loop[2501:]])
    seg, pts = _core.self_intersections(detour)
    assert len(seg) == 2 and np.all(pts[:, 1] < -9.4) and np.all(pts[:, 1] > -10.6)
    assert sorted(np.round(pts[:, 0], 1)) == [-0.2, 0.0]


@pytest.mark.parametrize(
    "call, needle",
    [
        (lambda: _core.polyline_length(np.zeros((1, 2))), "at least 2 points, got 1"),
        (lambda: _core.min_radius(np.zeros((2, 2)) + [[0, 0], [1, 0]], 0.5), "at least 3 points, got 2"),
        (lambda: _core.signed_area(np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]])), "at least 3 points, got 2"),
        (lambda: _core.curvature(np.array([[0.0, 0.0], [np.nan, 1.0], [1.0, 0.0]]), 0.5), "point 1 must be finite"),
        (lambda: _core.self_intersections(np.array([[0.0, 0.0], [np.inf, 1.0], [1.0, 0.0]])), "must be finite"),
        (lambda: _core.resample_closed(_circle(10, 1.0), 0.0), "spacing must be a finite length > 0"),
        (lambda: _core.resample_closed(_circle(10, 1.0), np.nan), "spacing"),
        (lambda: _core.resample_closed(_circle(10, 1.0), 1e-9), "samples"),
        (lambda: _core.curvature(_circle(10, 1.0), -1.0), "span_m must be a finite length > 0"),
        (lambda: _core.min_radius(_circle(10, 1.0), np.inf), "span_m"),
        (lambda: _core.resample_closed_values(_circle(10, 1.0), np.ones(7), 0.1), "one entry per point of xy (10)"),
        (lambda: _core.resample_closed_values(_circle(10, 1.0), np.r_[np.ones(9), np.nan], 0.1), "values[9]"),
        (lambda: _core.polyline_length(np.zeros((5, 3))), "shape (N, 2)"),
        (lambda: _core.self_intersections(_zigzag(16_000)), "folded onto itself"),
    ],
)
def test_bad_input_is_refused_with_a_one_line_message(call, needle):
    with pytest.raises(InvalidArgumentError) as e:
        call()
    assert needle in str(e.value) and "\n" not in str(e.value)
