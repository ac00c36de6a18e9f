"""`roboracer-arena bench physics` end to end (tiny durations; numbers are not checked)."""

from __future__ import annotations

import json

from roboracer_arena.bench.output import json_text
from roboracer_arena.bench.physics import PhysicsResult
from roboracer_arena.cli import main


def test_bench_physics_cli_writes_json(tmp_path, capsys):
    out = tmp_path / "physics.json"
    code = main(["bench", "physics", "--vehicles", "1", "4", "--per-env", "2", "--seconds", "0.05", "--json", str(out)])
    assert code == 0
    text = capsys.readouterr().out
    assert "28.1" in text and "lidar scan" in text
    assert json_text(PhysicsResult.model_validate_json(out.read_text())) == out.read_text()
    result = json.loads(out.read_text())
    rows = result["rows"]
    assert [(r["envs"], r["per_env"]) for r in rows] == [(1, 1), (2, 2)]
    assert all(r["vehicle_steps_per_s"] > 0 and r["wall_contact_fraction"] == 0 for r in rows)
    assert result["scan"]["beams"] == 1081 and result["scan"]["scan_us_median"] > 0
