"""General phrasing rules: numbers read whole, ranges refused, value before field, a lone
length as the lap, bare areas as the hall, hedges. Sentences here are not in the bench sets."""

from __future__ import annotations

import pytest
from test_parse_rules import stated

from roboracer_arena.errors import RequestParseError
from roboracer_arena.parse import parse_request


@pytest.mark.parametrize(
    "text, lap",
    [
        ("a 6e1 m lap", 60.0), ("a 4.2E1 metre loop", 42.0), ("a 5,500 cm circuit", 55.0),
        ("a 1,200 m lap", 1200.0), ("a 35.5m lap", 35.5), ("ninety-nine metres of track", 99.0),
        ("a lap of one thousand two hundred metres", 1200.0), ("a lap of forty five metres", 45.0),
    ],
)  # fmt: skip
def test_numbers_are_read_whole(text, lap):
    assert stated(text)["lap_length_m"] == lap


@pytest.mark.parametrize(
    "text, field, value",
    [
        ("half a dozen chicanes", "chicanes", 6), ("two dozen sweepers", "sweepers", 24),
        ("a dozen hairpins", "hairpins", 12), ("three and a half metre corridor", "corridor_width_m", 3.5),
    ],
)  # fmt: skip
def test_number_words(text, field, value):
    assert stated(text)[field] == value


@pytest.mark.parametrize(
    "text, message",
    [
        ("-5 m lap", r"lap_length_m = -5 m \('-5 m lap' at characters 0-8\).*1 to 2000 m"),
        ("a lap of −12 metres", r"lap_length_m = -12 m"),
        ("a lap of 1e308 m", r"lap_length_m = 1e\+308 m.*1 to 2000 m"),
        ("a 1e999 m lap", r"'1e999' at characters 2-7 is too large"),
        ("corridor 25 m wide", r"corridor_width_m = 25 m.*0.2 to 20 m"),
        ("a 45 m lap with 60 hairpins", r"hairpins = 60.*0 to 50"),
        ("a 45 m lap with -2 chicanes", r"chicanes = -2"),
        ("a 45 m lap with 2.5 hairpins", r"whole number: '2.5 hairpins'"),
        ("a 999999999999999999999 m lap", r"lap_length_m = 1e\+21 m"),
    ],
)
def test_out_of_range_and_signed_numbers_are_refused(text, message):
    with pytest.raises(RequestParseError, match=message):
        parse_request(text)


@pytest.mark.parametrize(
    "text, shown",
    [
        ("a lap between 40 and 50 m", "'between 40 and 50 m'"), ("a 40-50 m lap", "'40-50 m'"),
        ("a lap of 40 m - 50 m", "'40 m - 50 m'"), ("from 30 to 35 metres", "'from 30 to 35 metres'"),
        ("one or two chicanes", "'one or two'"), ("a corridor 1.2 to 1.5 m wide", "'1.2 to 1.5 m'"),
    ],
)  # fmt: skip
def test_ranges_are_refused_with_their_span(text, shown):
    with pytest.raises(RequestParseError, match="range") as e:
        parse_request(text)
    assert shown in str(e.value)


def test_dash_joins_words_and_units():
    assert stated("a 1.5-metre corridor and a forty-two-metre lap") == {"lap_length_m": 42.0, "corridor_width_m": 1.5}


@pytest.mark.parametrize(
    "text, want",
    [
        ("Four metres should be the longest straight", {"longest_straight_m": 4.0}),
        ("1.5 m as the minimum radius, 50 m lap", {"min_radius_m": 1.5, "lap_length_m": 50.0}),
        ("90 cm for the corridor", {"corridor_width_m": 0.9}),
        ("Thirty-three metres of circuit", {"lap_length_m": 33.0}),
        ("the circuit: 33 m", {"lap_length_m": 33.0}),
        ("radius no less than 1.2 m", {"min_radius_m": 1.2}),
    ],
)
def test_value_before_and_after_the_field(text, want):
    assert stated(text) == want


@pytest.mark.parametrize(
    "text, want",
    [
        ("a chicane and two sweepers, 38 metres", {"lap_length_m": 38.0, "chicanes": 1, "sweepers": 2}),
        ("clockwise, 4200 cm", {"lap_length_m": 42.0, "direction": "clockwise"}),
        ("17 by 13, 44 m", {"hall_x_m": 17.0, "hall_y_m": 13.0, "lap_length_m": 44.0}),
        ("21×14 m and a 50 m lap", {"hall_x_m": 21.0, "hall_y_m": 14.0, "lap_length_m": 50.0}),
        ("19 x 12 m", {"hall_x_m": 19.0, "hall_y_m": 12.0}),
    ],
)
def test_bare_lengths_and_areas(text, want):
    assert stated(text) == want


