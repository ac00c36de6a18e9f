"""Hostile input to generation (issue 10): a time budget, Ctrl-C, overflow-sized specs,
bad spec values and map frames all end in a typed outcome or a typed error, promptly."""

import math
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from roboracer_arena import TrackSpec
from roboracer_arena.errors import ArenaError, InvalidArgumentError, SpecError
from roboracer_arena.generate import Acceptance, GenerationFailure, Rejection, generate_track, validate_map
from roboracer_arena.maps.occupancy import OccupancyMap


def test_time_budget_stops_a_2km_search_promptly():
    t0 = time.perf_counter()
    out = generate_track(TrackSpec(lap_length_m=2000, hall_x_m=100, hall_y_m=100), timeout=0.5, suggest_timeout=None)
    assert time.perf_counter() - t0 < 5
    assert isinstance(out, GenerationFailure) and out.stopped == "timeout"
    assert "time budget" in out.summary()


@pytest.mark.parametrize("bad", [0, -1, math.nan, math.inf, True, "5"])
def test_bad_timeouts_are_refused(bad):
    with pytest.raises(InvalidArgumentError, match="timeout"):
        generate_track(TrackSpec(), timeout=bad)


def test_a_hall_over_the_raster_limit_is_refused_promptly():
    t0 = time.perf_counter()
    with pytest.raises(SpecError, match=r"hall_x_m × hall_y_m: .* allows at most"):
        generate_track(TrackSpec(lap_length_m=2000, hall_x_m=400, hall_y_m=400))
    assert time.perf_counter() - t0 < 2


@pytest.mark.parametrize("size", [1e9, 1e12, 1e308])
def test_huge_halls_are_refused_by_the_schema_and_by_the_core(size):
    from roboracer_arena import _core
    from roboracer_arena.config.constructor import ConstructorConfig

    with pytest.raises(SpecError, match="hall_x_m"):
        TrackSpec.from_dict({"lap_length_m": 60, "hall_x_m": size, "hall_y_m": size})
    # The core holds the schema's range itself (Rust callers, or a spec that skipped the schema).
    spec = {**TrackSpec().model_dump(), "hall_x_m": size, "hall_y_m": size}
    t0 = time.perf_counter()
    with pytest.raises(SpecError, match="hall_x_m"):
        _core.generate_lattice(spec, ConstructorConfig(), 0)
    assert time.perf_counter() - t0 < 2


@pytest.mark.parametrize("field", ["lap_length_m", "corridor_width_m", "hall_x_m", "min_radius_m", "hairpins"])
@pytest.mark.parametrize("value", [math.nan, math.inf, -1.0, True])
def test_bad_spec_values_are_refused_naming_the_field(field, value):
    with pytest.raises(SpecError, match=field):
        TrackSpec.from_dict({field: value})


@pytest.mark.parametrize(
    "resolution, origin",
    [
        (1e-300, (0.0, 0.0, 0.0)),
        (0.05, (1e300, -1e300, 0.0)),
        (math.nan, (0.0, 0.0, 0.0)),
        (1e300, (0.0, 0.0, 0.0)),
        (0.05, (0.0, math.inf, 0.0)),
    ],
)
def test_validate_refuses_unmeasurable_frames(resolution, origin):
    data = np.full((40, 40), 254, np.uint8)
    with pytest.raises(InvalidArgumentError, match="resolution|origin"):
        validate_map(OccupancyMap(data, resolution, origin), TrackSpec())


def test_ctrl_c_stops_generation_promptly():
    code = (
        "from roboracer_arena import TrackSpec\n"
        "from roboracer_arena.generate import generate_track\n"
        "print('go', flush=True)\n"
        "generate_track(TrackSpec(lap_length_m=2000, hall_x_m=100, hall_y_m=100), timeout=None)\n"
    )
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "go"
    time.sleep(0.5)
    t0 = time.perf_counter()
    p.send_signal(signal.SIGINT)
    try:
        _, err = p.communicate(timeout=10)
    finally:
        p.kill()
    assert time.perf_counter() - t0 < 5
    assert "KeyboardInterrupt" in err and "PanicException" not in err


spec_values = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-5, 10**6), st.booleans())


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    lap=spec_values,
    width=spec_values,
    hx=spec_values,
    hy=spec_values,
    h=st.integers(0, 6),
    c=st.integers(0, 3),
    s=st.integers(0, 3),
)
def test_any_spec_gives_a_typed_outcome_or_a_typed_error(lap, width, hx, hy, h, c, s):
    try:
        spec = TrackSpec.from_dict(
            {
                "lap_length_m": lap,
                "corridor_width_m": width,
                "hall_x_m": hx,
                "hall_y_m": hy,
                "hairpins": h,
                "chicanes": c,
                "sweepers": s,
            }
        )
    except SpecError:
        return
    try:
        out = generate_track(spec, timeout=1.0)
    except ArenaError:
        return
    assert isinstance(out, (Acceptance, Rejection, GenerationFailure))
    if isinstance(out, Acceptance):
        assert out.report.valid
