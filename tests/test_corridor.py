"""Corridor isolation and builder geometry (walls, ducts, centreline, meshes, IoU)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from roboracer_arena.errors import ConfigError, CorridorError, MapFormatError
from roboracer_arena.maps.corridor import DEFAULT_PARAMS, extract_corridor
from roboracer_arena.maps.occupancy import FREE, OCCUPIED, UNKNOWN, OccupancyMap

RES = 0.05
R_MID, WIDTH = 4.0, 1.5


def ring_map(outside: int = UNKNOWN, wall_cells: int = 3, gap: bool = False) -> OccupancyMap:
    """A ring corridor (centre radius 4 m, width 1.5 m) at 5 cm; walls `wall_cells` thick."""
    n = 220
    c = (np.arange(n) + 0.5) * RES - n * RES / 2
    x, y = np.meshgrid(c, -c)
    r = np.hypot(x, y)
    data = np.full((n, n), outside, np.uint8)
    half, t = WIDTH / 2, wall_cells * RES
    data[(np.abs(r - R_MID) > half) & (np.abs(r - R_MID) <= half + t)] = OCCUPIED
    data[np.abs(r - R_MID) <= half] = FREE
    if gap:  # open the outer wall towards +x
        data[(np.abs(y) < 0.3) & (x > R_MID)] = FREE
    return OccupancyMap(data, RES, (-n * RES / 2, -n * RES / 2, 0.0))


def check_ring_geometry(geo) -> None:  # type: ignore[no-untyped-def]
    assert geo.iou >= 0.97
    assert len(geo.walls) == 2
    radii = sorted(float(np.hypot(w[:, 0], w[:, 1]).mean()) for w in geo.walls)
    assert radii == pytest.approx([R_MID - WIDTH / 2, R_MID + WIDTH / 2], abs=0.05)
    cl = geo.centreline
    assert cl.ndim == 2 and cl.shape[1] == 2 and cl.dtype == np.float64
    assert np.hypot(cl[:, 0], cl[:, 1]) == pytest.approx(np.full(len(cl), R_MID), abs=0.05)
    area = 0.5 * np.sum(cl[:, 0] * np.roll(cl[:, 1], -1) - np.roll(cl[:, 0], -1) * cl[:, 1])
    assert area > 0, "counter-clockwise"
    assert not np.allclose(cl[0], cl[-1]), "no repeated end point"
    steps = np.linalg.norm(np.diff(np.vstack([cl, cl[:1]]), axis=0), axis=1)
    assert steps == pytest.approx(np.full(len(steps), 0.1), abs=0.005)
    assert geo.centreline_length == pytest.approx(2 * np.pi * R_MID, rel=0.01)


def test_filled_ring(tmp_path: Path) -> None:
    geo = extract_corridor(ring_map())
    check_ring_geometry(geo)
    assert set(geo.meshes) == {"floor", "walls", "ducts", "rings"}
    for verts, tris in geo.meshes.values():
        assert len(tris) and verts.dtype == np.float32 and verts.shape[1] == 3
        assert tris.dtype == np.uint32 and tris.shape[1] == 3 and tris.max() < len(verts)
    wall_v = geo.meshes["walls"][0]
    assert set(np.unique(wall_v[:, 2])) == {0.0, 0.5}
    assert geo.corridor_mask.dtype == np.bool_ and geo.corridor_mask.sum() == (geo.map.data == FREE).sum()
    assert geo.params == {**DEFAULT_PARAMS, "simplify_tolerance_m": RES / 2}
    assert set(geo.timings) >= {"corridor", "distance", "walls", "ducts", "centreline", "meshes", "roundtrip", "total"}
    duct_r = sorted(float(np.hypot(d[:, 0], d[:, 1]).mean()) for d in geo.ducts)
    assert duct_r == pytest.approx([R_MID - WIDTH / 2 - 0.165, R_MID + WIDTH / 2 + 0.165], abs=0.05)
    # a saved and reloaded map gives the same corridor
    geo.map.save(tmp_path / "ring.yaml")
    assert extract_corridor(tmp_path / "ring.yaml").corridor_mask.sum() == geo.corridor_mask.sum()


def test_thin_line_ring_and_start_pose() -> None:
    m = ring_map(outside=FREE, wall_cells=2)
    check_ring_geometry(extract_corridor(m))
    seeded = extract_corridor(m, start=(R_MID, 0.0, 1.57))
    assert seeded.corridor_mask.sum() == extract_corridor(m).corridor_mask.sum()
    with pytest.raises(CorridorError, match="encloses no infield"):
        extract_corridor(m, start=(0.0, 0.0))
    with pytest.raises(CorridorError, match="outside the map"):
        extract_corridor(m, start=(100.0, 0.0))


def test_params_change_geometry_and_bad_params_are_refused() -> None:
    m = ring_map()
    geo = extract_corridor(m, {"wall_height_m": 1.0, "tube_segments": 6, "ring_spacing_m": 0.0})
    assert float(geo.meshes["walls"][0][:, 2].max()) == pytest.approx(1.0)
    plain = extract_corridor(m, {"tube_segments": 6, "ring_spacing_m": 0.0})
    tubes_only = sum(2 * 6 * len(d) for d in plain.ducts)
    assert len(plain.meshes["ducts"][1]) == tubes_only and len(plain.meshes["rings"][1]) == 0
    moved = extract_corridor(m, {"wall_offset_m": 0.1})
    outer = max(float(np.hypot(w[:, 0], w[:, 1]).mean()) for w in moved.walls)
    assert outer == pytest.approx(R_MID + WIDTH / 2 + 0.1, abs=0.05)
    with pytest.raises(ConfigError, match="unknown field"):
        extract_corridor(m, {"tube_diamter_m": 0.3})
    with pytest.raises(ConfigError, match="tube_diameter_m"):
        extract_corridor(m, {"tube_diameter_m": -1})
    assert json.loads(json.dumps(DEFAULT_PARAMS))["tube_diameter_m"] == 0.33


def test_leaking_blank_and_empty_maps_are_refused_with_reasons() -> None:
    with pytest.raises(CorridorError, match=r"leak.*\(-?\d+\.\d+, -?\d+\.\d+\) m"):
        extract_corridor(ring_map(outside=FREE, wall_cells=2, gap=True))
    with pytest.raises(CorridorError, match="blank"):
        extract_corridor(OccupancyMap(np.full((30, 40), FREE, np.uint8), RES, (0, 0, 0)))
    with pytest.raises(CorridorError, match="no free cells"):
        extract_corridor(OccupancyMap(np.full((30, 40), OCCUPIED, np.uint8), RES, (0, 0, 0)))


@pytest.mark.parametrize(
    "rel",
    ["f1tenth-gym/maps/berlin.yaml", "f1tenth-racetracks/Spa/Spa_map.yaml"],
)
def test_shared_maps_build_with_high_iou(sources: Path, rel: str) -> None:
    geo = extract_corridor(sources / rel)
    assert geo.iou >= 0.97
    assert geo.max_wall_deviation_cells < 1.0
    assert len(geo.walls) >= 2 and geo.centreline_length > 50


def test_shared_maps_refused_for_the_right_reason(sources: Path) -> None:
    with pytest.raises(CorridorError, match="blank"):
        extract_corridor(sources / "f1tenth-gym-ros/maps/Spielberg_blank_map.yaml")
    with pytest.raises(CorridorError, match="no free region encloses an infield"):
        extract_corridor(sources / "bdevan5-f1tenth-benchmarks/maps/CornerHall.yaml")
    with pytest.raises(MapFormatError, match="porto.pgm"):
        extract_corridor(sources / "f1tenth-simulator/maps/porto.yaml")
