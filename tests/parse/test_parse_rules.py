"""The rules backend, one test group per phrase family of the issue."""

from __future__ import annotations

import pytest

from roboracer_arena.errors import RequestParseError
from roboracer_arena.parse import parse_request
from roboracer_arena.parse.numbers import read_number
from roboracer_arena.parse.result import DEFAULTS
from roboracer_arena.parse.units import to_metres


def stated(text: str) -> dict:
    r = parse_request(text)
    d = r.spec.model_dump()
    return {k: d[k] for k in r.stated}


# -- numbers --------------------------------------------------------------------------
@pytest.mark.parametrize(
    "words, value",
    [
        ("three", 3), ("twenty five", 25), ("ninety nine", 99), ("one hundred and twenty", 120),
        ("a hundred", 100), ("one point five", 1.5), ("two and a half", 2.5), ("a pair of", 2),
        ("a couple of", 2), ("zero", 0), ("half a", 0.5), ("three hundred", 300),
    ],
)  # fmt: skip
def test_number_words(words, value):
    got = read_number(words.split(), 0)
    assert got is not None and got[0] == value and got[1] == len(words.split())


def test_a_alone_is_not_a_number():
    assert read_number(["a", "38"], 0) is None


@pytest.mark.parametrize(
    "text, lap",
    [
        ("a twenty-five metre lap", 25), ("a twenty five metre lap", 25), ("a 1.5e lap", None),
        ("a sixty metre track", 60), ("a one hundred metre lap", 100), ("a 37.5 m lap", 37.5),
    ],
)  # fmt: skip
def test_numbers_in_requests(text, lap):
    if lap is None:  # "1.5e" is no number-with-unit: the 1.5 is refused, not dropped
        with pytest.raises(RequestParseError, match="'1.5'"):
            parse_request(text)
        assert "lap_length_m" not in parse_request(text, lenient=True).stated
    else:
        assert stated(text)["lap_length_m"] == lap


# -- units ----------------------------------------------------------------------------
@pytest.mark.parametrize(
    "text, metres",
    [
        ("a 45 m lap", 45), ("a 45 metre lap", 45), ("a 45 meters lap", 45), ("a 45m lap", 45),
        ("a lap of 4500 cm", 45), ("a lap of 45000 mm", 45), ("a 150 ft lap", 45.72),
        ("a 100 feet lap", 30.48), ("a 50 yd lap", 45.72), ("a 50 yards lap", 45.72),
    ],
)  # fmt: skip
def test_units_normalised_to_metres(text, metres):
    assert stated(text)["lap_length_m"] == pytest.approx(metres)


def test_to_metres_is_exact_for_centimetres():
    assert to_metres(150, "cm") == 1.5


# -- hall -----------------------------------------------------------------------------
@pytest.mark.parametrize(
    "text, x, y",
    [
        ("a small 15 by 12 hall", 15, 12), ("a 15x12 hall", 15, 12), ("a 15 × 12 m hall", 15, 12),
        ("in a 15 m x 12 m room", 15, 12), ("a hall of 20 by 15 metres", 20, 15),
        ("a 30 ft by 20 ft gym", 9.144, 6.096), ("a hall twenty by fifteen", 20, 15),
        ("a hall 15 m long and 12 m wide", 15, 12), ("a hall 12 m wide and 15 m long", 15, 12),
        ("a 20 m long by 15 m wide space", 20, 15), ("a 15 m wide by 20 m long space", 20, 15),
    ],
)  # fmt: skip
def test_hall_dimensions(text, x, y):
    s = stated(text)
    assert (s["hall_x_m"], s["hall_y_m"]) == (pytest.approx(x), pytest.approx(y))


def test_hall_single_dimension():
    assert stated("the hall is 18 m long") == {"hall_x_m": 18}
    assert stated("a hall width of 14 m") == {"hall_y_m": 14}


# -- lap length -----------------------------------------------------------------------
@pytest.mark.parametrize(
    "text",
    [
        "a 38 m lap", "a 38 m long loop", "lap of 38 m", "a lap length of 38 metres",
        "the track should be 38 metres long", "38 metres long", "38 m per lap",
        "a track roughly 38 m around", "total length: 38 m", "a 38-metre circuit", "38 m total length",
        "38 metres overall", "a lap of 38 m in total",
    ],
)  # fmt: skip
def test_lap_length(text):
    assert stated(text) == {"lap_length_m": 38}


