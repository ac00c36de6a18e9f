"""``roboracer-arena parse`` and ``generate "REQUEST"`` end to end (in-process)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from fake_ollama import Reply

from roboracer_arena.cli import EXIT_BAD_INPUT, EXIT_OK, EXIT_REJECTED, main
from roboracer_arena.spec import TrackSpec


def test_parse_prints_values_and_sources(capsys):
    assert main(["parse", "a 38 m lap for a small 15 by 12 hall with banked turns"]) == EXIT_OK
    out = capsys.readouterr().out
    assert "request: a [38 m lap] for a small [15] by [12] hall with ?banked? turns" in out
    assert "lap_length_m        38.0" in out and "'38 m lap' @2-10" in out
    assert "(default)" in out
    assert "not understood: 'banked'" in out


def test_parse_json(capsys):
    assert main(["parse", "two sweepers then a hairpin", "--json"]) == EXIT_OK
    d = json.loads(capsys.readouterr().out)
    assert d["spec"]["feature_order"] == ["sweeper", "sweeper", "hairpin"]
    assert d["stated"] == ["hairpins", "sweepers", "feature_order"]
    assert d["sources"]["sweepers"][0]["text"] == "two sweepers"


def test_parse_contradiction_exits_2(capsys):
    assert main(["parse", "clockwise and anticlockwise"]) == EXIT_BAD_INPUT
    assert "counter-clockwise" in capsys.readouterr().err


def test_parse_with_ollama_backend_and_invention(fake_ollama, capsys):
    text = "a 38 m lap for a small 15 by 12 hall"
    fake_ollama.reply = Reply(
        content=TrackSpec(lap_length_m=38, hall_x_m=15, hall_y_m=12, min_radius_m=9).model_dump_json()
    )
    argv = ["parse", text, "--backend", "ollama", "--ollama-host", fake_ollama.url]
    assert main(argv) == EXIT_BAD_INPUT
    assert "invented" in capsys.readouterr().err
    with pytest.warns(UserWarning, match="min_radius_m"):
        assert main([*argv, "--lenient", "--json"]) == EXIT_OK
    d = json.loads(capsys.readouterr().out)
    assert d["spec"]["min_radius_m"] == 0.0 and d["warnings"]


def test_generate_from_text_accepts(tmp_path, capsys):
    out = tmp_path / "t"
    code = main(["generate", "a 60 m lap with two hairpins in a 20 by 15 m hall", "-o", str(out), "--json"])
    assert code == EXIT_OK
    d = json.loads(capsys.readouterr().out)
    assert d["outcome"] == "accepted"
    assert d["parse"]["spec"]["hairpins"] == 2 and d["parse"]["spec"]["lap_length_m"] == 60
    assert all(c["passed"] for c in d["checks"])
    assert Path(d["files"]["map_yaml"]).is_file() and Path(d["files"]["map_yaml"]).parent == out


def test_generate_from_text_rejected_by_screen(tmp_path, capsys):
    code = main(["generate", "a 200 m lap in a 20 by 15 m hall", "-o", str(tmp_path / "r")])
    assert code == EXIT_REJECTED
    err = capsys.readouterr().err
    assert "200" in err and "rejected" in err.lower()


def test_generate_request_and_spec_together_is_bad_input(tmp_path, capsys):
    spec = tmp_path / "s.json"
    spec.write_text(TrackSpec().model_dump_json())
    assert main(["generate", "a 60 m lap", "--spec", str(spec)]) == EXIT_BAD_INPUT
