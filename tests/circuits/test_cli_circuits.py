"""``roboracer-arena circuits`` end to end on two real circuits from the shared sources."""

from __future__ import annotations

import json

from roboracer_arena.circuits import circuit_inputs
from roboracer_arena.cli import main


def test_every_tum_circuit_and_the_uncovered_bacinger_ones_are_listed(sources):
    inputs, skipped = circuit_inputs(sources)
    ids = {c.id for c in inputs}
    assert len(inputs) >= 44 and {"monaco", "baku", "suzuka", "spa"} <= ids
    assert sum(c.source == "tumftm" for c in inputs) == 25
    assert all(s["length_difference"] <= 0.03 for s in skipped)
    assert len(ids) == len(inputs)


def test_cli_builds_monaco_and_flags_suzuka(sources, tmp_path, capsys):
    rc = main(
        [
            "circuits",
            "--sources",
            str(sources),
            "-o",
            str(tmp_path),
            "--only",
            "monaco",
            "suzuka",
            "--jobs",
            "2",
            "--json",
        ]
    )
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out["built"] == 2 and out["one_corridor"] == 2
    by_id = {r["id"]: r for r in out["results"]}
    assert by_id["suzuka"]["grade_separated"] and by_id["suzuka"]["length_error"] is None
    assert not by_id["monaco"]["grade_separated"]
    assert by_id["monaco"]["length_error"] < 0.009
    assert 0 < by_id["monaco"]["narrowed_fraction"] < 0.2
    assert (tmp_path / "monaco" / "map.yaml").is_file() and (tmp_path / "index.json").is_file()
