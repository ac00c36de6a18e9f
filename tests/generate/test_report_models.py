"""The typed results of the generator's core calls: every field the core sends is a
model field (``extra="forbid"``), so drift between the Rust structs and the models fails here."""

from __future__ import annotations

import json

import pytest
from pydantic import ValidationError

from roboracer_arena import TrackSpec, _core
from roboracer_arena.constructor_config import ConstructorConfig
from roboracer_arena.generate import (
    Acceptance,
    DerivedGeometry,
    ScreenResult,
    ValidationReport,
    derived_geometry,
    generate_track,
    screen,
)

SPEC = TrackSpec(lap_length_m=45, corridor_width_m=1.2, hairpins=1)


def _raw(fn) -> dict:
    return json.loads(fn(SPEC.model_dump_json(), ConstructorConfig().model_dump_json()))


@pytest.mark.parametrize(("fn", "model"), [(_core.screen, ScreenResult), (_core.derived_geometry, DerivedGeometry)])
def test_models_hold_exactly_the_fields_the_core_sends(fn, model):
    raw = _raw(fn)
    assert set(raw) == set(model.model_fields)
    with pytest.raises(ValidationError):
        model.model_validate({**raw, "unexpected": 1})


def test_an_acceptance_carries_a_typed_report_whose_numbers_match_its_checks():
    out = generate_track(SPEC, seed=0)
    assert isinstance(out, Acceptance) and isinstance(out.report, ValidationReport)
    r = out.report
    assert r.valid and not r.failed() and r.measurements is not None
    assert r.measurements.hairpins == 1 == sum(f.kind == "hairpin" for f in r.features)
    lap = next(c for c in r.checks if c.name == "lap_length")
    assert f"{r.measurements.lap_length_m:.2f} m" == lap.measured
    assert lap.line().startswith("ok  lap_length")
    with pytest.raises(ValidationError):  # frozen: a report cannot be edited after the fact
        r.__setattr__("valid", False)


def test_screen_and_derived_geometry_agree():
    s, d = screen(SPEC), derived_geometry(SPEC)
    assert s.passed and s.pitch_m == d.pitch and s.l_max_m == d.l_max and s.r_min_m == d.r_min
