"""Every accepted map passes an independent re-measurement of the written PNG/YAML
(``independent_measure``: Pillow + numpy + scipy.ndimage, no code shared with the Rust
validator)."""

import json

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from independent_measure import assert_independently_valid

from benchmarks import bench_data
from roboracer_arena import TrackSpec
from roboracer_arena.generate import Acceptance, GenerationFailure, generate_track, screen


def _bench_specs() -> list[TrackSpec]:
    lines = bench_data("specs.jsonl").read_text().splitlines()
    return [TrackSpec.from_dict(json.loads(s)) for s in lines if s.strip()]


@pytest.mark.parametrize("spec", [s for s in _bench_specs() if screen(s).passed], ids=lambda s: s.name)
def test_bench_specs_accepted_maps_remeasure(spec, tmp_path):
    out = generate_track(spec, seed=0)
    assert isinstance(out, Acceptance), out.summary()
    assert_independently_valid(out, tmp_path)


specs = st.builds(
    TrackSpec,
    lap_length_m=st.floats(25, 70),
    corridor_width_m=st.sampled_from([1.2, 1.5, 1.8]),
    hall_x_m=st.floats(14, 24),
    hall_y_m=st.floats(10, 18),
    direction=st.sampled_from(["clockwise", "counterclockwise"]),
    hairpins=st.integers(0, 3),
    chicanes=st.integers(0, 2),
    sweepers=st.integers(0, 2),
)


@settings(
    max_examples=30,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.filter_too_much],
)
@given(spec=specs, seed=st.integers(0, 2**32 - 1))
def test_every_accepted_map_passes_independent_remeasurement(spec, seed, tmp_path_factory):
    assume(screen(spec).passed)
    out = generate_track(spec, seed=seed)
    if isinstance(out, GenerationFailure):
        assert out.candidates_tried == 800 and sum(out.reasons.values()) == 800
        return
    assert isinstance(out, Acceptance) and out.report.valid
    assert_independently_valid(out, tmp_path_factory.mktemp("map"))
