"""The generator finds small tracks (issue 15): short laps, narrow corridors and features
in small halls, where the lattice's one-pitch loop cannot fit, are built by the ring
constructor and judged by the same raster validator; the sweep's spec file is the one
``sweep_specs()`` defines."""

import pytest
from independent_measure import assert_independently_valid

from roboracer_arena import TrackSpec
from roboracer_arena.bench.constructor_sweep import SWEEP_FILE, load_sweep_file, sweep_specs
from roboracer_arena.generate import Acceptance, generate_track, screen

ISSUE_CASE = TrackSpec(lap_length_m=30, corridor_width_m=1.0, hall_x_m=12, hall_y_m=9, sweepers=1)


@pytest.mark.parametrize("seed", [0, 1, 2, 3, 11])
def test_issue_case_30m_1m_12x9_one_sweeper_is_accepted(seed, tmp_path):
    out = generate_track(ISSUE_CASE, seed=seed)
    assert isinstance(out, Acceptance), out.summary()
    assert [f.kind for f in out.report.features] == ["sweeper"]
    assert_independently_valid(out, tmp_path)


@pytest.mark.parametrize(
    "spec",
    [
        TrackSpec(name="oval-25m-narrow", lap_length_m=25, corridor_width_m=0.8, hall_x_m=10, hall_y_m=8),
        TrackSpec(
            name="hairpin-chicane-13x10",
            lap_length_m=40,
            corridor_width_m=1.0,
            hall_x_m=13,
            hall_y_m=10,
            hairpins=1,
            chicanes=1,
            direction="clockwise",
        ),
        TrackSpec(name="long-in-16x12", lap_length_m=45, corridor_width_m=1.5, hall_x_m=16, hall_y_m=12),
    ],
    ids=lambda s: s.name,
)
def test_small_hall_specs_are_accepted_and_independently_valid(spec, tmp_path):
    assert screen(spec).passed
    out = generate_track(spec, seed=0)
    assert isinstance(out, Acceptance), out.summary()
    assert_independently_valid(out, tmp_path)


def test_shipped_sweep_file_is_the_defined_sweep():
    shipped = load_sweep_file()
    assert len(shipped) >= 300, SWEEP_FILE
    assert [s.model_dump() for s in shipped] == [s.model_dump() for s in sweep_specs()]
    assert all(screen(s).passed for s in shipped[::17])


def test_sweep_runner_counts_and_writes_remeasurable_maps(tmp_path):
    from independent_measure import problems

    from roboracer_arena.bench.constructor_sweep import run_sweep

    specs = [ISSUE_CASE.model_copy(update={"name": "issue-case"}), TrackSpec(name="paper-200m", lap_length_m=200.0)]
    result = run_sweep(specs, maps=tmp_path, progress=False)
    assert result["specs"] == 2 and result["accepted"] == 1
    assert [m["spec"] for m in result["misses"]] == ["paper-200m"] and result["misses"][0]["outcome"] == "rejected"
    assert result["by_hall"] == {"12x9": "1/1", "20x15": "0/1"}
    assert problems(ISSUE_CASE, tmp_path / "issue-case" / "map.yaml") == []
