"""``roboracer-arena bench env`` runs end to end (tiny budget; the figures live in BENCHMARKS.md)."""

import json

from roboracer_arena.bench.env import EnvResult
from roboracer_arena.bench.output import json_text
from roboracer_arena.cli import main


def test_bench_env_smoke(sources, tmp_path, capsys):
    out = tmp_path / "env.json"
    berlin = sources / "f1tenth-gym" / "maps" / "berlin.yaml"
    code = main(
        [
            "bench",
            "env",
            "--map",
            str(berlin),
            "--num-envs",
            "1",
            "2",
            "--seconds",
            "0.2",
            "--beams",
            "109",
            "--json",
            str(out),
        ]
    )
    assert code == 0
    text = capsys.readouterr().out
    assert "physics" in text and "python" in text
    assert "F1TENTH Gym" not in text  # the peer's figure is the checkout's (python -m benchmarks env)
    assert json_text(EnvResult.model_validate_json(out.read_text())) == out.read_text()
    res = json.loads(out.read_text())
    assert res["f1tenth_gym_env_steps_per_s"] == []
    assert [(r["workload"], r["num_envs"]) for r in res["rows"]] == [
        (w, n) for w in ("constant", "lap", "random") for n in (1, 2)
    ]
    assert all(r["env_steps_per_s"] > 0 and r["steps"] > 0 for r in res["rows"])
    assert all(set(r["breakdown_us_per_call"]) == {"physics", "scan", "python"} for r in res["rows"])
    assert all(r["breakdown_us_per_call"]["physics"] > 0 and r["python_us_per_step"] > 0 for r in res["rows"])
    assert res["recorded_lap_steps"] > 1000  # a full lap at 100 Hz
    assert res["scan_over_lap"]["poses"] > 50 and res["scan_over_lap"]["median_us"] > 0
