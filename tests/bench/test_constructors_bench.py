"""``bench constructors`` and its ``--sweep``: what ``--json`` writes is the result model's
dump (the trial counting itself is tested in tests/generate/test_bench_constructors.py)."""

from __future__ import annotations

from benchmarks.__main__ import main
from benchmarks.constructor_sweep import SweepResult, run_sweep
from benchmarks.constructors import ConstructorsResult
from roboracer_arena.bench.output import json_text
from roboracer_arena.spec import TrackSpec

SMALL = TrackSpec(name="small", lap_length_m=40, hall_x_m=15, hall_y_m=12, hairpins=1)


def test_constructors_json_is_the_model(tmp_path, capsys):
    specs, out = tmp_path / "specs.jsonl", tmp_path / "r.json"
    specs.write_text(SMALL.model_dump_json() + '\n{"name": "too-long", "lap_length_m": 200}\n')
    argv = ["constructors", "--specs", str(specs), "--seeds", "0", "--constructors", "lattice-raw", "random"]
    assert main([*argv, "--json", str(out)]) == 0
    assert f"wrote {out}" in capsys.readouterr().out
    text = out.read_text()
    res = ConstructorsResult.model_validate_json(text)
    assert json_text(res) == text
    assert [t.constructor for t in res.trials] == ["lattice-raw", "random"]
    assert [r.spec for r in res.screen_rejections] == ["too-long"]


def test_sweep_json_is_the_model():
    res = run_sweep([SMALL, TrackSpec(name="too-long", lap_length_m=200.0)], progress=False)
    text = json_text(res)
    assert SweepResult.model_validate_json(text) == res and json_text(SweepResult.model_validate_json(text)) == text
    (miss,) = res.misses
    assert miss.spec == "too-long" and miss.outcome == "rejected" and miss.top_reasons is not None
    assert [r.top_reasons is None for r in res.rows] == [res.rows[0].outcome == "accepted", False]
