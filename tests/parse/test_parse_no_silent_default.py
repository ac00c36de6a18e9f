"""Nothing silently defaulted: a number no field explains is refused with its span
(``lenient``: ignored with a warning); ``defaulted`` lists the unstated fields."""

from __future__ import annotations

import json

import pytest
from fake_ollama import Reply

from roboracer_arena.cli import EXIT_BAD_INPUT, EXIT_OK, main
from roboracer_arena.errors import MalformedOutputError, RequestParseError
from roboracer_arena.parse import parse_request
from roboracer_arena.parse.result import FIELDS
from roboracer_arena.spec import TrackSpec


@pytest.mark.parametrize(
    "text, span",
    [
        ("a 45 m lap with 3 hairpins in 10 minutes", "'10' (characters 30-32)"),
        ("50 m lap with 2 hairpins and 7", "'7' (characters 29-30)"),
        ("a 60 m lap for 4 drivers", "'4' (characters 15-16)"),
        ("a 45 m lap in a 20 by 15 m hall with 1.5", "'1.5'"),
        ("a lap, eight hairpins, and nineteen", "'nineteen'"),
        ("a 45 m lap, top speed 5 m/s", "'5 m'"),
    ],
)
def test_unexplained_number_is_refused_naming_its_span(text, span):
    with pytest.raises(RequestParseError, match="no TrackSpec field explains") as e:
        parse_request(text)
    assert span in str(e.value)


def test_lenient_ignores_with_a_warning_and_lists_it():
    r = parse_request("a 45 m lap with 3 hairpins in 10 minutes", lenient=True)
    assert (r.spec.lap_length_m, r.spec.hairpins) == (45.0, 3)
    assert [(f.text, f.start, f.end) for f in r.ignored] == [("10", 30, 32)]
    assert any(w.startswith("lenient: ignored '10'") for w in r.warnings)


def test_two_bare_lengths_are_ambiguous_not_guessed():
    with pytest.raises(RequestParseError, match="'8 m'.*'1.2 m'"):
        parse_request("two chicanes, 8 m, 1.2 m")


def test_defaulted_lists_every_unstated_field():
    r = parse_request("a 45 m lap with two hairpins")
    assert r.stated == ("lap_length_m", "hairpins")
    assert set(r.defaulted) == set(FIELDS) - {"lap_length_m", "hairpins"}
    d = r.to_dict()
    assert d["defaulted"] == list(r.defaulted) and d["stated"] == ["lap_length_m", "hairpins"]


def test_pronoun_one_is_not_a_number():
    assert parse_request("a track, one with a 40 m lap").spec.lap_length_m == 40.0


