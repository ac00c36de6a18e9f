"""The Ollama backend through the real ``ollama`` client against a local fake server
that returns recorded model outputs; every failure path gives a typed BackendError."""

from __future__ import annotations

import json
import os

import pytest
from fake_ollama import Reply

from roboracer_arena.errors import (
    BackendError,
    BackendTimeoutError,
    BackendUnavailableError,
    GroundingError,
    MalformedOutputError,
    ModelNotFoundError,
)
from roboracer_arena.parse import parse_request
from roboracer_arena.parse.ollama_backend import SEED, ask_ollama, reachable
from roboracer_arena.spec import TrackSpec

PAPER = "a 38 m lap for a small 15 by 12 hall"
CORRECT = TrackSpec(lap_length_m=38, hall_x_m=15, hall_y_m=12).model_dump_json()
# Mistral 7B's answer in the paper: an unstated 9 m minimum radius added.
INVENTED = TrackSpec(lap_length_m=38, hall_x_m=15, hall_y_m=12, min_radius_m=9).model_dump_json()


def test_correct_answer_is_parsed_and_grounded(fake_ollama):
    fake_ollama.reply = Reply(content=CORRECT)
    r = parse_request(PAPER, backend="ollama", ollama_host=fake_ollama.url)
    assert r.backend == "ollama"
    assert (r.spec.lap_length_m, r.spec.hall_x_m, r.spec.hall_y_m) == (38, 15, 12)
    assert r.stated == ("lap_length_m", "hall_x_m", "hall_y_m")
    assert PAPER[slice(*r.span("lap_length_m"))].startswith("38")
    assert PAPER[slice(*r.span("hall_x_m"))] == "15"


def test_request_uses_schema_temperature_zero_and_fixed_seed(fake_ollama):
    fake_ollama.reply = Reply(content=CORRECT)
    parse_request(PAPER, backend="ollama", ollama_host=fake_ollama.url, model="gemma4:31b")
    (req,) = fake_ollama.requests
    assert req["path"] == "/api/chat"
    assert req["model"] == "gemma4:31b"
    assert req["stream"] is False
    assert req["format"] == json.loads(json.dumps(TrackSpec.json_schema()))
    assert req["options"]["temperature"] == 0
    assert req["options"]["seed"] == SEED
    assert req["messages"][-1] == {"role": "user", "content": PAPER}


def test_invented_minimum_radius_is_caught(fake_ollama):
    fake_ollama.reply = Reply(content=INVENTED)
    with pytest.raises(GroundingError, match="min_radius_m=9"):
        parse_request(PAPER, backend="ollama", ollama_host=fake_ollama.url)


def test_invented_value_reset_with_warning_when_not_strict(fake_ollama):
    fake_ollama.reply = Reply(content=INVENTED)
    with pytest.warns(UserWarning, match="min_radius_m"):
        r = parse_request(PAPER, backend="ollama", ollama_host=fake_ollama.url, strict=False)
    assert r.spec.min_radius_m == 0.0
    assert r.spec.lap_length_m == 38
    assert any("min_radius_m" in w for w in r.warnings)


@pytest.mark.parametrize(
    "reply",
    [
        Reply(content='{"lap_length_m": 38, "hall_x_m": 15'),  # truncated JSON
        Reply(content="Sure! Here is your track: 38 m."),  # prose
        Reply(content='{"lap_length_m": -38}'),  # JSON, but not a valid TrackSpec
        Reply(content='{"lap_length_m": 38, "banking_deg": 5}'),  # unknown field
        Reply(content='["not", "an", "object"]'),
        Reply(content=""),  # empty answer
        Reply(body="<html>proxy error</html>"),  # HTTP body that is not a chat response
    ],
    ids=["truncated", "prose", "invalid-value", "extra-field", "array", "empty", "not-json-body"],
)
def test_malformed_output(fake_ollama, reply):
    fake_ollama.reply = reply
    with pytest.raises(MalformedOutputError):
        parse_request(PAPER, backend="ollama", ollama_host=fake_ollama.url)


