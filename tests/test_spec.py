"""TrackSpec: the paper's 12 fields and the optional speed cap, defaults, validation
errors that name the field."""

import json
import math

import pytest

from roboracer_arena import TrackSpec
from roboracer_arena.errors import SpecError


def test_twelve_fields_and_the_optional_cap_with_defaults():
    assert len(TrackSpec.model_fields) == 13
    s = TrackSpec()
    assert s.feature_order == [] and s.min_radius_m == 0 and s.longest_straight_m == 0
    assert s.max_straight_m is None
    assert "properties" in TrackSpec.json_schema()


@pytest.mark.parametrize(
    "data, field",
    [
        ({"lap_length_m": -5}, "lap_length_m"),
        ({"corridor_width_m": math.nan}, "corridor_width_m"),
        ({"hairpins": -1}, "hairpins"),
        ({"direction": "sideways"}, "direction"),
        ({"hairpins": 1, "feature_order": ["chicane"]}, "feature_order"),
        ({"bogus": 1}, "bogus"),
    ],
)
def test_invalid_values_name_the_field(data, field):
    with pytest.raises(SpecError, match=field):
        TrackSpec.from_dict(data)


def test_from_file_errors_name_the_file(tmp_path):
    p = tmp_path / "s.json"
    p.write_text("{not json")
    with pytest.raises(SpecError, match="s.json"):
        TrackSpec.from_file(p)
    with pytest.raises(SpecError, match="cannot read"):
        TrackSpec.from_file(tmp_path / "missing.json")
    p.write_text(
        json.dumps({"hairpins": 3, "chicanes": 1, "feature_order": ["hairpin", "chicane", "hairpin", "hairpin"]})
    )
    assert TrackSpec.from_file(p).hairpins == 3
