"""Long titles wrap between items, never inside a value."""

from __future__ import annotations

import pytest

from roboracer_arena.render.frame import wrap_items

TITLE = "gym-berlin: counterclockwise, lap 70.9 m, map 30.0 x 30.0 m at 0.05 m/cell"


def fits(n: int):
    return lambda line: len(line) <= n


@pytest.mark.parametrize("width", [20, 30, 45, 60, 200])
def test_titles_break_between_items_and_lose_nothing(width):
    lines = wrap_items(TITLE, fits(width))
    assert " ".join(lines) == TITLE
    for value in ("lap 70.9 m", "30.0 x 30.0 m", "0.05 m/cell"):
        assert any(value in line for line in lines), (value, lines)


def test_items_come_whole_when_they_fit():
    assert wrap_items(TITLE, fits(45)) == [
        "gym-berlin: counterclockwise, lap 70.9 m,",
        "map 30.0 x 30.0 m at 0.05 m/cell",
    ]
    assert wrap_items(TITLE, fits(200)) == [TITLE]


def test_an_item_too_long_for_a_line_breaks_between_its_values_only():
    sub = "Start: the env's grid start at x 7.01 m, y -22.67 m, heading 88°."
    lines = wrap_items(sub, fits(16))
    assert " ".join(lines) == sub
    assert "x 7.01 m," in lines and "y -22.67 m," in lines and "heading 88°." in lines
    assert wrap_items("map 30.0 x 30.0 m at 0.05 m/cell", fits(18)) == ["map 30.0 x 30.0 m", "at 0.05 m/cell"]
