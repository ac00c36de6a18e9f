"""The speed profile obeys v_max, the lateral limit and the acceleration envelope."""

from __future__ import annotations

import numpy as np

from roboracer_arena.raceline import VehicleLimits, preset, speed_profile
from roboracer_arena.raceline.speed import lateral_limit


def _check(kappa, ds, lim):
    prof = speed_profile(kappa, ds, lim)
    v = prof.vx
    assert (v <= lim.v_max + 1e-9).all()
    assert (np.abs(kappa) * v**2 <= lim.ay_tyre(v) + 1e-6).all()
    assert (prof.ax <= np.maximum(lim.ax_machine(v), 0) + 1e-6).all()
    assert (prof.ax >= -lim.ax_tyre(np.roll(v, -1)) - 1e-6).all()
    assert np.isclose(prof.lap_time, np.sum(2 * ds / (v + np.roll(v, -1))))
    return prof


def test_profile_respects_every_limit():
    s = np.linspace(0, 100, 500, endpoint=False)
    kappa = 0.5 * np.sin(2 * np.pi * s / 25.0) ** 8  # straights and sharp bends
    ds = np.full(500, 0.2)
    for name in ("f1tenth-racetracks", "forzaeth", "car"):
        _check(kappa, ds, preset(name))


def test_straight_loop_runs_at_v_max_and_corner_at_lateral_limit():
    lim = VehicleLimits(v_max=5.0, ggv=[(0.0, 4.0, 8.0)], ax_max_machines=[(0.0, 3.0)])
    assert _check(np.zeros(100), np.full(100, 0.5), lim).vx.min() == 5.0
    v = lateral_limit(np.array([2.0]), lim)
    assert np.isclose(v[0], 2.0)  # sqrt(8 / 2)


def test_acceleration_out_of_a_hairpin_follows_the_motor():
    lim = VehicleLimits(v_max=20.0, ggv=[(0.0, 9.0, 9.0)], ax_max_machines=[(0.0, 2.0)])
    kappa = np.zeros(400)
    kappa[0] = 9.0  # v = 1 m/s there
    prof = _check(kappa, np.full(400, 0.1), lim)
    # v^2 = 1 + 2 * 2 * s after the hairpin (the friction ellipse is unused on the straight)
    assert np.isclose(prof.vx[101] ** 2, prof.vx[1] ** 2 + 2 * 2.0 * 10.0, rtol=1e-6)