# -- corridor width -------------------------------------------------------------------
@pytest.mark.parametrize(
    "text",
    [
        "a 1.2 m wide corridor", "corridor width of 1.2 m", "corridors 1.2 m wide", "a 120 cm corridor",
        "track width: 1.2 m", "a track 1.2 m wide", "1.2 m in width", "a 1.2-metre-wide track",
    ],
)  # fmt: skip
def test_corridor_width(text):
    assert stated(text) == {"corridor_width_m": 1.2}


# -- direction ------------------------------------------------------------------------
@pytest.mark.parametrize(
    "text, sense",
    [
        ("clockwise", "clockwise"), ("driven CW", "clockwise"), ("anticlockwise", "counterclockwise"),
        ("anti-clockwise", "counterclockwise"), ("counter-clockwise", "counterclockwise"),
        ("counter clockwise", "counterclockwise"), ("counterclockwise", "counterclockwise"),
        ("run it CCW", "counterclockwise"), ("not clockwise", "counterclockwise"),
        ("clock-wise", "clockwise"), ("anti-clock-wise", "counterclockwise"),
    ],
)  # fmt: skip
def test_direction(text, sense):
    assert stated(text)["direction"] == sense


def test_contradictory_direction_is_an_error():
    with pytest.raises(RequestParseError, match="clockwise and counter-clockwise"):
        parse_request("a clockwise track, driven counter-clockwise")


# -- feature counts -------------------------------------------------------------------
@pytest.mark.parametrize(
    "text, counts",
    [
        ("two hairpins", {"hairpins": 2}), ("a hairpin", {"hairpins": 1}), ("one chicane", {"chicanes": 1}),
        ("a pair of sweepers", {"sweepers": 2}), ("a couple of chicanes", {"chicanes": 2}),
        ("3 tight hairpins", {"hairpins": 3}), ("a single sweeping bend", {"sweepers": 1}),
        ("no chicanes", {"chicanes": 0}), ("zero sweepers", {"sweepers": 0}),
        ("without chicanes or sweepers", {"chicanes": 0, "sweepers": 0}),
        ("four hairpin turns and two S-bends", {"hairpins": 4, "chicanes": 2}),
        ("a U-turn", {"hairpins": 1}), ("hairpins: 2", {"hairpins": 2}),
        ("a hairpin and another hairpin", {"hairpins": 2}),
    ],
)  # fmt: skip
def test_feature_counts(text, counts):
    assert stated(text) == counts


def test_zero_and_positive_count_contradict():
    with pytest.raises(RequestParseError, match="contradictory"):
        parse_request("no hairpins, but two hairpins")


def test_bare_plural_is_reported_not_guessed():
    r = parse_request("a track with hairpins")
    assert r.stated == () and [u.text for u in r.unparsed] == ["hairpins"]


# -- feature order --------------------------------------------------------------------
@pytest.mark.parametrize(
    "text, order",
    [
        ("two sweepers then a hairpin", ["sweeper", "sweeper", "hairpin"]),
        ("first a chicane, followed by a hairpin", ["chicane", "hairpin"]),
        ("a hairpin, a chicane, and then a sweeper", ["hairpin", "chicane", "sweeper"]),
        ("a chicane after two hairpins", ["hairpin", "hairpin", "chicane"]),
        ("a chicane before two hairpins", ["chicane", "hairpin", "hairpin"]),
        ("a hairpin, then a chicane, then another hairpin", ["hairpin", "chicane", "hairpin"]),
        ("hairpin, chicane and sweeper in that order", ["hairpin", "chicane", "sweeper"]),
        ("two hairpins and a chicane, the chicane first", ["chicane", "hairpin", "hairpin"]),
        ("two hairpins and a chicane. The chicane comes first, then the hairpins", ["chicane", "hairpin", "hairpin"]),
        ("starting with a sweeper, then two chicanes", ["sweeper", "chicane", "chicane"]),
        ("2 hairpins, each followed by a chicane", ["hairpin", "chicane", "hairpin", "chicane"]),
    ],
)
def test_feature_order(text, order):
    assert stated(text)["feature_order"] == order


def test_unordered_features_leave_order_empty():
    r = parse_request("two hairpins and a chicane")
    assert "feature_order" not in r.stated and r.spec.feature_order == []


