"""The grounding guard: non-default values must be traceable to the request."""

from __future__ import annotations

import json

import pytest

from benchmarks import bench_data
from roboracer_arena.errors import GroundingError
from roboracer_arena.parse import ground, parse_request
from roboracer_arena.spec import TrackSpec

PAPER = "a 38 m lap for a small 15 by 12 hall"
PAPER_SPEC = dict(lap_length_m=38, hall_x_m=15, hall_y_m=12)


def spec(**kw) -> TrackSpec:
    return TrackSpec(**kw)


def test_faithful_answer_passes_with_spans():
    g = ground(PAPER, spec(**PAPER_SPEC), rules_reading=False)
    assert g.invented == {}
    assert PAPER[slice(*g.spans["lap_length_m"][0])] == "38 m"
    assert PAPER[slice(*g.spans["hall_y_m"][0])] == "12"


@pytest.mark.parametrize("rules_reading", [True, False])
def test_paper_invented_minimum_radius_is_rejected(rules_reading):
    with pytest.raises(GroundingError, match=r"min_radius_m=9\.0"):
        ground(PAPER, spec(**PAPER_SPEC, min_radius_m=9), rules_reading=rules_reading)


def test_non_strict_resets_to_default_with_warning():
    with pytest.warns(UserWarning, match="min_radius_m"):
        g = ground(PAPER, spec(**PAPER_SPEC, min_radius_m=9), strict=False)
    assert g.spec == spec(**PAPER_SPEC)
    assert g.invented == {"min_radius_m": 9.0} and len(g.warnings) == 1


def test_copied_number_in_an_unstated_field_is_rejected():
    # 15 is in the request, but nothing there speaks of a radius
    with pytest.raises(GroundingError, match="min_radius_m"):
        ground(PAPER, spec(**PAPER_SPEC, min_radius_m=15), rules_reading=False)


@pytest.mark.parametrize(
    "text, value, ok",
    [
        ("a 150 ft lap", 45.72, True), ("a 150 ft lap", 45.7, True), ("a 38 m lap", 11.5824, False),
        ("a lap of 3800 cm", 38, True), ("a thirty-eight metre lap", 38, True), ("a 38 m lap", 40, False),
    ],
)  # fmt: skip
def test_lengths_traced_in_their_unit(text, value, ok):
    s = spec(lap_length_m=value)
    if ok:
        assert ground(text, s, rules_reading=False).invented == {}
    else:
        with pytest.raises(GroundingError):
            ground(text, s, rules_reading=False)


@pytest.mark.parametrize(
    "text, fields, ok",
    [
        ("two hairpins", dict(hairpins=2), True),
        ("two hairpins", dict(hairpins=3), False),
        ("two hairpins", dict(hairpins=2, chicanes=1), False),
        ("a hairpin, then a chicane, then another hairpin", dict(hairpins=2, chicanes=1), True),
        ("a clockwise track", dict(direction="clockwise"), True),
        ("a track, not counter-clockwise", dict(direction="clockwise"), True),
        ("a 40 m track", dict(direction="clockwise"), False),
        ("a track called kestrel", dict(name="Kestrel"), True),
        ("a 40 m track", dict(name="Kestrel"), False),
        ("a hairpin then a chicane", dict(hairpins=1, chicanes=1, feature_order=["hairpin", "chicane"]), True),
        ("a hairpin and a chicane", dict(hairpins=1, chicanes=1, feature_order=["hairpin", "chicane"]), False),
        ("an 8 m straight", dict(longest_straight_m=8), True),
        ("an 8 m lap", dict(lap_length_m=8, longest_straight_m=8), False),
    ],
)
def test_words_and_counts(text, fields, ok):
    s = spec(**fields)
    if ok:
        assert ground(text, s, rules_reading=False).invented == {}
    else:
        with pytest.raises(GroundingError):
            ground(text, s, rules_reading=False)


def test_non_strict_drops_an_order_that_no_longer_matches():
    s = spec(hairpins=1, chicanes=1, feature_order=["hairpin", "chicane"])
    with pytest.warns(UserWarning):
        g = ground("a hairpin then a turn", s, strict=False, rules_reading=False)
    assert g.spec.chicanes == 0 and g.spec.feature_order == []
    assert g.spec.hairpins == 1


def test_defaults_need_no_trace():
    assert ground("anything at all", TrackSpec()).invented == {}


@pytest.mark.parametrize("name", ["requests.jsonl", "requests_heldout.jsonl"])
def test_rules_output_is_always_grounded(name):
    for line in bench_data(name).read_text().splitlines():
        text = json.loads(line)["text"]
        r = parse_request(text)
        assert ground(text, r.spec, rules_reading=False).invented == {}, text