def test_a_bare_number_without_unit_is_not_a_lap():
    with pytest.raises(RequestParseError, match="'44'"):
        parse_request("two chicanes, 44")


@pytest.mark.parametrize(
    "text, field, hedge, value",
    [
        ("about 40 m lap", "lap_length_m", "approximately", 40.0),
        ("a lap of 40 m or so", "lap_length_m", "approximately", 40.0),
        ("radius at least 2 m", "min_radius_m", "at least", 2.0),
        ("straight of at least 5 m", "longest_straight_m", "at least", 5.0),
        ("a hall up to 20 by 15 m", "hall_x_m", "at most", 20.0),
    ],
)
def test_hedges_keep_the_value_silently_when_it_means_the_same(text, field, hedge, value):
    r = parse_request(text)
    assert getattr(r.spec, field) == value and r.hedges[field] == hedge and r.warnings == ()


@pytest.mark.parametrize(
    "text, field, value",
    [
        ("a lap no more than 50 m", "lap_length_m", 50.0),
        ("a corridor at least 1.4 m wide", "corridor_width_m", 1.4),
        ("a lap of 50 m, no more than 3 hairpins", "hairpins", 3),
    ],
)
def test_bounds_on_targets_are_read_as_the_bound_with_a_warning(text, field, value):
    r = parse_request(text)
    assert getattr(r.spec, field) == value
    assert any(w.startswith(f"{field}:") and "bound" in w for w in r.warnings)


def test_a_cap_on_a_floor_is_refused():
    with pytest.raises(RequestParseError, match="min_radius_m is a minimum; 'at most 2 m'"):
        parse_request("radius at most 2 m")
    # A cap on the straight is the speed cap max_straight_m (issue 28), not a refusal.
    r = parse_request("a straight of no more than 6 m")
    assert r.spec.max_straight_m == 6 and r.spec.longest_straight_m == 0 and r.hedges["max_straight_m"] == "at most"


@pytest.mark.parametrize(
    "text, want",
    [
        ("lap length (m): 52", {"lap_length_m": 52.0}),
        ("corridor width in cm: 130", {"corridor_width_m": 1.3}),
        ("hall [m]: 18 x 12, lap (m) 41", {"hall_x_m": 18.0, "hall_y_m": 12.0, "lap_length_m": 41.0}),
        ("width 1.1m lap 39m", {"corridor_width_m": 1.1, "lap_length_m": 39.0}),
        ("an 18x12m hall, a 41m loop", {"hall_x_m": 18.0, "hall_y_m": 12.0, "lap_length_m": 41.0}),
        ("lap41 m", {"lap_length_m": 41.0}),
        ("a 1:10 scale F1 track of 41 m", {"lap_length_m": 41.0}),
    ],
)
def test_units_before_numbers_glued_tokens_and_adjacent_nouns(text, want):
    assert stated(text) == want


def test_other_scales_are_refused():
    with pytest.raises(RequestParseError, match="'1:5 scale'.*1:10-scale tracks only"):
        parse_request("a 1:5 scale track of 41 m")


def test_a_count_of_laps_is_not_a_length():
    assert stated("one lap of 41 m") == {"lap_length_m": 41.0}
    with pytest.raises(RequestParseError, match="'3' \\(characters 17-18\\)"):
        parse_request("a 41 metre loop, 3 laps")  # the number of laps is no TrackSpec field


def test_ish_is_an_approximate_hedge():
    r = parse_request("a lap of 41-ish metres")
    assert r.spec.lap_length_m == 41.0 and r.hedges == {"lap_length_m": "approximately"}


@pytest.mark.parametrize(
    "text, hairpins",
    [
        ("two hairpins then a chicane then two more hairpins", 4),
        ("3 hairpins, then a chicane, then 2 hairpins", 5),  # an ordered run adds up
        ("two hairpins and 3 extra hairpins", 5),
        ("2 hairpins. Yes, 2 hairpins.", 2),  # an equal restatement is the same count
    ],
)
def test_repeated_counts_add_or_restate(text, hairpins):
    assert parse_request(text).spec.hairpins == hairpins


def test_a_different_restated_count_is_refused_not_corrected():
    with pytest.raises(RequestParseError, match="chicanes twice with different counts: 'four chicanes'"):
        parse_request("four chicanes in a 40 m lap? Hmm, two chicanes.")
