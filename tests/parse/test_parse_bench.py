"""``roboracer-arena bench parser``: scoring, the shipped request set, and the ollama row."""

from __future__ import annotations

import json
from pathlib import Path

from fake_ollama import Reply

from benchmarks import bench_data
from benchmarks.__main__ import main
from benchmarks.parser import (
    REPO_REQUESTS,
    ParserResult,
    ParserRow,
    Unreachable,
    load_requests,
    run,
    run_sets,
    score,
)
from roboracer_arena.bench.output import json_text
from roboracer_arena.cli import EXIT_OK
from roboracer_arena.parse.result import DEFAULTS
from roboracer_arena.spec import TrackSpec


def test_score_exact_and_invention():
    got = {**DEFAULTS, "lap_length_m": 38.0}
    assert score(got, {"lap_length_m": 38.0}) == (True, True, [])
    assert score({**got, "min_radius_m": 9.0}, {"lap_length_m": 38.0}) == (False, False, ["min_radius_m"])
    assert score({**got, "lap_length_m": 40.0}, {"lap_length_m": 38.0}) == (False, True, ["lap_length_m"])
    assert score(None, {}) == (False, False, ["(error)"])


def test_shipped_set_size_and_rules_scores(capsys):
    reqs = load_requests(REPO_REQUESTS)
    assert sum(r["set"] == "parse" for r in reqs) >= 12
    assert sum(r["set"] == "audit" for r in reqs) >= 17
    assert any(r["text"] == "a 38 m lap for a small 15 by 12 hall" for r in reqs)
    row = run(REPO_REQUESTS, ("rules",), repeats=3).rows["rules"]
    assert isinstance(row, ParserRow)
    assert row.parse_exact == row.parse_total
    assert row.audit_pass == row.audit_calls == 3 * sum(r["set"] == "audit" for r in reqs)
    assert row.misses == []
    assert "gemma4:31b (paper)" in capsys.readouterr().out


def _small_set(tmp_path: Path) -> Path:
    lines = [
        {"id": "p", "set": "parse", "text": "a 38 m lap for a small 15 by 12 hall",
         "expected": {"lap_length_m": 38.0, "hall_x_m": 15.0, "hall_y_m": 12.0}},
        {"id": "a", "set": "audit", "text": "a 38 m lap for a small 15 by 12 hall",
         "expected": {"lap_length_m": 38.0, "hall_x_m": 15.0, "hall_y_m": 12.0}},
    ]  # fmt: skip
    p = tmp_path / "r.jsonl"
    p.write_text("\n".join(json.dumps(x) for x in lines) + "\n")
    return p


def test_ollama_row_counts_inventions_and_guard(tmp_path, fake_ollama, capsys):
    fake_ollama.reply = Reply(
        content=TrackSpec(lap_length_m=38, hall_x_m=15, hall_y_m=12, min_radius_m=9).model_dump_json()
    )
    res = run(_small_set(tmp_path), ("ollama",), repeats=2, ollama_host=fake_ollama.url)
    row = res.rows["ollama gemma4:31b"]
    assert isinstance(row, ParserRow)
    assert row.parse == "0/1" and row.audit == "0/2"
    assert row.inventions_caught_by_guard == 3 and row.inventions_missed_by_guard == 0
    assert len(fake_ollama.requests) == 3
    assert "min_radius_m" in capsys.readouterr().out


def test_unreachable_ollama_is_a_row_not_a_failure(tmp_path, dead_url, capsys):
    out = tmp_path / "b.json"
    argv = ["parser", "--requests", str(_small_set(tmp_path)), "--backend", "rules", "ollama",
            "--ollama-host", dead_url, "--json", str(out)]  # fmt: skip
    assert main(argv) == EXIT_OK
    assert "not reachable" in capsys.readouterr().out
    text = out.read_text()
    assert json_text(ParserResult.model_validate_json(text)) == text
    d = json.loads(text)
    assert d["rows"]["rules"]["parse"] == "1/1" and "sets" not in d
    assert d["rows"]["ollama gemma4:31b"]["status"].startswith("not reachable")
    assert isinstance(ParserResult.model_validate_json(text).rows["ollama gemma4:31b"], Unreachable)


def test_refusal_rows_need_a_typed_error_naming_the_span(tmp_path):
    lines = [
        {"id": "r1", "set": "refuse", "text": "a 45 m lap in 10 minutes", "expected": {}, "span": "10"},
        {"id": "r2", "set": "refuse", "text": "a 45 m lap", "expected": {}},  # accepted: a miss
        {"id": "r3", "set": "refuse", "text": "a 45 m lap in 10 minutes", "expected": {}, "span": "99"},
    ]
    p = tmp_path / "r.jsonl"
    p.write_text("\n".join(json.dumps(x) for x in lines) + "\n")
    row = run(p, ("rules",), repeats=1).rows["rules"]
    assert isinstance(row, ParserRow)
    assert row.refuse == "1/3"
    assert [(m.id, m.fields) for m in row.misses] == [("r2", ["(accepted)"]), ("r3", ["(span not named)"])]


def test_every_shipped_set_with_the_recorded_blind_score(capsys):
    everyday = load_requests(bench_data("requests_everyday.jsonl"))
    assert len(everyday) >= 100 and sum(r["batch"] == "blind" for r in everyday) >= 40
    assert len(load_requests(bench_data("requests_e2e.jsonl"))) == 8
    res = run_sets()
    sets = res.sets
    e2e = sets["paper end-to-end (8)"]
    assert e2e.parse_exact == e2e.parse_total == 8  # the end-to-end requests must parse exactly
    for label in ("everyday, blind batch", "everyday, after batch"):
        r = sets[label]
        assert r.refuse_correct == r.refuse_total  # no refusal is ever missed
        assert r.parse_exact >= r.parse_total - 1
    blind = res.blind_recorded.files["requests_everyday.jsonl"]
    assert blind.total == sum(r["batch"] == "blind" for r in everyday)
    out = capsys.readouterr().out
    assert "blind run: requests_everyday.jsonl" in out and "everyday, after batch" in out
