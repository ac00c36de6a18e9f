"""Issue 38, class B for the parser: "max/maximum/at most ... straight" is the cap
``max_straight_m``, never the floor ``longest_straight_m`` (a required minimum, the
opposite of what the user asked); "min/minimum ... straight" is the floor."""

from __future__ import annotations

import pytest

from roboracer_arena.parse import parse_request

CAPS = [
    "max straight 3 m",
    "maximum straight 3 m",
    "Maximum straight: 3 m",
    "a 40 m lap, maximum straight of 3 m",
    "maximum straight length 3 m",
    "the max straight is 3 m",
    "a max. straight of 3 m",
    "3 m max straight",
    "at most 3 m straight",
    "at most 3 m straights",
    "straights of at most 3 m",
    "longest straight at most 3 m",
    "maximum straight length of at most 3 m",
    "no straight longer than 3 m",
]


@pytest.mark.parametrize("text", CAPS)
def test_a_capped_straight_is_max_straight_m(text):
    r = parse_request(text)
    assert r.spec.max_straight_m == 3.0 and r.spec.longest_straight_m == 0.0, (text, r.stated)
    assert "longest_straight_m" not in r.stated and not r.unparsed


@pytest.mark.parametrize("text", ["min straight 3 m", "minimum straight length of 3 m", "a 3 m straight"])
def test_a_floored_straight_stays_longest_straight_m(text):
    r = parse_request(text)
    assert r.spec.longest_straight_m == 3.0 and r.spec.max_straight_m is None, (text, r.stated)


def test_a_cap_with_a_floor_hedge_is_refused():
    from roboracer_arena.errors import RequestParseError

    with pytest.raises(RequestParseError, match="max_straight_m is a maximum"):
        parse_request("maximum straight of at least 3 m")
