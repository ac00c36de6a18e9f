"""The generator finds small tracks (issue 15): short laps, narrow corridors and features
in small halls, where the lattice's one-pitch loop cannot fit, are built by the ring
constructor and judged by the same raster validator; the sweep's spec file is the one
``sweep_specs()`` defines."""

import pytest
from independent_measure import assert_independently_valid

from benchmarks.constructor_sweep import SWEEP_FILE, load_sweep_file, obvious_construction, sweep_specs
from roboracer_arena import TrackSpec
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


@pytest.mark.parametrize(
    "spec",
    [
        TrackSpec(name="chicane-in-20m", lap_length_m=20, corridor_width_m=1.5, hall_x_m=20, hall_y_m=15, chicanes=1),
        TrackSpec(
            name="three-features-in-20m",
            lap_length_m=20,
            corridor_width_m=1.5,
            hall_x_m=12,
            hall_y_m=9,
            hairpins=1,
            chicanes=1,
            sweepers=1,
            direction="clockwise",
        ),
        TrackSpec(
            name="wide-hairpin-in-20m", lap_length_m=20, corridor_width_m=2.0, hall_x_m=16, hall_y_m=12, hairpins=1
        ),
        TrackSpec(
            name="wide-sweeper-in-20m", lap_length_m=20, corridor_width_m=2.0, hall_x_m=12, hall_y_m=9, sweepers=1
        ),
        # The largest rounded rectangle in the hall is 0.6 % short of L: the ring takes it.
        TrackSpec(
            name="sweeper-fills-12x9", lap_length_m=30, corridor_width_m=1.2, hall_x_m=12, hall_y_m=9, sweepers=1
        ),
    ],
    ids=lambda s: s.name,
)
@pytest.mark.parametrize("seed", [0, 1])
def test_short_laps_with_features_are_accepted_and_independently_valid(spec, seed, tmp_path):
    """Laps too short for the ring's four spaced corners plus the features (the polygon
    constructor), and a lap just above the hall's rectangle (the ring's 1 % slack)."""
    assert obvious_construction(spec)
    out = generate_track(spec, seed=seed)  # a screen rejection would fail the next line
    assert isinstance(out, Acceptance), out.summary()  # the validator counted the features
    assert_independently_valid(out, tmp_path)


def test_obvious_construction_is_a_rounded_rectangle_of_length_l_in_the_hall():
    # 12 × 9 m hall less 2 × 0.5 m margins and a 1.3 m corridor (w + 2 t_w): a 9.7 × 6.7 m
    # centreline box; r_c = 0.9 m → 2 (9.7 + 6.7) − 4 (2 − π/2) 0.9 = 31.25 m.
    assert obvious_construction(ISSUE_CASE)
    assert obvious_construction(ISSUE_CASE.model_copy(update={"lap_length_m": 31.2}))
    assert not obvious_construction(ISSUE_CASE.model_copy(update={"lap_length_m": 31.3}))
    assert not obvious_construction(TrackSpec(lap_length_m=200.0))


def test_shipped_sweep_file_is_the_defined_sweep():
    shipped = load_sweep_file()
    assert len(shipped) >= 300, SWEEP_FILE
    assert [s.model_dump() for s in shipped] == [s.model_dump() for s in sweep_specs()]
    assert all(screen(s).passed for s in shipped[::17])


def test_sweep_runner_counts_and_writes_remeasurable_maps(tmp_path):
    from independent_measure import problems

    from benchmarks.constructor_sweep import run_sweep

    specs = [ISSUE_CASE.model_copy(update={"name": "issue-case"}), TrackSpec(name="paper-200m", lap_length_m=200.0)]
    result = run_sweep(specs, maps=tmp_path, progress=False)
    assert result.specs == 2 and result.accepted == 1
    assert [m.spec for m in result.misses] == ["paper-200m"] and result.misses[0].outcome == "rejected"
    assert result.by_hall == {"12x9": "1/1", "20x15": "0/1"}
    assert (result.obvious_accepted, result.obvious_specs) == (1, 1)
    assert problems(ISSUE_CASE, tmp_path / "issue-case" / "map.yaml") == []
    # Fill bands (issue 28): 30 m of L_max 53.3 m (w = 1 m, 12 × 9 m) is 0.56, in the
    # practical region; the 200 m lap is beyond L_max (the last band holds it).
    assert result.rows[0].fill == pytest.approx(30 / (11 * 8 / 1.65))
    assert result.by_fill == {"0.4-0.6": "1/1", "0.8-1": "0/1"}
    assert (result.practical_accepted, result.practical_specs) == (1, 1)
    assert result.misses_with_suggestion is None
