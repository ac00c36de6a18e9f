"""Issue 38, class F: every pydantic field that takes a number refuses a string or a
bool, optional (``float | None``) and container fields included: ``{"max_straight_m":
"5"}`` was accepted while ``{"lap_length_m": "40"}`` was refused."""

from __future__ import annotations

import pytest
from pydantic import ValidationError

from roboracer_arena.catalog.entry import OpenMap
from roboracer_arena.config.build import BuildConfig
from roboracer_arena.foundation.strict import NumbersAreNumbers
from roboracer_arena.spec import TrackSpec
from roboracer_arena.usd.metadata import StageMetadata


class Sample(NumbersAreNumbers):
    a: float | None = None
    b: int | None = None
    c: tuple[float, float] | None = None
    d: list[int] = []
    e: dict[str, float] = {}
    f: float | str = 0.0  # a union that takes text takes it
    g: str = ""


@pytest.mark.parametrize(
    "data",
    [{"a": "5"}, {"a": True}, {"b": "1"}, {"c": ["1", 2]}, {"c": (1.0, False)}, {"d": [1, "2"]}, {"e": {"x": "1"}}],
)
def test_a_string_or_bool_where_a_number_belongs_is_refused(data):
    with pytest.raises(ValidationError, match="must be a"):
        Sample.model_validate(data)


def test_numbers_and_text_fields_still_pass():
    s = Sample.model_validate({"a": 5, "b": None, "c": [1, 2.5], "d": [1], "e": {"x": 1}, "f": "x", "g": "1"})
    assert s.a == 5.0 and s.c == (1.0, 2.5) and s.f == "x"


def test_trackspec_optional_numbers_refuse_strings():
    with pytest.raises(ValidationError, match="max_straight_m"):
        TrackSpec.model_validate({"max_straight_m": "5"})
    with pytest.raises(ValidationError, match="lap_length_m"):
        TrackSpec.model_validate({"lap_length_m": "40"})
    assert TrackSpec.model_validate({"max_straight_m": 5}).max_straight_m == 5.0


def test_configs_and_records_refuse_strings():
    with pytest.raises(Exception, match="must be a number"):
        BuildConfig.from_dict({"geometry": {"wall_height_m": "0.5"}})
    with pytest.raises(ValidationError, match="must be a"):
        StageMetadata.model_validate({"start": ["1", "2"]})
    with pytest.raises(ValidationError, match="must be a"):
        StageMetadata.model_validate({"raster_px": [10, "10"]})
    good = {
        "id": "x",
        "source_path": "a.yaml",
        "reason": "r",
        "resolution_m": 0.05,
        "raster": {"width_px": 1, "height_px": 1},
        "start": [0, 0, 0],
        "start_clearance_m": 1.0,
    }
    assert OpenMap.model_validate(good).start == (0.0, 0.0, 0.0)
    for bad in ({"resolution_m": "0.05"}, {"narrowest_gap_m": "1"}, {"start": [0, "0", 0]}):
        with pytest.raises(ValidationError, match="must be a"):
            OpenMap.model_validate({**good, **bad})


@pytest.mark.parametrize(
    "text, words",
    [
        ("[1, 2]", "mapping"),
        ("[" * 3000 + "]" * 3000, "nested too deeply"),
        ('{"v_max": ' + "9" * 5000 + "}", "digits"),
        ("not json", "not valid JSON"),
    ],
)
def test_a_hostile_limits_file_is_one_typed_line(tmp_path, text, words):
    """Limits files (``raceline --limits``) go through the same reader: bounded, typed."""
    from roboracer_arena.errors import ConfigError
    from roboracer_arena.raceline.limits import load_limits

    p = tmp_path / "limits.json"
    p.write_text(text)
    with pytest.raises(ConfigError, match=words) as e:
        load_limits(p)
    assert "limits.json" in str(e.value) and "\n" not in str(e.value)


def test_a_limits_number_given_as_text_is_refused(tmp_path):
    import json

    from roboracer_arena.errors import ConfigError
    from roboracer_arena.raceline.limits import limits_json, load_limits, preset

    doc = json.loads(limits_json(preset("car")))
    doc["v_max"] = str(doc["v_max"])
    p = tmp_path / "limits.json"
    p.write_text(json.dumps(doc))
    with pytest.raises(ConfigError, match="v_max"):
        load_limits(p)
