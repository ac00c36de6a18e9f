"""CI runs the ES example briefly: a few generations on a small generated catalog track
(packaged, no shared data needed), and the population's return must improve."""

import runpy
from pathlib import Path

import numpy as np
import pytest

from roboracer_arena.learn import ESConfig, train

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "train_es.py"
TRACK = "gen-l070-w20-h0c0s0-ccw-s0"  # 70 m, 2 m wide: a few generations show progress


@pytest.mark.slow
def test_es_return_improves_in_a_few_generations():
    cfg = ESConfig(generations=14, pairs=8, episode_steps=80, seed=1)
    result = train(TRACK, cfg)
    means = np.array([r["mean_return"] for r in result.curve])
    assert len(means) == 14 and result.env_steps > 0
    # Start poses differ per generation, so single generations are noisy: compare thirds.
    assert means[-3:].mean() > means[:3].mean() + 2.0, means


def test_es_is_seeded():
    cfg = ESConfig(generations=2, pairs=4, episode_steps=20, seed=3)
    a, b = train(TRACK, cfg), train(TRACK, cfg)
    assert np.array_equal(a.theta, b.theta)


@pytest.mark.slow
def test_example_script_runs_and_writes_outputs(tmp_path, monkeypatch):
    import json
    import sys

    png, out = tmp_path / "curve.png", tmp_path / "es.json"
    monkeypatch.setattr(
        sys,
        "argv",
        [
            "train_es.py",
            "--track",
            TRACK,
            "--generations",
            "2",
            "--pairs",
            "4",
            "--episode-steps",
            "20",
            "--png",
            str(png),
            "--json",
            str(out),
        ],
    )
    with pytest.raises(SystemExit) as e:
        runpy.run_path(str(EXAMPLE), run_name="__main__")
    assert e.value.code == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    doc = json.loads(out.read_text())
    assert len(doc["curve"]) == 2 and doc["laps"][0]["track"] == TRACK
