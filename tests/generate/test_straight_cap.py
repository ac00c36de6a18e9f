"""The speed cap ``max_straight_m`` (issue 28): optional (specs without it load and
behave as before), parsed from "no straight longer than 8 m" / "straights of at most
8 m", screened against the straight floor, steered towards by the constructors and
checked by the raster validator with no tolerance."""

import json

import pytest

from roboracer_arena import TrackSpec
from roboracer_arena.cli import main
from roboracer_arena.errors import RequestParseError
from roboracer_arena.generate import Acceptance, Rejection, generate_track, validate_map
from roboracer_arena.parse import parse_request

# Uncapped, seed 0 builds this lap with an 8.2 m straight; capped, its straights stay under 6 m.
REQUEST = "a 40 m lap with a hairpin and a chicane in a 20 by 15 m hall, no straight longer than 6 m"
CAP = 6.0


def test_specs_without_a_cap_load_unchanged():
    old = {"lap_length_m": 45, "hairpins": 2}
    s = TrackSpec.from_dict(old)
    assert s.max_straight_m is None
    assert TrackSpec.model_validate_json(s.model_dump_json()) == s
    with pytest.raises(Exception, match="max_straight_m"):
        TrackSpec.from_dict({**old, "max_straight_m": 0})


@pytest.mark.parametrize(
    "text",
    [
        "a 60 m lap in a 20 by 15 m hall with no straight longer than 8 m",
        "a 60 m lap in a 20 by 15 m hall, straights of at most 8 m",
        "a 60 m lap in a 20 by 15 m hall; the longest straight should be no more than 8 m",
        "60 m lap, 20 x 15 m hall, no straight is longer than 8 metres",
    ],
)
def test_parser_reads_the_cap(text):
    r = parse_request(text, backend="rules")
    assert r.spec.max_straight_m == 8 and r.spec.longest_straight_m == 0, r.spec
    assert "max_straight_m" in r.stated


def test_a_floor_stays_a_floor_and_a_floor_on_the_cap_is_refused():
    assert parse_request("a 60 m lap with a straight of at least 8 m", backend="rules").spec.longest_straight_m == 8
    with pytest.raises(RequestParseError, match="max_straight_m is a maximum"):
        parse_request("a 60 m lap with no straight longer than 8 m or more", backend="rules")


def test_a_cap_builds_a_track_that_respects_it_checked_by_the_validator():
    spec = parse_request(REQUEST, backend="rules").spec
    assert spec.max_straight_m == CAP
    uncapped = generate_track(spec.model_copy(update={"max_straight_m": None}), seed=0)
    assert isinstance(uncapped, Acceptance) and uncapped.report.measurements is not None
    assert uncapped.report.measurements.longest_straight_m > CAP  # the cap has work to do
    out = generate_track(spec, seed=0)
    assert isinstance(out, Acceptance), out.summary()
    check = next(c for c in out.report.checks if c.name == "max_straight")
    assert check.passed
    assert out.report.measurements is not None and out.report.measurements.longest_straight_m <= CAP
    # The validator judges the map on its own: re-measured from the raster, the cap holds,
    # and a tighter cap fails the same map.
    report, _ = validate_map(out.map, spec)
    assert report.valid
    tighter, _ = validate_map(out.map, spec.model_copy(update={"max_straight_m": 0.5}))
    assert not tighter.valid and [c.name for c in tighter.failed()] == ["max_straight"]


def test_cli_end_to_end_with_a_cap(tmp_path, capsys):
    assert main(["generate", REQUEST, "-o", str(tmp_path / "t"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    check = next(c for c in summary["checks"] if c["name"] == "max_straight")
    assert check["passed"] and float(check["measured"].split()[0]) <= CAP
    assert json.loads((tmp_path / "t" / "spec.json").read_text())["max_straight_m"] == CAP


def test_a_cap_below_the_floor_is_a_proven_rejection():
    spec = TrackSpec(lap_length_m=60, longest_straight_m=8, max_straight_m=7)
    out = generate_track(spec)
    assert isinstance(out, Rejection) and "max_straight_m = 7.00 m" in out.violations[0]
    # At the bound (0.95 × floor = cap) the screen stays a necessary condition only.
    assert not isinstance(
        generate_track(spec.model_copy(update={"max_straight_m": 7.6}), suggest_timeout=None), Rejection
    )
