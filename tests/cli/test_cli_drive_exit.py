"""``drive`` exit codes: 0 when every lap is completed, 5 when the car crashes or does not
finish; ``--reverse`` drives the other way round."""

from __future__ import annotations

import json

from roboracer_arena.cli import EXIT_LAP_FAILED, EXIT_OK, main

SMALL_CW = "gen-l040-w12-h2c1s1-clo-s0"  # a 40 m clockwise generated track from the catalog


def test_drive_exits_nonzero_when_the_lap_is_not_finished(capsys):
    assert main(["drive", SMALL_CW, "--max-time", "1", "--json"]) == EXIT_LAP_FAILED
    out = json.loads(capsys.readouterr().out)
    assert out["completed"] is False and out["laps_completed"] == 0
    assert main(["drive", SMALL_CW, "--max-time", "1"]) == EXIT_LAP_FAILED
    assert "did not finish" in capsys.readouterr().out


def test_drive_completes_both_ways(capsys):
    assert main(["drive", SMALL_CW, "--json"]) == EXIT_OK
    assert json.loads(capsys.readouterr().out)["completed"] is True
    assert main(["drive", SMALL_CW, "--reverse", "--json"]) == EXIT_OK
    assert json.loads(capsys.readouterr().out)["completed"] is True
