"""Both converters on tiny inputs written here, and one circuit built end to end."""

from __future__ import annotations

import json

import numpy as np
import pytest

from roboracer_arena.circuits import CircuitConfig, build_circuit, read_geojson, read_tum_csv
from roboracer_arena.circuits.projection import geodesic_length
from roboracer_arena.errors import MapFormatError


def _circle(r: float, n: int) -> np.ndarray:
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.column_stack([r * np.cos(a), r * np.sin(a)])


def _write_tum(path, xy, wr, wl):
    rows = "\n".join(f"{x:.6f},{y:.6f},{wr:.3f},{wl:.3f}" for x, y in xy)
    path.write_text("# x_m,y_m,w_tr_right_m,w_tr_left_m\n" + rows + "\n")


def test_tum_csv_reader_moves_to_the_corridor_middle(tmp_path):
    f = tmp_path / "TinyRing.csv"
    _write_tum(f, _circle(100.0, 120), wr=4.0, wl=6.0)  # counter-clockwise: left = inside
    c = read_tum_csv(f)
    assert (c.id, c.name, c.source) == ("tiny-ring", "Tiny Ring", "tumftm")
    assert np.allclose(c.widths, 10.0)
    r = np.hypot(c.xy[:, 0], c.xy[:, 1])
    assert np.allclose(r, 99.0, atol=0.01)  # 1 m towards the wider (left, inner) side


def test_tum_csv_reader_names_the_file_and_line(tmp_path):
    f = tmp_path / "Bad.csv"
    f.write_text("# x,y,wr,wl\n1,2,3,4\n1,2,three,4\n")
    with pytest.raises(MapFormatError, match=r"Bad.csv:3"):
        read_tum_csv(f)
    f.write_text("1,2,3\n")
    with pytest.raises(MapFormatError, match="4 columns"):
        read_tum_csv(f)


def _geojson_ring(lon0: float, lat0: float, r_m: float, n: int) -> list[list[float]]:
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    dlat = r_m * np.sin(a) / 111_132.0
    dlon = r_m * np.cos(a) / (111_320.0 * np.cos(np.radians(lat0)))
    pts = [[lon0 + x, lat0 + y] for x, y in zip(dlon, dlat)]
    return pts + [pts[0]]


def test_geojson_reader_projects_and_sets_a_constant_width(tmp_path):
    coords = _geojson_ring(7.42, 43.73, 300.0, 90)
    doc = {
        "type": "FeatureCollection",
        "features": [
            {
                "type": "Feature",
                "properties": {"id": "xx-2000", "Location": "Tiny Town", "Name": "Tiny Ring", "length": 1885},
                "geometry": {"type": "LineString", "coordinates": coords},
            }
        ],
    }
    f = tmp_path / "xx-2000.geojson"
    f.write_text(json.dumps(doc))
    c = read_geojson(f, width_m=12.0)
    assert (c.id, c.name, c.source) == ("tiny-town", "Tiny Ring", "bacinger")
    assert len(c.xy) == 90  # the closing duplicate is dropped
    assert np.allclose(c.widths, 12.0)
    assert c.length_m == pytest.approx(geodesic_length(np.asarray(coords[:-1])), rel=1e-6)
    assert np.hypot(*c.xy.T).mean() == pytest.approx(300.0, rel=0.01)
    assert "12 m" in c.width_note


def test_geojson_reader_refuses_a_point(tmp_path):
    f = tmp_path / "p.geojson"
    f.write_text(
        json.dumps({"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [1, 2]}})
    )
    with pytest.raises(MapFormatError, match="LineString"):
        read_geojson(f)
    f.write_text("{not json")
    with pytest.raises(MapFormatError, match="not valid JSON"):
        read_geojson(f)


def test_build_circuit_end_to_end_on_a_tiny_ring(tmp_path):
    f = tmp_path / "Ring.csv"
    _write_tum(f, _circle(100.0, 120), wr=6.0, wl=6.0)
    rep = build_circuit(read_tum_csv(f), tmp_path / "out", CircuitConfig())
    assert rep.one_corridor and not rep.grade_separated
    assert rep.lap_length_m == pytest.approx(2 * np.pi * 10.0, rel=1e-3)
    assert rep.length_error < 0.005
    assert rep.width_mean_m == pytest.approx(1.2)
    assert rep.narrowed_fraction == 0.0
    for name in ("map.png", "map.yaml", "centreline.csv", "circuit.json"):
        assert (tmp_path / "out" / "ring" / name).is_file()
    assert json.loads((tmp_path / "out" / "ring" / "circuit.json").read_text())["map_sha256"] == rep.map_sha256


def test_shipped_circuit_reports_load_typed_and_round_trip():
    """Every committed ``circuit.json`` is a :class:`CircuitReport` and writes back as it is."""
    from roboracer_arena.circuits.report import CircuitReport
    from roboracer_arena.foundation.paths import tracks_dir

    files = sorted((tracks_dir() / "circuits").glob("*/circuit.json"))
    assert len(files) >= 44
    for f in files:
        text = f.read_text(encoding="utf-8")
        rep = CircuitReport.model_validate_json(text)
        assert json.dumps(rep.to_json_dict(), indent=2) + "\n" == text, f
