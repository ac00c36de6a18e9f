"""The admissibility screen's worked examples (Eqs. 1–2) and the constructor constants."""

import pytest

from roboracer_arena import TrackSpec
from roboracer_arena.config.constructor import ConstructorConfig
from roboracer_arena.generate import Rejection, derived_geometry, generate_track, screen


def test_defaults_give_the_papers_pitch_and_hall_margin():
    cfg = ConstructorConfig()
    assert cfg.hall_margin_m == 0.5
    assert cfg.pitch(1.5) == pytest.approx(2.15)
    assert derived_geometry(TrackSpec()).pitch == pytest.approx(2.15)
    assert cfg.max_candidates == 800


def test_200m_in_20x15_is_rejected_naming_lmax():
    out = generate_track(TrackSpec(lap_length_m=200, hall_x_m=20, hall_y_m=15))
    assert isinstance(out, Rejection)
    assert out.screen.l_max_m == pytest.approx(123.72, abs=0.01)
    assert out.violations == ["L = 200.0 m > L_max = 123.7 m for a 20×15 m hall (p = 2.15 m, m_h = 0.5 m)"]
    assert "L_max = 123.7 m" in out.summary()


def test_five_hairpins_in_45m_clear_the_budget_by_077_and_six_do_not():
    r = screen(TrackSpec(lap_length_m=45, hairpins=5))
    assert r.passed
    assert r.feature_budget_m - r.feature_length_m == pytest.approx(0.77, abs=0.005)
    r6 = screen(TrackSpec(lap_length_m=45, hairpins=6))
    assert not r6.passed and "0.70·(1 − 0.28)·L" in r6.violations[0]


def test_lap_shorter_than_a_circle_of_rmin_is_rejected():
    r = screen(TrackSpec(lap_length_m=5.0))
    assert not r.passed and "2π r_min" in r.violations[0]
    assert r.r_min_m == pytest.approx(1.125)  # max(0.9, 0.75 · 1.5)


def test_requested_radius_overrides_the_default_rmin():
    assert screen(TrackSpec(min_radius_m=2.0)).r_min_m == 2.0
    assert screen(TrackSpec(corridor_width_m=1.0)).r_min_m == 0.9


def test_json_schema_export_has_the_twelve_fields_and_the_cap():
    schema = TrackSpec.json_schema()
    assert len(schema["properties"]) == 13 and "max_straight_m" in schema["properties"]
    assert schema["additionalProperties"] is False
    assert set(schema["properties"]["direction"]["enum"]) == {"clockwise", "counterclockwise"}
    lap = schema["properties"]["lap_length_m"]
    assert (lap["minimum"], lap["maximum"]) == (1, 2000)  # the one range, shared with the parser
