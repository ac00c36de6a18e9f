"""Direction of travel: orienting centrelines, and where each kind of track takes it from."""

from __future__ import annotations

import numpy as np
import pytest
from source_sense import source_sign

from roboracer_arena.errors import InvalidArgumentError, MapFormatError
from roboracer_arena.maps.direction import (
    CLOCKWISE,
    COUNTERCLOCKWISE,
    TrackDirection,
    check_direction,
    direction_for_map,
    direction_of,
    orient,
    orient_to,
    read_centreline_file,
    reverse,
    signed_area,
)

SQUARE_CCW = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])


def test_signed_area_and_direction():
    assert signed_area(SQUARE_CCW) == pytest.approx(1.0)
    assert signed_area(SQUARE_CCW[::-1]) == pytest.approx(-1.0)
    assert direction_of(SQUARE_CCW) == COUNTERCLOCKWISE and direction_of(SQUARE_CCW[::-1]) == CLOCKWISE
    closed = np.vstack([SQUARE_CCW, SQUARE_CCW[:1]])
    assert signed_area(closed) == pytest.approx(1.0)


def test_orient_reverses_only_when_needed_and_rolls_to_start():
    out = orient(SQUARE_CCW, CLOCKWISE)
    assert direction_of(out) == CLOCKWISE and sorted(map(tuple, out)) == sorted(map(tuple, SQUARE_CCW))
    assert np.array_equal(orient(SQUARE_CCW, COUNTERCLOCKWISE), SQUARE_CCW)
    started = orient(SQUARE_CCW, COUNTERCLOCKWISE, start=(0.9, 1.1))
    assert np.array_equal(started[0], [1.0, 1.0]) and direction_of(started) == COUNTERCLOCKWISE
    closed = np.vstack([SQUARE_CCW, SQUARE_CCW[:1]])
    oc = orient(closed, CLOCKWISE, start=(0.0, 1.0))
    assert len(oc) == 5 and np.array_equal(oc[0], oc[-1]) and np.array_equal(oc[0], [0.0, 1.0])


def test_reverse_keeps_the_first_vertex():
    r = reverse(SQUARE_CCW)
    assert np.array_equal(r[0], SQUARE_CCW[0]) and direction_of(r) == CLOCKWISE
    assert np.array_equal(reverse(r), SQUARE_CCW)


def test_orient_to_ignores_a_start_off_the_track():
    how = TrackDirection(CLOCKWISE, (50.0, 50.0), "x")
    out = orient_to(SQUARE_CCW, how)
    assert direction_of(out) == CLOCKWISE and np.array_equal(out[0], SQUARE_CCW[0])
    assert direction_of(orient_to(SQUARE_CCW, how, reverse_it=True)) == COUNTERCLOCKWISE


@pytest.mark.parametrize(
    "raw,want",
    [
        ("cw", CLOCKWISE),
        ("Counter-Clockwise", COUNTERCLOCKWISE),
        ("anticlockwise", COUNTERCLOCKWISE),
        ("clockwise", CLOCKWISE),
    ],
)
def test_check_direction_spellings(raw, want):
    assert check_direction(raw) == want


def test_check_direction_rejects_names_the_field():
    with pytest.raises(InvalidArgumentError, match="spec.direction: expected"):
        check_direction("sideways", "spec.direction")


def test_read_centreline_formats(tmp_path):
    ours = tmp_path / "centreline.csv"
    ours.write_text("# x_m, y_m, w_tr_right_m, w_tr_left_m\n0,0,1,1\n1,0,1,1\n1,1,1,1\n")
    race = tmp_path / "T_raceline.csv"
    race.write_text("# id\n# hash\n# s_m; x_m; y_m; psi\n0; 5; 6; 0\n1; 7; 8; 0\n2; 9; 1; 0\n")
    assert read_centreline_file(ours).tolist() == [[0, 0], [1, 0], [1, 1]]
    assert read_centreline_file(race).tolist() == [[5, 6], [7, 8], [9, 1]]
    bad = tmp_path / "bad.csv"
    bad.write_text("0,0\nx,y\n")
    with pytest.raises(MapFormatError, match="bad.csv:2"):
        read_centreline_file(bad)


def test_recorded_map_takes_the_direction_of_its_source_centreline(sources):
    spa = sources / "f1tenth-racetracks/Spa/Spa_map.yaml"
    how = direction_for_map(spa)
    assert how.source == "Spa_centerline.csv"
    assert (1 if how.direction == COUNTERCLOCKWISE else -1) == source_sign(
        sources / "f1tenth-racetracks/Spa/Spa_centerline.csv"
    )
    assert how.direction == CLOCKWISE  # Spa-Francorchamps is driven clockwise
    assert how.start == (0.0, 0.0)


def test_map_without_source_centreline_gets_the_documented_default(sources):
    how = direction_for_map(sources / "f1tenth-gym/maps/berlin.yaml")
    assert how == TrackDirection(COUNTERCLOCKWISE, None, "default")
