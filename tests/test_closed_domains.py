"""Closed domains cross the core boundary as enums converted at the signature (issue 37):
the strings callers pass are accepted, anything else is an ``InvalidArgumentError``
naming the allowed values, raised before the function body runs."""

from __future__ import annotations

import numpy as np
import pytest

from roboracer_arena import _core
from roboracer_arena.errors import InvalidArgumentError
from roboracer_arena.maps.occupancy import load_map

KINDS = "'sim', 'build', 'constructor' or 'spec'"


@pytest.mark.parametrize("kind", ["sim", "build", "constructor"])
def test_config_kinds_are_accepted(kind):
    assert _core.check_config(kind, _core.config_defaults(kind))


@pytest.mark.parametrize("kind", ["nope", "SIM", "", 3, None, b"sim"])
def test_an_unknown_config_kind_names_the_allowed_ones(kind):
    for call in (lambda: _core.config_defaults(kind), lambda: _core.check_config(kind, {})):
        with pytest.raises(InvalidArgumentError, match=f"config kind .*expected {KINDS}"):
            call()


def test_the_spec_kind_has_no_core_defaults():
    with pytest.raises(InvalidArgumentError, match="no core defaults.*TrackSpec"):
        _core.config_defaults("spec")
    from roboracer_arena import TrackSpec

    assert _core.check_config("spec", TrackSpec())["lap_length_m"] > 0


@pytest.mark.parametrize("fmt", ["png", "pgm", "PNG", "Pgm"])
def test_image_formats_in_any_case(tmp_path, fmt):
    data = np.full((8, 8), 254, np.uint8)
    image = _core.save_map(data, 0.05, (0.0, 0.0, 0.0), tmp_path / "m.yaml", fmt)
    assert image.endswith("." + fmt.lower())
    assert load_map(tmp_path / "m.yaml").meta.image_format == fmt.lower()


@pytest.mark.parametrize("fmt", ["jpg", "", 1, None])
def test_an_unknown_image_format_is_refused_before_writing(tmp_path, fmt):
    with pytest.raises(InvalidArgumentError, match="image_format must be 'png' or 'pgm'"):
        _core.save_map(np.full((8, 8), 254, np.uint8), 0.05, (0.0, 0.0, 0.0), tmp_path / "m.yaml", fmt)
    assert not any(tmp_path.iterdir())
