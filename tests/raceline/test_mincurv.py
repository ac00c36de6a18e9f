"""The minimum-curvature QP: inside the corridor less the margin, closed, and less curved
than the centreline."""

from __future__ import annotations

import numpy as np

from roboracer_arena.raceline import speed_profile
from roboracer_arena.raceline.bounds import lateral_bounds
from roboracer_arena.raceline.geometry import closed_path
from roboracer_arena.raceline.mincurv import solve_offsets


def test_offsets_stay_within_their_bounds(oval):
    ref = closed_path(oval.loop, 0.2)
    left, right = lateral_bounds(ref.xy, ref.normals, oval.clearance, 0.3)
    alpha = solve_offsets(ref, left, right)
    assert (alpha <= left + 1e-9).all() and (alpha >= -right - 1e-9).all()
    assert np.abs(alpha).max() > 0.1  # it used the corridor


def test_bounds_keep_the_half_width_all_the_way(oval):
    ref = closed_path(oval.loop, 0.2)
    left, right = lateral_bounds(ref.xy, ref.normals, oval.clearance, 0.3)
    for frac in (0.25, 0.5, 1.0):
        pts = np.vstack([ref.xy + frac * left[:, None] * ref.normals, ref.xy - frac * right[:, None] * ref.normals])
        assert oval.clearance(pts).min() >= 0.3 - 1e-6
    # the stadium is 1.6 m wide: 0.8 - 0.3 = 0.5 m either side, found to within the tolerance
    assert np.allclose(np.median(left), 0.5, atol=0.01) and np.allclose(np.median(right), 0.5, atol=0.01)


def test_raceline_is_closed_within_the_margin_and_straighter(stadium_line, oval):
    line = stadium_line
    assert line.min_clearance >= line.half_width - 0.005
    assert oval.clearance(line.xy).min() >= line.half_width - 0.005
    step = np.hypot(*np.diff(np.vstack([line.xy, line.xy[:1]]), axis=0).T)
    assert step.max() < 0.25 and step.min() > 0.15  # closed: the last point leads back to the first
    assert np.isclose(line.s[-1] + step[-1], line.length, atol=1e-6)
    # Less curvature in all (the stadium's line turns along its straights too) and a faster lap.
    ref = closed_path(oval.loop, 0.2)
    assert np.sum(line.kappa**2 * line.ds) < 0.9 * np.sum(ref.kappa**2 * ref.ds)
    assert line.lap_time < 0.97 * speed_profile(ref.kappa, ref.ds, line.limits).lap_time


def test_min_time_mode_keeps_the_margin_and_is_never_slower(oval, stadium_line):
    from roboracer_arena.raceline import plan_raceline

    fast = plan_raceline(oval, stadium_line.limits, mode="mintime")
    assert fast.lap_time <= stadium_line.lap_time + 1e-9
    assert oval.clearance(fast.xy).min() >= fast.half_width - 0.005
