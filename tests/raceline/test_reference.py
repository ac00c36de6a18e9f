"""Against a published raceline: with f1tenth_racetracks' limits, our line on Spielberg is
no slower than theirs (+1 %), and our speed profile on their own line gives their lap
time to within their profile's difference (ours ignores nothing: theirs brakes for
curvature their exported line does not have)."""

from __future__ import annotations

import numpy as np
import pytest

from roboracer_arena.raceline import plan_raceline, preset, read_tum_csv, speed_profile
from roboracer_arena.raceline.geometry import closed_path
from roboracer_arena.raceline.source import resolve_track


@pytest.mark.slow
def test_spielberg_lap_time_against_the_published_raceline(sources):
    pub = read_tum_csv(sources / "f1tenth-racetracks/Spielberg/Spielberg_raceline.csv")
    assert pub.lap_time == pytest.approx(45.05, abs=0.01)
    lim = preset("f1tenth-racetracks")
    theirs = closed_path(np.column_stack([pub.x[:-1], pub.y[:-1]]), 0.2)
    their_profile = speed_profile(theirs.kappa, theirs.ds, lim).lap_time
    assert their_profile <= pub.lap_time
    track, _ = resolve_track("racetracks-spielberg")
    ours = plan_raceline(track, lim)
    assert ours.lap_time <= 1.01 * pub.lap_time
    assert ours.lap_time <= 1.01 * their_profile  # same profile: the lines compare
