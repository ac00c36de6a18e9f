"""The typed results of the generator's core calls: every field the core sends is a
model field (``extra="forbid"``), so drift between the Rust structs and the models fails here."""

from __future__ import annotations

import numpy as np
import pytest
from pydantic import ValidationError

from roboracer_arena import TrackSpec, _core
from roboracer_arena.config.constructor import ConstructorConfig
from roboracer_arena.generate import (
    Acceptance,
    CurveAnalysis,
    DerivedGeometry,
    ScreenResult,
    ValidationReport,
    derived_geometry,
    generate_track,
    screen,
)

SPEC = TrackSpec(lap_length_m=45, corridor_width_m=1.2, hairpins=1)


def _raw(fn) -> dict:
    """The core's result as field -> value (a typed core object's public attributes)."""
    out = fn(SPEC, ConstructorConfig())
    if isinstance(out, dict):
        return out
    return {k: getattr(out, k) for k in dir(out) if not k.startswith("_")}


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


def test_curve_analysis_of_an_ellipse():
    t = np.linspace(0.0, 2 * np.pi, 2000, endpoint=False)
    a, b = 10.0, 6.0
    c = CurveAnalysis.of(np.c_[a * np.cos(t), b * np.sin(t)], corner_radius=1.1, exclude_m=3.0)
    assert c.min_radius_m == pytest.approx(b * b / a, rel=0.02)  # at the ends of the major axis
    assert c.total_turn_rad == pytest.approx(2 * np.pi, rel=1e-6)  # counter-clockwise
    assert c.length_m == pytest.approx(51.05, abs=0.05) and c.features == ()
    # nearest point more than exclude_m of arc away: on a smooth convex curve, a chord of about that length
    assert c.self_clearance_m == pytest.approx(3.0, rel=0.02)
