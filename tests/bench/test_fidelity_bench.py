"""``roboracer-arena bench fidelity --quick`` end to end: the JSON is its model's dump (the
physics checks of the manoeuvres live in tests/envs/test_vehicle_fidelity.py)."""

from __future__ import annotations

from benchmarks.__main__ import main
from benchmarks.fidelity import FidelityResult
from roboracer_arena.bench.output import json_text


def test_bench_fidelity_cli_writes_its_model(tmp_path, capsys):
    out = tmp_path / "fidelity.json"
    assert main(["fidelity", "--quick", "--json", str(out)]) == 0
    assert "dt sensitivity" in capsys.readouterr().out
    text = out.read_text()
    res = FidelityResult.model_validate_json(text)
    assert json_text(res) == text
    assert [t.v for t in res.turns][::4] == [1.0, 3.0, 5.0] and [lim.v for lim in res.limit] == [5.0]
    assert '"yaw_rate_3ms_0.2"' in text and res.braking.t_ideal is not None and res.gym_braking.t_ideal is None
