"""Spline resampling and the width reduction on a synthetic near-touching loop (crossings and
lengths from the core toolbox, see tests/test_polyline.py)."""

from __future__ import annotations

import numpy as np
import pytest

from roboracer_arena import _core
from roboracer_arena.circuits.geometry import reduce_widths, smooth_resample
from roboracer_arena.errors import CorridorError

SPACING, WALL, RES = 0.1, 0.15, 0.05


def _pinched_stadium(gap_mid: float) -> np.ndarray:
    """Two 20 m straights joined by r = 1 m ends, pinched to ``gap_mid`` apart mid-way."""
    x = np.linspace(-10, 10, 201)
    half = 1.0 - (1.0 - gap_mid / 2) * np.exp(-((x / 3) ** 2))
    a = np.linspace(-np.pi / 2, np.pi / 2, 31)[1:-1]
    right = np.column_stack([10 + np.cos(a), np.sin(a)])
    left = np.column_stack([-10 - np.cos(a), -np.sin(a)])
    return np.vstack([np.column_stack([x, -half]), right, np.column_stack([x[::-1], half[::-1]]), left])


def _resampled(gap_mid: float, width: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    raw = _pinched_stadium(gap_mid)
    return smooth_resample(raw, np.full(len(raw), width), SPACING, 0.001)


def test_resampling_is_uniform_and_keeps_length():
    ring = (
        np.column_stack(
            [
                np.cos(np.linspace(0, 2 * np.pi, 50, endpoint=False)),
                np.sin(np.linspace(0, 2 * np.pi, 50, endpoint=False)),
            ]
        )
        * 5
    )
    xy, w = smooth_resample(ring, np.full(50, 1.0), 0.1, 0.0)
    steps = np.hypot(*np.diff(np.vstack([xy, xy[:1]]), axis=0).T)
    assert steps.std() < 1e-3 and steps.mean() == pytest.approx(0.1, rel=0.01)
    assert _core.polyline_length(xy) == pytest.approx(2 * np.pi * 5, rel=1e-4)
    assert np.allclose(w, 1.0)


def test_near_touching_sections_are_narrowed_and_stay_apart():
    xy, w = _resampled(gap_mid=0.9)
    # Without narrowing the two straights merge mid-way: the wall strip between them is
    # cut in two, so the raster has two "infields" instead of one.
    assert _infields(xy, w) == 2
    nar = reduce_widths(xy, w, WALL, SPACING)
    assert 0 < nar.narrowed_fraction < 0.5 and nar.unresolved_fraction == 0
    assert nar.min_separation_m == pytest.approx(0.9, abs=0.01)
    assert nar.factor.min() == pytest.approx((0.9 - WALL) / 1.0, abs=0.01)
    assert (nar.widths >= 0.6 * w - 1e-12).all()
    assert _infields(xy, nar.widths) == 1


def _infields(xy: np.ndarray, widths: np.ndarray) -> int:
    data, origin = _core.rasterise_centreline(xy, widths, RES, WALL, 0.3)
    try:
        mm = _core.measure_map(data, RES, origin)
    except CorridorError:
        return 0
    assert mm.corridor_components == 1
    return mm.infields


def test_narrowing_never_goes_below_sixty_percent():
    xy, w = _resampled(gap_mid=0.5)
    nar = reduce_widths(xy, w, WALL, SPACING)
    assert nar.factor.min() == pytest.approx(0.6)
    assert nar.unresolved_fraction > 0


def test_wide_loop_is_not_narrowed():
    xy, w = _resampled(gap_mid=2.0)
    nar = reduce_widths(xy, w, WALL, SPACING)
    assert nar.narrowed_fraction == 0 and np.allclose(nar.widths, w)


def test_figure_eight_has_one_crossing_and_keeps_its_width_there():
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    eight = np.column_stack([10 * np.sin(t), 5 * np.sin(2 * t)])
    xy, w = smooth_resample(eight, np.full(len(t), 1.0), SPACING, 0.0)
    segments, points = _core.self_intersections(xy)
    assert segments.shape == (1, 2) and np.allclose(points[0], 0.0, atol=0.05)
    assert len(_core.self_intersections(_pinched_stadium(2.0))[0]) == 0
    nar = reduce_widths(xy, w, WALL, SPACING, segments)
    assert nar.narrowed_fraction == 0
    # Without the crossing the two sections through the middle would be narrowed.
    assert reduce_widths(xy, w, WALL, SPACING).narrowed_fraction > 0


def test_measure_map_reads_any_memory_layout():
    # A rectangular ring; the binding copies C-contiguous input in one go and must read
    # Fortran-ordered and strided arrays in logical (row, column) order all the same.
    a = np.full((40, 60), 205, np.uint8)
    a[5:35, 5:55] = 0
    a[8:32, 8:52] = 254
    a[14:26, 14:46] = 0
    ref = _core.measure_map(a, 0.05, (0.0, 0.0, 0.0))
    wide = np.full((40, 120), 7, np.uint8)
    wide[:, ::2] = a
    for view in (np.asfortranarray(a), wide[:, ::2]):
        got = _core.measure_map(view, 0.05, (0.0, 0.0, 0.0))
        for k in ("corridor_components", "infields", "mean_width_m", "extent_m", "centreline_length_m"):
            assert getattr(got, k) == getattr(ref, k), k
        assert np.array_equal(got.centreline, ref.centreline) and np.array_equal(got.widths, ref.widths)
    assert ref.infields == 1 and ref.centreline.shape == (len(ref.widths), 2)
    assert ref.extent_m == pytest.approx((2.5, 1.5)) and ref.mean_width_m > 0
