"""The GeoJSON projection against known geodesic distances."""

from __future__ import annotations

import math

import numpy as np
import pytest

from roboracer_arena.circuits.projection import geodesic_distance, geodesic_length, project_local


def _dms(d: float, m: float, s: float) -> float:
    return d + m / 60 + s / 3600


def test_vincenty_matches_the_published_flinders_peak_buninyong_distance():
    # Geoscience Australia's worked example (GRS80; WGS84 differs by < 0.1 mm here).
    d = geodesic_distance(
        _dms(144, 25, 29.52440), -_dms(37, 57, 3.72030), _dms(143, 55, 35.38390), -_dms(37, 39, 10.15610)
    )
    assert d == pytest.approx(54972.271, abs=0.002)


def test_one_degree_of_meridian_at_the_equator():
    # WGS84 meridian arc from 0° to 1° latitude: 110 574.389 m (geodesic and projected).
    assert geodesic_distance(0, 0, 0, 1) == pytest.approx(110574.389, abs=0.01)
    p = project_local(np.array([[0.0, 0.0], [0.0, 1.0]]), centre=(0.0, 0.0))
    assert p[1, 1] - p[0, 1] == pytest.approx(110574.389, abs=0.01)
    assert abs(p[1, 0]) < 1e-6


@pytest.mark.parametrize("lat0", [-37.8, 0.5, 43.7, 60.0])
def test_projected_distances_match_geodesics_at_circuit_scale(lat0):
    rng = np.random.default_rng(7)
    lon0 = 7.42
    ll = np.column_stack([lon0 + rng.uniform(-0.02, 0.02, 40), lat0 + rng.uniform(-0.015, 0.015, 40)])
    xy = project_local(ll)
    for i in range(0, 40, 2):
        g = geodesic_distance(*ll[i], *ll[i + 1])
        e = float(np.hypot(*(xy[i] - xy[i + 1])))
        assert abs(e - g) / g < 2e-7, (g, e)


def test_projection_is_conformal_and_centred():
    lat0, lon0 = 43.7347, 7.4206  # Monaco
    ll = np.array([[lon0, lat0], [lon0 + 1e-5, lat0], [lon0, lat0 + 1e-5]])
    xy = project_local(ll, centre=(lon0, lat0))
    assert np.allclose(xy[0], 0, atol=1e-6)
    a, b = xy[1] - xy[0], xy[2] - xy[0]
    cos = a @ b / (np.linalg.norm(a) * np.linalg.norm(b))
    assert abs(cos) < 1e-6  # east ⟂ north is kept
    assert geodesic_length(ll[:2], closed=False) == pytest.approx(np.linalg.norm(a), rel=1e-7)


def test_bad_shape_is_refused():
    with pytest.raises(ValueError):
        project_local(np.zeros((3, 3)))
    assert math.isclose(geodesic_distance(1, 2, 1, 2), 0.0)
