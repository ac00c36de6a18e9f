"""The core's ``generate_lattice`` screens once and returns a typed, read-only
``LatticeOutcome`` (issue 37): the pipeline no longer runs the screen itself, and a
rejection carries the core's own screen."""

from __future__ import annotations

import numpy as np
import pytest

from roboracer_arena import TrackSpec, _core, generate_track
from roboracer_arena.config.constructor import ConstructorConfig
from roboracer_arena.generate import pipeline
from roboracer_arena.generate.outcomes import Acceptance, Rejection
from roboracer_arena.generate.report import ScreenResult

SMALL = TrackSpec(lap_length_m=45, corridor_width_m=1.2, hairpins=1)
#: A lap far longer than its hall holds: the screen proves it impossible.
IMPOSSIBLE = TrackSpec(lap_length_m=400, hall_x_m=10, hall_y_m=10)


@pytest.fixture
def no_python_screen(monkeypatch):
    """Fail any screen run outside the core's generate."""

    def refuse(*_a, **_k):
        raise AssertionError("the pipeline ran the screen itself")

    monkeypatch.setattr(pipeline._core, "screen", refuse)


def test_an_acceptance_screens_only_in_the_core(no_python_screen):
    out = generate_track(SMALL, seed=0)
    assert isinstance(out, Acceptance) and out.report.valid


def test_a_rejection_carries_the_core_screen(no_python_screen):
    out = generate_track(IMPOSSIBLE, seed=0)
    assert isinstance(out, Rejection)
    assert out.violations and not out.screen.passed


def test_the_outcome_is_typed_and_read_only():
    acc = _core.generate_lattice(SMALL, ConstructorConfig(), 0)
    assert acc.kind == "accepted" and acc.tried >= 1 and acc.candidate_index is not None
    data, origin = acc.map
    assert data.dtype == np.uint8 and len(origin) == 3 and acc.centreline.shape[1] == 2
    assert (
        isinstance(acc.report, _core.ValidationReport)
        and acc.report.valid
        and acc.pitch_m > 0
        and acc.screen is None
        and acc.reasons == {}
    )
    with pytest.raises(AttributeError):
        acc.kind = "rejected"  # type: ignore[misc]

    rej = _core.generate_lattice(IMPOSSIBLE, None, 0)
    assert rej.kind == "rejected" and rej.map is None and rej.report is None and rej.tried == 0
    assert isinstance(rej.screen, _core.ScreenResult)
    assert not ScreenResult.model_validate(rej.screen, from_attributes=True).passed


def test_a_failure_names_its_reasons_and_what_stopped_it():
    out = _core.generate_lattice(SMALL, None, 0, 1e-9)
    assert out.kind == "failed" and out.map is None and out.screen is None and out.report is None
    assert out.stopped == "timeout" and all(isinstance(n, int) for n in out.reasons.values())


def test_the_constructor_alone_returns_a_typed_construction():
    built = _core.construct_lattice(SMALL, ConstructorConfig(), 0)
    assert built.tried >= 1 and built.centreline.shape[1] == 2 and built.pitch_m > 0
    assert built.reasons == {} and built.stopped is None
    with pytest.raises(AttributeError):
        built.tried = 0  # type: ignore[misc]
    none = _core.construct_lattice(SMALL, ConstructorConfig(max_candidates=1), 0, 1e-9)
    assert none.centreline is None and none.pitch_m is None
    assert none.stopped in (None, "timeout") and all(isinstance(n, int) for n in none.reasons.values())


def test_derived_geometry_is_typed_and_read_only():
    d = _core.derived_geometry(SMALL)
    assert isinstance(d, _core.Derived) and d.s_min == max(d.pitch, 2 * d.r_min) and d.corner_radius == d.s_min / 2
    assert pipeline.derived_geometry(SMALL).l_max == d.l_max
    with pytest.raises(AttributeError):
        d.pitch = 0.0  # type: ignore[misc]
