"""Nearest feasible specs after a generation failure (issue 28): every suggestion was
built by the search, and running it as suggested (its spec, its seed, the default
candidate cap and budget) is accepted again; the CLI prints and ``--json`` carries them."""

import json

import pytest

from benchmarks.constructor_sweep import load_sweep_file, run_sweep
from roboracer_arena import TrackSpec
from roboracer_arena.cli import main
from roboracer_arena.generate import Acceptance, GenerationFailure, generate_track, nearest_specs

# A sweep miss: 60 m at w = 0.8 m in 12 × 9 m fills 0.87 of L_max.
LONG = TrackSpec(name="long-in-small-hall", lap_length_m=60, corridor_width_m=0.8, hall_x_m=12, hall_y_m=9)


def test_a_failure_carries_suggestions_that_build_as_suggested():
    out = generate_track(LONG, seed=0)
    assert isinstance(out, GenerationFailure) and out.nearest is not None
    sugg = out.nearest.suggestions
    assert sugg, out.nearest
    fields = {s.field for s in sugg}
    assert "lap_length_m" in fields and "hall" in fields
    for s in sugg:
        # One field changed at a time; every other field as requested.
        same = {k for k in TrackSpec.model_fields if getattr(s.spec, k) == getattr(LONG, k)}
        assert set(TrackSpec.model_fields) - same == set(s.changes), s
        again = generate_track(s.spec, seed=s.seed, suggest_timeout=None)
        assert isinstance(again, Acceptance), (s.text(), again.summary())
        assert again.candidates_tried == s.candidate_index + 1
    lap = next(s for s in sugg if s.field == "lap_length_m")
    assert lap.spec.lap_length_m < 60 and lap.text().startswith(
        f"lap_length_m = {lap.spec.lap_length_m:g} (built with seed"
    )
    hall = next(s for s in sugg if s.field == "hall")
    assert hall.spec.hall_x_m > 12 and abs(hall.spec.hall_x_m / hall.spec.hall_y_m - 12 / 9) < 0.05
    assert "not proofs" in out.summary()


def test_the_search_is_deterministic_and_can_be_skipped():
    a, b = nearest_specs(LONG, 0), nearest_specs(LONG, 0)
    assert [s.model_dump() for s in a.suggestions] == [s.model_dump() for s in b.suggestions]
    out = generate_track(LONG, seed=0, suggest_timeout=None)
    assert isinstance(out, GenerationFailure) and out.nearest is None


def test_cli_prints_try_lines_and_json_carries_the_specs(tmp_path, capsys):
    spec = tmp_path / "spec.json"
    spec.write_text(LONG.model_dump_json())
    assert main(["generate", "--spec", str(spec), "-o", str(tmp_path / "o")]) == 4
    err = capsys.readouterr().err
    assert "try: lap_length_m = " in err and "(built with seed " in err and "not proofs" in err
    assert main(["generate", "--spec", str(spec), "-o", str(tmp_path / "o"), "--json"]) == 4
    summary = json.loads(capsys.readouterr().out)
    near = summary["nearest"]
    assert near["suggestions"] and "not proofs" in near["note"]
    first = near["suggestions"][0]
    rerun = tmp_path / "again.json"
    rerun.write_text(json.dumps(first["spec"]))
    assert main(["generate", "--spec", str(rerun), "--seed", str(first["seed"]), "-o", str(tmp_path / "a")]) == 0
    capsys.readouterr()
    assert main(["generate", "--spec", str(spec), "-o", str(tmp_path / "o"), "--json", "--no-suggest"]) == 4
    assert "nearest" not in json.loads(capsys.readouterr().out)


@pytest.mark.slow
def test_sweep_failures_get_a_suggestion_that_builds():
    """The issue's 'done when' on a tenth of the 360-spec sweep (every tenth spec, so
    about eight generation failures; the whole sweep is ``bench constructors --sweep
    --suggest``, recorded in BENCHMARKS.md): each generation failure has at least one
    suggestion accepted when run as suggested (the bench re-runs every suggestion)."""
    result = run_sweep(load_sweep_file()[::10], jobs=2, progress=False, suggest=True)
    failed = [m for m in result.misses if m.outcome == "failed"]
    assert failed, "the sample has no generation failures left to suggest for"
    lacking = [m.spec for m in failed if not m.suggestions_built]
    assert not lacking, lacking
    assert result.misses_with_suggestion == len(failed)


def test_the_core_result_is_typed_and_read_only():
    from roboracer_arena import _core

    found = _core.nearest_specs(LONG, None, 0, 20.0)
    assert isinstance(found, _core.NearestFound) and found.probes >= 1 and isinstance(found.exhausted, bool)
    assert found.suggestions and all(isinstance(s, _core.NearestSuggestion) for s in found.suggestions)
    first = found.suggestions[0]
    assert first.field in ("lap_length_m", "hall", "corridor_width_m", "features")
    assert TrackSpec.model_validate(first.spec).lap_length_m > 0 and first.candidate_index >= 0
    with pytest.raises(AttributeError):
        found.probes = 0  # type: ignore[misc]
