"""Vehicle limits: presets, files (JSON/YAML) validated with the file and field named."""

from __future__ import annotations

import json

import pytest

from roboracer_arena.errors import ConfigError
from roboracer_arena.raceline import PRESETS, load_limits, preset


def test_presets_load_and_match_their_sources():
    for name in PRESETS:
        assert preset(name).name == name
    f1 = preset("f1tenth-racetracks")
    assert f1.v_max == 8.0 and f1.ay_tyre(5.0) == pytest.approx(10.0, abs=0.01)
    fz = preset("forzaeth")
    assert (fz.v_max, fz.ax_machine(0.0), fz.ax_machine(15.0), fz.ay_tyre(3.0)) == (15.0, 9.11, 1.47, 12.0)
    car = preset("car")
    assert 6.0 < car.v_max < 8.0 and 6.0 < car.ay_tyre(4.0) < 8.2  # mu 0.83: at most 8.1 m/s^2


def test_a_limits_file_round_trips(tmp_path):
    p = tmp_path / "mine.json"
    p.write_text(json.dumps({"v_max": 9, "ggv": [[0, 5, 6], [9, 4, 6]], "ax_max_machines": [[0, 3]]}))
    lim = load_limits(p)
    assert lim.name == "mine.json" and lim.ax_tyre(4.5) == pytest.approx(4.5)
    y = tmp_path / "mine.yaml"
    y.write_text("v_max: 9\nggv: [[0, 5, 6]]\nax_max_machines: [[0, 3]]\n")
    assert load_limits(y).v_max == 9


@pytest.mark.parametrize(
    "doc, field",
    [
        ({"ggv": [[0, 5, 6]], "ax_max_machines": [[0, 3]]}, "v_max"),
        ({"v_max": 9, "ggv": [[0, -5, 6]], "ax_max_machines": [[0, 3]]}, "ggv"),
        ({"v_max": 9, "ggv": [[1, 5, 6], [0, 5, 6]], "ax_max_machines": [[0, 3]]}, "ggv"),
        ({"v_max": 9, "ggv": [[0, 5, 6]], "ax_max_machines": [[0, 0]]}, "ax_max_machines"),
        ({"v_max": 9, "ggv": [[0, 5, 6]], "ax_max_machines": [[0, 3]], "colour": "red"}, "colour"),
        ({"v_max": "fast", "ggv": [[0, 5, 6]], "ax_max_machines": [[0, 3]]}, "v_max"),
    ],
)
def test_bad_limits_name_the_file_and_the_field(tmp_path, doc, field):
    p = tmp_path / "bad.json"
    p.write_text(json.dumps(doc))
    with pytest.raises(ConfigError, match=field) as e:
        load_limits(p)
    assert str(e.value).startswith(f"{p}: ")


def test_scaling_and_overrides():
    car = preset("car")
    half = car.scaled(0.5)
    assert half.ay_tyre(3.0) == pytest.approx(0.5 * car.ay_tyre(3.0)) and half.v_max == car.v_max
    o = car.with_overrides(v_max=5.0, ay_max=6.0)
    assert o.v_max == 5.0 and o.ay_tyre(1.0) == 6.0 and o.ax_tyre(1.0) == car.ax_tyre(1.0)
    with pytest.raises(ConfigError, match="v_max"):
        car.with_overrides(v_max=-1.0)


@pytest.mark.slow
def test_the_car_preset_is_what_the_simulator_measures():
    """``presets/car.json`` is ``raceline --measure-limits``' output for the default car, not typed in."""
    from roboracer_arena.raceline.measure import measure_limits

    measured, shipped = measure_limits(), preset("car")
    assert measured.v_max == shipped.v_max
    assert measured.ggv == shipped.ggv and measured.ax_max_machines == shipped.ax_max_machines