def test_model_not_found_404(fake_ollama):
    fake_ollama.reply = Reply(content=CORRECT)
    with pytest.raises(ModelNotFoundError, match="no-such-model"):
        parse_request(PAPER, backend="ollama", ollama_host=fake_ollama.url, model="no-such-model:1b")


def test_other_http_error_is_backend_error(fake_ollama):
    fake_ollama.reply = Reply(status=500, body=json.dumps({"error": "out of memory"}))
    with pytest.raises(BackendError, match="out of memory"):
        parse_request(PAPER, backend="ollama", ollama_host=fake_ollama.url)


def test_slow_answer_times_out(fake_ollama):
    fake_ollama.reply = Reply(content=CORRECT, delay_s=1.5)
    with pytest.raises(BackendTimeoutError, match="0.2 s"):
        parse_request(PAPER, backend="ollama", ollama_host=fake_ollama.url, timeout=0.2)


def test_server_down(dead_url):
    with pytest.raises(BackendUnavailableError, match="cannot reach"):
        parse_request(PAPER, backend="ollama", ollama_host=dead_url, timeout=2)
    assert not reachable(dead_url)


def test_host_from_environment(fake_ollama, monkeypatch):
    fake_ollama.reply = Reply(content=CORRECT)
    monkeypatch.setenv("OLLAMA_HOST", fake_ollama.url)
    spec, raw = ask_ollama(PAPER)
    assert spec.lap_length_m == 38 and raw["hall_y_m"] == 12
    assert reachable()


def test_auto_uses_rules_alone_when_everything_is_explained(fake_ollama):
    fake_ollama.reply = Reply(content=INVENTED)
    r = parse_request(PAPER, backend="auto", ollama_host=fake_ollama.url)
    assert r.backend == "rules" and fake_ollama.requests == []


def test_auto_asks_the_model_for_unexplained_words_and_guards_it(fake_ollama):
    text = "a 40 m lap with a banked hairpin"  # "banked" is unknown to the rules
    fake_ollama.reply = Reply(content=TrackSpec(lap_length_m=40, hairpins=1).model_dump_json())
    r = parse_request(text, backend="auto", ollama_host=fake_ollama.url)
    assert len(fake_ollama.requests) == 1 and r.backend == "auto"
    assert (r.spec.lap_length_m, r.spec.hairpins) == (40, 1)
    assert [u.text for u in r.unparsed] == ["banked hairpin"]  # the rules cannot count it
    fake_ollama.reply = Reply(content=TrackSpec(lap_length_m=40, hairpins=1, min_radius_m=3).model_dump_json())
    with pytest.raises(GroundingError, match="min_radius_m"):
        parse_request(text, backend="auto", ollama_host=fake_ollama.url)


def test_auto_keeps_rules_result_when_model_fails(fake_ollama):
    fake_ollama.reply = Reply(content="garbage")
    r = parse_request("a 40 m lap with a banked hairpin", backend="auto", ollama_host=fake_ollama.url)
    assert r.backend == "rules" and r.spec.lap_length_m == 40
    assert any("Ollama backend failed" in w for w in r.warnings)


def test_auto_without_server_is_rules(dead_url):
    r = parse_request("a 40 m lap with a banked hairpin", backend="auto", ollama_host=dead_url)
    assert r.backend == "rules"


def _live_host() -> str | None:
    host = os.environ.get("OLLAMA_HOST")
    return host if host and reachable(host, timeout=2) else None


@pytest.mark.ollama_live
@pytest.mark.skipif(_live_host() is None, reason="no Ollama server reachable at OLLAMA_HOST")
def test_live_server_paper_example():
    model = os.environ.get("ROBORACER_ARENA_OLLAMA_MODEL", "gemma4:31b")
    r = parse_request(PAPER, backend="ollama", model=model, timeout=600)
    assert (r.spec.lap_length_m, r.spec.hall_x_m, r.spec.hall_y_m) == (38, 15, 12)
    assert r.spec.min_radius_m == 0
