"""`roboracer-arena bench physics` end to end (tiny durations; numbers are not checked), and
the checkout's `python -m benchmarks physics`, the same run with the paper's figures beside."""

from __future__ import annotations

import json

import pytest

from benchmarks.__main__ import main as benchmarks_main
from roboracer_arena.bench.output import json_text
from roboracer_arena.bench.physics import PhysicsResult
from roboracer_arena.cli import main


@pytest.mark.parametrize("wheel", [True, False], ids=["roboracer-arena bench", "python -m benchmarks"])
def test_bench_physics_cli_writes_json(wheel, tmp_path, capsys):
    out = tmp_path / "physics.json"
    argv = ["physics", "--vehicles", "1", "4", "--per-env", "2", "--seconds", "0.05", "--json", str(out)]
    code = main(["bench", *argv]) if wheel else benchmarks_main(argv)
    assert code == 0
    text = capsys.readouterr().out
    assert "lidar scan" in text
    assert ("28.1" in text) is not wheel  # the paper's Isaac Sim figure for 1 vehicle: the checkout's only
    assert json_text(PhysicsResult.model_validate_json(out.read_text())) == out.read_text()
    result = json.loads(out.read_text())
    rows = result["rows"]
    assert [(r["envs"], r["per_env"]) for r in rows] == [(1, 1), (2, 2)]
    assert all(r["vehicle_steps_per_s"] > 0 and r["wall_contact_fraction"] == 0 for r in rows)
    assert result["scan"]["beams"] == 1081 and result["scan"]["scan_us_median"] > 0
