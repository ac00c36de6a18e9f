"""A spec that passes the screen but cannot be built ends in GenerationFailure with the
candidates tried and a reason histogram — never in a map."""

from roboracer_arena import TrackSpec
from roboracer_arena.cli import main
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


def test_baselines_never_return_an_invalid_map():
    spec = TrackSpec(name="random-small", lap_length_m=40, hall_x_m=15, hall_y_m=12, hairpins=1)
    for seed in range(3):
        out = generate_track(spec, seed=seed, constructor="random")
        if isinstance(out, GenerationFailure):
            assert out.candidates_tried == 1 and out.reasons
            assert out.built_invalid_report is None or not out.built_invalid_report.valid
        else:
            assert out.report.valid
