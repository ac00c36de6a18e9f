"""CI runs the ES example script briefly (the trainer itself: tests/learn/test_es.py)."""

import runpy
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "train_es.py"
TRACK = "gen-l070-w20-h0c0s0-ccw-s0"  # 70 m, 2 m wide: a few generations show progress


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
