"""The core's reports cross as typed, read-only objects (issue 37): ``screen``,
``derived_geometry``, ``validate_map``, ``analyse_curve`` and the lattice outcome's
``report`` / ``screen`` are frozen mirrors of the core's structs (nested ones too), with
exactly the pydantic models' fields; the models built from their attributes write the
same JSON as the objects hold."""

from __future__ import annotations

import json
import pickle
import types
from typing import Any

import numpy as np
import pytest

from roboracer_arena import TrackSpec, _core
from roboracer_arena.config.constructor import ConstructorConfig
from roboracer_arena.generate import pipeline
from roboracer_arena.generate.outcomes import Acceptance
from roboracer_arena.generate.report import (
    Check,
    CurveAnalysis,
    DerivedGeometry,
    FeatureAt,
    Measurements,
    ScreenResult,
    Turn,
    ValidationReport,
)

SMALL = TrackSpec(lap_length_m=45, corridor_width_m=1.2, hairpins=1)
#: A lap far longer than its hall holds: the screen proves it impossible.
IMPOSSIBLE = TrackSpec(lap_length_m=400, hall_x_m=10, hall_y_m=10)

PAIRS = [
    (_core.ScreenResult, ScreenResult),
    (_core.Derived, DerivedGeometry),
    (_core.ValidationReport, ValidationReport),
    (_core.Check, Check),
    (_core.Measurements, Measurements),
    (_core.FeatureAt, FeatureAt),
    (_core.CurveAnalysis, CurveAnalysis),
    (_core.Turn, Turn),
]


def fields(cls: type) -> set[str]:
    """A core class's read-only attributes (``get_all``)."""
    return {n for n, v in vars(cls).items() if isinstance(v, types.GetSetDescriptorType)}


def plain(value: Any) -> Any:
    """A core report as plain JSON values, field by field (what the old dicts held)."""
    if type(value).__module__ == "roboracer_arena._core":
        return {f: plain(getattr(value, f)) for f in fields(type(value))}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    return value


@pytest.fixture(scope="module")
def reports() -> dict[str, Any]:
    """One of each report, from each door that returns one."""
    acc = _core.generate_lattice(SMALL, ConstructorConfig(), 0)
    data, origin = acc.map
    validated, _ = _core.validate_map(data, ConstructorConfig().resolution_m, origin, SMALL)
    d = _core.derived_geometry(SMALL)
    curve = _core.analyse_curve(acc.centreline, d.corner_radius, np.pi * d.pitch / 2)
    return {
        "screen": _core.screen(SMALL),
        "rejected": _core.generate_lattice(IMPOSSIBLE, None, 0).screen,
        "report": acc.report,
        "validated": validated,
        "curve": curve,
        "derived": d,
    }


@pytest.mark.parametrize(("core", "model"), PAIRS, ids=lambda c: c.__name__)
def test_each_core_report_has_exactly_its_models_fields(core, model):
    assert fields(core) == set(model.model_fields)


def test_every_door_returns_the_typed_object(reports):
    assert isinstance(reports["screen"], _core.ScreenResult) and reports["screen"].passed
    assert isinstance(reports["rejected"], _core.ScreenResult) and not reports["rejected"].passed
    for r in (reports["report"], reports["validated"]):
        assert isinstance(r, _core.ValidationReport) and r.valid
        assert all(isinstance(c, _core.Check) for c in r.checks)
        assert isinstance(r.measurements, _core.Measurements) and r.measurements.hairpins == 1
        assert [f.kind for f in r.features] == ["hairpin"] and isinstance(r.features[0], _core.FeatureAt)
        assert isinstance(r.measurements.extent_m, tuple) and len(r.measurements.extent_m) == 2
    c = reports["curve"]
    assert isinstance(c, _core.CurveAnalysis) and c.turns and isinstance(c.turns[0], _core.Turn)
    assert [f.kind for f in c.features] == ["hairpin"] and isinstance(c.features[0], _core.FeatureAt)


@pytest.mark.parametrize(
    ("name", "path"),
    [
        ("screen", "passed"),
        ("report", "valid"),
        ("report", "checks.0.passed"),
        ("report", "measurements.hairpins"),
        ("report", "features.0.kind"),
        ("curve", "length_m"),
        ("curve", "turns.0.angle_rad"),
        ("curve", "self_clearance_m"),
    ],
)
def test_reports_are_read_only(reports, name, path):
    *parents, last = path.split(".")
    obj = reports[name]
    for p in parents:
        obj = obj[int(p)] if p.isdigit() else getattr(obj, p)
    with pytest.raises(AttributeError):
        setattr(obj, last, getattr(obj, last))


def test_a_curve_without_a_non_local_pass_has_no_clearance():
    """The core says None itself (it used to send -1 for JSON's sake)."""
    t = np.linspace(0.0, 2 * np.pi, 400, endpoint=False)
    c = _core.analyse_curve(np.c_[5 * np.cos(t), 5 * np.sin(t)], 1.0, 100.0)
    assert c.self_clearance_m is None
    assert CurveAnalysis.model_validate(c, from_attributes=True).self_clearance_m is None


def test_the_repr_names_every_field(reports):
    r = reports["report"]
    text = repr(r)
    assert text.startswith("ValidationReport(valid=True, checks=[Check(name='corridor'")
    assert all(f"{f}=" in text for f in fields(_core.Measurements) | fields(_core.FeatureAt))
    assert repr(reports["screen"]).startswith("ScreenResult(passed=True, violations=[], r_min_m=")


def test_reports_pickle_to_equal_objects(reports):
    for r in reports.values():
        back = pickle.loads(pickle.dumps(r))
        assert type(back) is type(r) and plain(back) == plain(r) and repr(back) == repr(r)


@pytest.mark.parametrize(
    ("name", "model"),
    [
        ("screen", ScreenResult),
        ("rejected", ScreenResult),
        ("report", ValidationReport),
        ("validated", ValidationReport),
        ("curve", CurveAnalysis),
        ("derived", DerivedGeometry),
    ],
)
def test_the_models_write_exactly_what_the_core_objects_hold(reports, name, model):
    """The JSON outputs (``report.json``, ``validate --json``, ``generate --json``) dump the
    models (their field order is the key order); built from the objects' attributes they
    add, drop and change no value."""
    obj = reports[name]
    built = model.model_validate(obj, from_attributes=True)
    assert json.dumps(built.model_dump(mode="json"), sort_keys=True) == json.dumps(plain(obj), sort_keys=True)


def test_the_pipeline_hands_out_the_models(reports):
    s = pipeline.screen(SMALL)
    assert isinstance(s, ScreenResult) and s == ScreenResult.model_validate(reports["screen"], from_attributes=True)
    acc = pipeline.generate_track(SMALL, seed=0)
    assert isinstance(acc, Acceptance) and isinstance(acc.report, ValidationReport)
    report, _ = pipeline.validate_map(acc.map, SMALL)
    assert isinstance(report, ValidationReport) and report == acc.report
