"""``tracks show`` prints a track's recorded raceline; ``tracks verify --raceline`` plans it
again and fails on a record that no longer holds."""

from __future__ import annotations

import json

import pytest

from roboracer_arena.cli import EXIT_BAD_INPUT, EXIT_OK, main
from roboracer_arena.cli import tracks as tracks_cli
from roboracer_arena.library.racelines import build_racelines, load_index

SMALL = "gen-l040-w12-h2c1s1-clo-s0"


@pytest.fixture(scope="module")
def index_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("racelines") / "racelines.json"
    build_racelines([SMALL], path=path)
    return path


def test_show_prints_the_raceline(index_file, monkeypatch, capsys):
    monkeypatch.setattr(tracks_cli, "load_index", lambda: load_index(index_file))
    assert main(["tracks", "show", SMALL]) == EXIT_OK
    out = capsys.readouterr().out
    assert "raceline:" in out and "planned lap" in out and "racing driver:" in out
    assert main(["tracks", "show", SMALL, "--json"]) == EXIT_OK
    rec = json.loads(capsys.readouterr().out)["raceline"]
    assert rec["id"] == SMALL and rec["lap_time_s"] > 0 and rec["driver"]["clean"] is True


def test_verify_raceline_checks_the_record(index_file, monkeypatch, capsys):
    monkeypatch.setattr(tracks_cli, "load_index", lambda: load_index(index_file))
    argv = ["tracks", "verify", "--ids", SMALL, "--no-usd", "--no-physx", "--no-drive", "--jobs", "1", "--raceline"]
    assert main(argv) == EXIT_OK
    assert "racelines: 1/1 as recorded" in capsys.readouterr().out
    good = load_index(index_file)
    rec = good.get(SMALL)
    bad = good.with_fields(records=[rec.with_fields(csv_sha1="0" * 40).to_json_dict()])
    monkeypatch.setattr(tracks_cli, "load_index", lambda: bad)
    assert main(argv) == EXIT_BAD_INPUT
    assert "CSV differs" in capsys.readouterr().err
