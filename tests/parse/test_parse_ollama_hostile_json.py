"""Issue 38, class C for the model's answer: the Ollama backend's JSON is hostile input
too. Nested thousands deep or with a 5000-digit number it was a RecursionError or a
ValueError traceback; now it is the backend's typed MalformedOutputError, like any other
answer that is not a TrackSpec."""

from __future__ import annotations

import pytest
from fake_ollama import Reply

from roboracer_arena.errors import MalformedOutputError
from roboracer_arena.parse import parse_request

PAPER = "A 60 m lap in a 20 by 15 m hall."


@pytest.mark.parametrize(
    "content",
    ["[" * 100_000 + "]" * 100_000, '{"lap_length_m": ' + "9" * 5000 + "}", '{"a": ' * 70 + "1" + "}" * 70],
    ids=["100000-deep", "5000-digit", "70-deep-object"],
)
def test_hostile_model_json_is_a_malformed_output(fake_ollama, content):
    fake_ollama.reply = Reply(content=content)
    with pytest.raises(MalformedOutputError) as e:
        parse_request(PAPER, backend="ollama", ollama_host=fake_ollama.url)
    assert "\n" not in str(e.value) and len(str(e.value)) < 500
