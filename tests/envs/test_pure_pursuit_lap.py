"""The reference driver completes a lap of a shared recorded map without a contact."""

import pytest

from roboracer_arena.drivers import drive_laps


def test_pure_pursuit_laps_the_stadium(oval):
    res = drive_laps(oval, laps=2, sim={"lidar": {"num_beams": 109}})
    assert res.completed, res
    assert res.lap_times[1] < res.lap_times[0]  # flying lap beats the standing start
    assert res.max_speed > 3.0


@pytest.mark.slow
def test_pure_pursuit_completes_a_lap_of_berlin(berlin):
    res = drive_laps(berlin, laps=1)
    assert res.completed, res.to_dict()
    assert res.laps_completed == 1 and not res.collided
    assert 10.0 < res.lap_times[0] < 120.0
