"""The default recipe's policy files that BENCHMARKS.md reports (docs/learning/policies/,
written by ``python -m benchmarks generalisation --policies``) still drive the held-out
recorded maps in the current build exactly as the benchmark recorded: the same clean laps
and lap times, at least 95 % clean over the seeds, and no slower than the reference pure
pursuit. Training them again takes most of an hour (``make docs-figures``); driving them
takes seconds, so CI holds the claim here."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import roboracer_arena as ra
from roboracer_arena.learn import HELD_OUT, evaluate_policy

ROOT = Path(__file__).resolve().parents[2]
DATA = json.loads((ROOT / "docs" / "learning" / "generalisation.json").read_text())
RUNS = [r for r in DATA["runs"] if r["condition"] == "pool_rand"]


def test_the_benchmark_kept_the_default_recipe_policies_and_its_held_out_list():
    assert len(RUNS) >= 5 and all((ROOT / r["policy_file"]).is_file() for r in RUNS)
    assert DATA["held_out"] == list(HELD_OUT) and len(HELD_OUT) >= 10
    laps = [lap for r in RUNS for lap in r["laps"]]
    assert sum(lap["clean_lap"] for lap in laps) >= 0.95 * len(laps)
    ratios = [lap["ratio"] for lap in laps if lap["ratio"] is not None]
    assert np.mean(ratios) <= 1.0


@pytest.mark.slow
@pytest.mark.parametrize("run", RUNS, ids=lambda r: f"seed{r['seed']}")
def test_default_recipe_policy_drives_the_held_out_maps_as_recorded(run, sources):
    policy = ra.load_policy(ROOT / run["policy_file"])
    assert not set(HELD_OUT) & set(policy.training["track_names"]), "a held-out map was trained on"
    laps = evaluate_policy(policy, list(HELD_OUT))
    assert [lap["clean_lap"] for lap in laps] == [lap["clean_lap"] for lap in run["laps"]]
    for got, want in zip(laps, run["laps"]):
        if want["lap_time"] is not None:
            assert got["lap_time"] == pytest.approx(want["lap_time"], abs=1e-6), got["track"]
