"""bench generalisation end to end on a tiny budget (the real run is in BENCHMARKS.md)."""

import pytest

from benchmarks.__main__ import main
from benchmarks.generalisation import GeneralisationResult, HeldOutLap, TrainingRun, run, summarise
from roboracer_arena.bench.output import json_text
from roboracer_arena.errors import ConfigError


@pytest.mark.slow
def test_tiny_generalisation_run_reports_both_conditions(sources, capsys):
    res = run(
        seeds=1,
        generations=2,
        pairs=2,
        episode_steps=20,
        single="gen-l070-w20-h0c0s0-ccw-s0",
        held_out=["gym-skirk"],
        pool={"generated:gen-l040-*": 1.0},
        verbose=False,
    )
    assert set(res.summary) == {"single", "pool"}
    for s in res.summary.values():
        assert 0.0 <= s.clean_lap_rate <= 1.0 and set(s.clean_laps_per_track) == {"gym-skirk"}
    assert [r.condition for r in res.runs] == ["single", "pool"]
    text = json_text(res)  # as written by --json
    assert json_text(GeneralisationResult.model_validate_json(text)) == text


def test_summary_counts_clean_laps_and_times():
    def lap(track: str, time: float | None) -> HeldOutLap:
        return HeldOutLap(track=track, clean_lap=time is not None, lap_time=time, progress=5.0)

    def training(seed: int, env_steps: int, laps: list[HeldOutLap]) -> TrainingRun:
        return TrainingRun(
            condition="single",
            seed=seed,
            env_steps=env_steps,
            train_seconds=1.0,
            cpu_seconds=1.0,
            wall_seconds=1.0,
            final_mean_return=0.0,
            laps=laps,
        )

    runs = [training(0, 10, [lap("a", 10.0), lap("b", None)]), training(1, 20, [lap("a", 12.0), lap("b", 20.0)])]
    s = summarise(runs)["single"]
    assert s.clean_lap_rate == 0.75 and s.mean_lap_time_s == 14.0
    assert s.clean_laps_per_track == {"a": 2, "b": 1} and s.mean_env_steps == 15


def test_training_track_in_held_out_is_refused():
    with pytest.raises(ConfigError, match="held-out"):
        run(seeds=1, generations=1, pairs=1, single="gym-skirk", held_out=["gym-skirk"], verbose=False)
    assert main(["generalisation", "--seeds", "0"]) == 2
