"""bench generalisation end to end on a tiny budget (the real run is in BENCHMARKS.md),
its summary arithmetic, and its refusals."""

import pytest

from benchmarks.__main__ import main
from benchmarks.generalisation import GeneralisationResult, HeldOutLap, TrainingRun, interval, run, summarise
from roboracer_arena.bench.output import json_text
from roboracer_arena.errors import ConfigError


@pytest.mark.slow
def test_tiny_generalisation_run_reports_its_condition(sources, tmp_path):
    res = run(
        seeds=1,
        generations=1,
        conditions=("single",),
        single="gen-l070-w20-h0c0s0-ccw-s0",
        held_out=["gym-skirk"],
        policies=tmp_path,
        verbose=False,
    )
    assert set(res.summary) == {"single"}
    s = res.summary["single"]
    assert 0.0 <= s.clean_lap_rate.mean <= 1.0 and set(s.clean_laps_per_track) == {"gym-skirk"}
    assert res.reference_laps["gym-skirk"] == pytest.approx(13.45, abs=0.2)
    assert (tmp_path / "single-seed0.npz").is_file()
    text = json_text(res)  # as written by --json
    assert json_text(GeneralisationResult.model_validate_json(text)) == text


def test_summary_counts_clean_laps_ratios_and_intervals():
    def lap(track: str, time: float | None) -> HeldOutLap:
        ratio = None if time is None else time / 10.0
        return HeldOutLap(
            track=track, clean_lap=time is not None, lap_time=time, progress=5.0, reference_lap_time=10.0, ratio=ratio
        )

    def training(seed: int, laps: list[HeldOutLap]) -> TrainingRun:
        return TrainingRun(
            condition="pool",
            seed=seed,
            generations=1,
            env_steps=10,
            train_seconds=1.0,
            cpu_seconds=2.0,
            final_mean_return=0.0,
            clean_laps=sum(x.clean_lap for x in laps),
            laps=laps,
        )

    runs = [training(0, [lap("a", 9.0), lap("b", None)]), training(1, [lap("a", 8.0), lap("b", 10.0)])]
    s = summarise(runs)["pool"]
    assert s.clean_lap_rate.mean == 0.75 and s.clean_lap_rate.n == 2
    assert s.lap_time_ratio is not None and s.lap_time_ratio.mean == pytest.approx(0.9 * 0.5 + 0.9 * 0.5)
    assert s.clean_laps_per_track == {"a": 2, "b": 1} and s.env_steps == 10 and s.train_cpu_seconds == 2.0
    i = interval([1.0, 1.0, 1.0])
    assert (i.low, i.high) == (1.0, 1.0)
    i = interval([0.6, 0.8, 1.0])
    assert i.low < 0.8 < i.high and i.high - 0.8 == pytest.approx(4.303 * 0.2 / 3**0.5, abs=1e-3)


def test_training_track_in_held_out_is_refused():
    with pytest.raises(ConfigError, match="held out"):
        run(seeds=1, generations=1, single="gym-skirk", held_out=["gym-skirk"], verbose=False)
    assert main(["generalisation", "--seeds", "0"]) == 2
