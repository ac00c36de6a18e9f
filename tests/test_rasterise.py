"""Rasteriser (Eq. 3) through the Python binding: values, geometry, bad input."""

import numpy as np
import pytest

from roboracer_arena import _core
from roboracer_arena.errors import InvalidArgumentError


def _circle(r: float, n: int = 1500) -> np.ndarray:
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.c_[r * np.cos(t), r * np.sin(t)]


def test_circle_values_follow_eq3():
    r, w, res, tw = 3.0, 1.5, 0.05, 0.15
    data, (ox, oy, yaw) = _core.rasterise_centreline(_circle(r), np.full(1500, w), res, tw, 0.5)
    assert data.dtype == np.uint8 and yaw == 0.0
    assert set(np.unique(data)) == {0, 205, 254}
    h, wd = data.shape
    # Cell centres in the map frame (row 0 = top).
    xs = ox + (np.arange(wd) + 0.5) * res
    ys = oy + (h - 1 - np.arange(h) + 0.5) * res
    d = np.abs(np.hypot(xs[None, :], ys[:, None]) - r)
    clear = (np.abs(d - (w / 2 - res / 2)) > 1e-3) & (np.abs(d - (w / 2 + tw)) > 1e-3)
    expect = np.where(d <= w / 2 - res / 2, 254, np.where(d <= w / 2 + tw, 0, 205))
    assert np.array_equal(data[clear], expect[clear])


def test_free_width_across_a_straight_is_w():
    # A long thin loop: measure the free run across the bottom straight.
    xy = np.array([[0, 0], [20, 0], [20, 8], [0, 8]], float)
    res, w = 0.05, 1.5
    data, (ox, oy, _) = _core.rasterise_centreline(xy, np.full(4, w), res, 0.15, 0.3)
    col = int((10 - ox) / res)
    free_cells = int((data[:, col] == 254).sum())
    assert abs(free_cells * res - 2 * w) <= 2 * res  # two straights cross this column


def test_bad_input_raises_typed_error():
    with pytest.raises(InvalidArgumentError, match="widths"):
        _core.rasterise_centreline(_circle(2.0), np.ones(3), 0.05, 0.15, 0.0)
    with pytest.raises(InvalidArgumentError, match="shape"):
        _core.rasterise_centreline(np.zeros((5, 3)), np.ones(5), 0.05, 0.15, 0.0)
    with pytest.raises(InvalidArgumentError, match="resolution"):
        _core.rasterise_centreline(_circle(2.0), np.ones(1500), -1.0, 0.15, 0.0)