def test_order_that_omits_a_counted_feature_is_an_error():
    with pytest.raises(RequestParseError, match="feature order"):
        parse_request("two sweepers. a hairpin then a chicane")


# -- minimum radius, longest straight, name -------------------------------------------
@pytest.mark.parametrize(
    "text",
    [
        "a minimum radius of 2 m", "min radius 2m", "a 2 m minimum radius", "a radius of at least 2 metres",
        "a minimum turning radius of 2 m", "no turn tighter than 2 m", "corners no tighter than 2 m radius",
        "radii of no less than 2 m", "corners mustn't be tighter than a 2 m radius", "turns can't be tighter than 2 m",
    ],
)  # fmt: skip
def test_min_radius(text):
    assert stated(text) == {"min_radius_m": 2}


@pytest.mark.parametrize(
    "text",
    ["a longest straight of 8 m", "an 8 m straight", "a straight of at least 8 m", "an 8 m long straight",
     "the back straight should be 8 m long", "an 8 m straightaway"],
)  # fmt: skip
def test_longest_straight(text):
    assert stated(text) == {"longest_straight_m": 8}


@pytest.mark.parametrize(
    "text, name",
    [
        ('a track called "Gym Sprint"', "Gym Sprint"), ("a track named Foxtrot, 40 m lap", "Foxtrot"),
        ("call it Red Arrow with two hairpins", "Red Arrow"), ("named Loop-9.", "Loop-9"),
        ("a circuit called 'The Oval'", "The Oval"), ("name the track 'Blue Line'; 40 m lap", "Blue Line"),
    ],
)  # fmt: skip
def test_name(text, name):
    assert stated(text)["name"] == name


# -- the whole request ----------------------------------------------------------------
def test_paper_example_and_spans():
    text = "a 38 m lap for a small 15 by 12 hall"
    r = parse_request(text)
    assert r.stated == ("lap_length_m", "hall_x_m", "hall_y_m")
    assert r.source_text("lap_length_m") == "38 m lap"
    assert r.source_text("hall_x_m") == "15" and r.source_text("hall_y_m") == "12"
    assert r.unparsed == ()
    assert r.highlight("lap_length_m") == "a [38 m lap] for a small 15 by 12 hall"


def test_unstated_fields_keep_defaults():
    r = parse_request("two chicanes")
    d = r.spec.model_dump()
    assert all(d[k] == DEFAULTS[k] for k in d if k != "chicanes")


def test_unexplained_words_are_reported_with_spans():
    text = "a tight, technical 40 m lap with banked corners"
    r = parse_request(text)
    assert r.stated == ("lap_length_m",)
    assert [u.text for u in r.unparsed] == ["tight", "technical", "banked"]
    for u in r.unparsed:
        assert text[u.start : u.end] == u.text


def test_stray_number_is_refused_or_reported_when_lenient():
    with pytest.raises(RequestParseError, match=r"'7' \(characters 16-17\)"):
        parse_request("a 40 m lap with 7 bumps")
    r = parse_request("a 40 m lap with 7 bumps", lenient=True)
    assert [u.text for u in r.unparsed] == ["7 bumps"]
    assert [i.text for i in r.ignored] == ["7"] and "ignored '7'" in r.warnings[0]
    assert [u.text for u in parse_request("a track with three turns", lenient=True).unparsed] == ["three turns"]


def test_each_multiplies_counts():
    assert stated("2 hairpins, each followed by a chicane")["chicanes"] == 2


def test_qualifier_words_of_a_stated_field_are_explained():
    r = parse_request("the tightest corner should have a radius of 2.5 m")
    assert r.unparsed == () and r.spec.min_radius_m == 2.5


def test_same_field_twice_with_different_values_is_an_error():
    with pytest.raises(RequestParseError, match="twice"):
        parse_request("a 38 m lap; lap length 40 m")


def test_same_value_twice_is_fine():
    assert stated("a 38 m lap, i.e. 38 metres long") == {"lap_length_m": 38}


def test_empty_request_is_an_error():
    with pytest.raises(RequestParseError):
        parse_request("   ")


def test_invalid_stated_value_is_a_parse_error():
    with pytest.raises(RequestParseError, match="lap_length_m"):
        parse_request("a 0 m lap")
