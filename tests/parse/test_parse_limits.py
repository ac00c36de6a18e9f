"""Bounded work: the input cap, and the rules parser linear in the request's length (a
100 kB request, quadratic before, completes; the bound is generous, not a timing claim)."""

from __future__ import annotations

import math
import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from roboracer_arena.errors import ArenaError, RequestParseError
from roboracer_arena.parse import MAX_REQUEST_CHARS, parse_request
from roboracer_arena.parse.limits import FIELD_RANGES
from roboracer_arena.parse.rules import parse_rules


def test_over_long_request_is_refused_before_any_work():
    text = "a 45 m lap " * (MAX_REQUEST_CHARS // 10)
    with pytest.raises(
        RequestParseError, match=f"{len(text)} characters long; the parser accepts at most {MAX_REQUEST_CHARS}"
    ):
        parse_request(text)
    with pytest.raises(RequestParseError, match="at most"):
        parse_request(text, backend="ollama", ollama_host="http://127.0.0.1:9")  # refused before any call


def test_cli_refuses_an_over_long_request_in_one_line(capsys):
    from roboracer_arena.cli import EXIT_BAD_INPUT, main

    assert main(["parse", "a 45 m lap " * 10_000]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "110000 characters long" in err


@pytest.mark.parametrize(
    "unit",
    ["a 45 m lap with two hairpins then a chicane, ", "tight ", "the hairpins and ", "45 m ", 'called "x ',
     "please make it nice and fast, ", "-1-2-3 ", "hairpin "],
)  # fmt: skip
def test_100_kB_request_completes(unit):
    text = (unit * (100_000 // len(unit) + 1))[:100_000]
    t0 = time.perf_counter()
    try:
        parse_rules(text, max_chars=None, lenient=True)
    except RequestParseError:
        pass  # refusing is fine; hanging is not
    assert time.perf_counter() - t0 < 5.0  # quadratic: 45 s before; linear: about 1 s


_REQUEST_WORDS = st.sampled_from(
    ["a", "lap", "hall", "by", "x", "m", "cm", "metres", "wide", "long", "hairpin", "chicanes", "sweeper",
     "then", "no", "at", "most", "least", "about", "between", "and", "to", "-", "−", "radius", "straight",
     "clockwise", "counter", "corridor", "twenty", "five", "dozen", "half", "one", ",", ".", "called", '"',
     "e", "1e308", "6e1", "-5", "4,000", "0", "0.5", "45", "1e999", "×", "or", "so", "not"]
)  # fmt: skip


def _check(text: str) -> None:
    for lenient in (False, True):
        try:
            r = parse_request(text, lenient=lenient)
        except ArenaError:
            continue
        spec = r.spec.model_dump()
        for name, (lo, hi) in FIELD_RANGES.items():
            if name in r.stated:
                assert math.isfinite(spec[name]) and lo <= spec[name] <= hi, (name, spec[name], text)
        assert lenient or not r.ignored


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(_REQUEST_WORDS, max_size=30).map(" ".join))
def test_request_like_text_gives_a_typed_error_or_finite_values_in_range(text):
    _check(text)


@settings(max_examples=300, deadline=None)
@given(st.text(max_size=200))
def test_arbitrary_text_gives_a_typed_error_or_finite_values_in_range(text):
    _check(text)


@pytest.mark.parametrize("text", ["1e308 hairpin 1e308 hairpin", "1e308 chicanes", "9" * 400 + " m lap"])
def test_huge_counts_and_numbers_are_typed_refusals(text):  # found by the property test
    with pytest.raises(RequestParseError):
        parse_request(text, lenient=True)