def test_cli_parse_refuses_with_exit_2_and_the_span(capsys):
    assert main(["parse", "a 45 m lap with 3 hairpins in 10 minutes"]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert "'10' (characters 30-32)" in err and "--lenient" in err and err.count("\n") == 1


def test_cli_parse_lenient_warns_and_prints_defaulted(capsys):
    assert main(["parse", "a 45 m lap with 3 hairpins in 10 minutes", "--lenient"]) == EXIT_OK
    out = capsys.readouterr().out
    assert "warning: lenient: ignored '10'" in out
    assert "stated: lap_length_m, hairpins" in out
    assert "defaulted: name, corridor_width_m, hall_x_m" in out


def test_cli_parse_json_lists_defaulted_hedges_and_ignored(capsys):
    assert main(["parse", "roughly 42 m long loop and 9 cones", "--lenient", "--json"]) == EXIT_OK
    d = json.loads(capsys.readouterr().out)
    assert d["stated"] == ["lap_length_m"] and "corridor_width_m" in d["defaulted"]
    assert d["hedges"] == {"lap_length_m": "approximately"}
    assert d["ignored"] == [{"text": "9", "start": 27, "end": 28}]


def test_cli_generate_refuses_an_unexplained_number(tmp_path, capsys):
    out = tmp_path / "g"
    assert main(["generate", "a 45 m lap with 3 hairpins in 10 minutes", "-o", str(out)]) == EXIT_BAD_INPUT
    assert "'10' (characters 30-32)" in capsys.readouterr().err
    assert not out.exists()


def test_ollama_answer_must_explain_every_number(fake_ollama):
    text = "a 45 m lap with 3 hairpins in 10 minutes"
    fake_ollama.reply = Reply(content=TrackSpec(lap_length_m=45, hairpins=3).model_dump_json())
    with pytest.raises(RequestParseError, match="'10' \\(characters 30-32\\)"):
        parse_request(text, backend="ollama", ollama_host=fake_ollama.url)
    r = parse_request(text, backend="ollama", ollama_host=fake_ollama.url, lenient=True)
    assert [f.text for f in r.ignored] == ["10"] and r.spec.hairpins == 3


def test_ollama_answer_explaining_every_number_passes(fake_ollama):
    text = "a 60 m lap, five hairpins, in a 20 by 15 m hall"  # 60, 20, 15 equal the defaults
    fake_ollama.reply = Reply(content=TrackSpec(hairpins=5).model_dump_json())
    r = parse_request(text, backend="ollama", ollama_host=fake_ollama.url)
    assert r.spec.hairpins == 5 and r.ignored == ()


def test_ollama_value_out_of_range_is_refused(fake_ollama):
    fake_ollama.reply = Reply(content=json.dumps({**TrackSpec().model_dump(), "lap_length_m": 1e9}))
    with pytest.raises(MalformedOutputError, match="lap_length_m.*2000"):  # the schema's own range
        parse_request("a lap of 1e9 m", backend="ollama", ollama_host=fake_ollama.url)


def test_auto_without_server_applies_the_same_rule(dead_url):
    with pytest.raises(RequestParseError, match="'10'"):
        parse_request("a 45 m lap with 3 hairpins in 10 minutes", backend="auto", ollama_host=dead_url)
    r = parse_request("a 45 m lap with 3 hairpins in 10 minutes", backend="auto", ollama_host=dead_url, lenient=True)
    assert [f.text for f in r.ignored] == ["10"]


def test_auto_lets_the_model_explain_what_the_rules_could_not(fake_ollama):
    text = "a 45 m lap with turns whose radius never drops below 2 m"  # the rules leave "2 m"
    with pytest.raises(RequestParseError, match="'2 m'"):
        parse_request(text)
    fake_ollama.reply = Reply(content=TrackSpec(lap_length_m=45, min_radius_m=2).model_dump_json())
    r = parse_request(text, backend="auto", ollama_host=fake_ollama.url)
    assert (r.spec.lap_length_m, r.spec.min_radius_m) == (45.0, 2.0) and r.ignored == ()
    fake_ollama.reply = Reply(content=TrackSpec(lap_length_m=45).model_dump_json())  # the model misses it too
    with pytest.raises(RequestParseError, match="'2 m'"):
        parse_request(text, backend="auto", ollama_host=fake_ollama.url)


def test_cli_generate_lenient_warns_and_builds(tmp_path, capsys):
    out = tmp_path / "g"
    argv = ["generate", "a 60 m lap with two hairpins in a 20 by 15 m hall, 3 cones", "-o", str(out), "--lenient"]
    assert main(argv) == EXIT_OK
    err = capsys.readouterr().err
    assert "warning: lenient: ignored '3' (characters 51-52)" in err and "defaulted: name" in err
    assert (out / "map.yaml").is_file()


def test_ollama_summed_counts_explain_each_written_count(fake_ollama):
    text = "two hairpins then a chicane then two more hairpins, 45 m"
    fake_ollama.reply = Reply(
        content=TrackSpec(
            hairpins=4, chicanes=1, lap_length_m=45, feature_order=["hairpin"] * 2 + ["chicane"] + ["hairpin"] * 2
        ).model_dump_json()
    )
    r = parse_request(text, backend="ollama", ollama_host=fake_ollama.url)
    assert r.spec.hairpins == 4 and r.ignored == ()
