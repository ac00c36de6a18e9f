"""The racing driver laps a small catalog track cleanly near its plan, from the CLI too."""

from __future__ import annotations

import json

from roboracer_arena.cli import EXIT_BAD_INPUT, EXIT_OK, main
from roboracer_arena.raceline.driver import drive_raceline, plan_for_driver
from roboracer_arena.raceline.source import resolve_track

SMALL = "gen-l040-w12-h2c1s1-clo-s0"


def test_racing_driver_laps_cleanly_near_the_plan():
    track, _ = resolve_track(SMALL)
    line = plan_for_driver(track)
    res = drive_raceline(SMALL, line, 2)
    assert res.completed, res
    assert res.lap_times[-1] <= 1.08 * line.lap_time  # flying lap (standing start on lap 1)
    assert res.lap_times[-1] >= 0.95 * line.lap_time  # no faster than physics allows the plan


def test_drive_raceline_flag(capsys):
    assert main(["drive", SMALL, "--raceline", "--laps", "2", "--json"]) == EXIT_OK
    out = json.loads(capsys.readouterr().out)
    assert out["completed"] is True
    assert main(["drive", SMALL, "--raceline", "--reverse"]) == EXIT_BAD_INPUT
    assert "--raceline" in capsys.readouterr().err
