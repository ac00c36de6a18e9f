"""A spec that passes the screen but cannot be built ends in GenerationFailure with the
candidates tried and a reason histogram — never in a map."""

import importlib.util

import pytest

from roboracer_arena import TrackSpec
from roboracer_arena.cli import EXIT_BAD_INPUT, main
from roboracer_arena.errors import InvalidArgumentError
from roboracer_arena.generate import GenerationFailure, generate_track, screen

# r_req = 0.1 m makes a hairpin cheap for the screen (Σℓ_min = 13.9 m ≤ 20.2 m), but the
# corridor pitch p = 2.15 m leaves room for ~18 lattice edges: 12 hairpins cannot fit.
IMPOSSIBLE = TrackSpec(name="twelve-hairpins-40m", lap_length_m=40, hairpins=12, min_radius_m=0.1)


def test_impossible_counts_pass_the_screen_then_fail_generation():
    assert screen(IMPOSSIBLE).passed
    out = generate_track(IMPOSSIBLE, seed=0)
    assert isinstance(out, GenerationFailure)
    assert out.candidates_tried == 800
    assert sum(out.reasons.values()) == 800 and all(v > 0 for v in out.reasons.values())
    assert not hasattr(out, "map")
    assert "800 candidate(s)" in out.summary()


def test_cli_exit_4_writes_no_map(tmp_path, capsys):
    spec = tmp_path / "spec.json"
    spec.write_text(IMPOSSIBLE.model_dump_json())
    outdir = tmp_path / "out"
    code = main(["generate", "--spec", str(spec), "-o", str(outdir), "--json"])
    assert code == 4
    import json

    summary = json.loads(capsys.readouterr().out)
    assert summary["outcome"] == "failed" and summary["candidates_tried"] == 800
    assert sum(summary["reasons"].values()) == 800
    assert not outdir.exists() or not any(outdir.iterdir())


@pytest.mark.parametrize("constructor", ["de", "random"])
def test_the_paper_baselines_left_the_package_with_a_pointer(constructor, tmp_path, capsys):
    """The DE / random baselines live in the checkout's benchmarks/ now: generate_track and
    ``generate --constructor`` name where they went, and the package has no copy."""
    spec = TrackSpec(name="small", lap_length_m=40, hall_x_m=15, hall_y_m=12, hairpins=1)
    with pytest.raises(InvalidArgumentError, match=f"python -m benchmarks constructors --constructors {constructor}"):
        generate_track(spec, constructor=constructor)
    argv = ["generate", "a 40 m lap in a 15 by 12 m hall", "--constructor", constructor, "-o", str(tmp_path / "o")]
    assert main(argv) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert "python -m benchmarks" in err.strip().splitlines()[-1]  # after the parse it prints
    assert importlib.util.find_spec("roboracer_arena.generate.baselines") is None
