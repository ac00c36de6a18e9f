"""build_environment end to end on maps the tests write: report, stage, IoU, errors."""

from __future__ import annotations

import numpy as np
import pytest
from pxr import Usd, UsdPhysics

from roboracer_arena import BuildConfig, BuildReport, build_environment, load_map
from roboracer_arena.errors import ArenaError, ConfigError, CorridorError, InvalidArgumentError, MapIOError
from roboracer_arena.usd import read_meshes, stage_metadata, validation_errors

from .ringmap import ring_raster, write_map
from .synthetic import load_physics


@pytest.fixture(scope="module")
def ring_yaml(tmp_path_factory):
    return write_map(tmp_path_factory.mktemp("maps"), ring_raster(240, style="filled"))


@pytest.fixture(scope="module")
def built(ring_yaml, tmp_path_factory):
    out = tmp_path_factory.mktemp("out") / "ring.usdc"
    return build_environment(ring_yaml, out), out


def test_report(built, ring_yaml):
    report, out = built
    assert isinstance(report, BuildReport)
    assert report.source == str(ring_yaml) and report.output == str(out)
    assert report.raster_px == (240, 240) and report.raster_mp == pytest.approx(0.0576)
    assert report.usd_bytes == out.stat().st_size
    for stage in ("load", "geometry", "usd_author", "usd_write", "total"):
        assert report.timings_s[stage] >= 0
    assert report.timings_s["total"] == pytest.approx(
        sum(report.timings_s[k] for k in ("load", "geometry", "usd_author", "usd_write"))
    )
    for name in ("floor", "walls", "ducts", "rings"):
        assert report.meshes[name].vertices > 0 and report.meshes[name].triangles > 0
    assert report.walls == 2  # the outer and the inner wall of the ring
    assert report.iou >= 0.97
    assert report.max_wall_deviation_cells < 2
    # centreline of a ring with radii 0.25 and 0.42 of 12 m: 2 pi 4.02 m
    assert report.centreline_length_m == pytest.approx(2 * np.pi * 0.335 * 12, rel=0.03)
    assert "IoU" in report.summary()


def test_stage_is_valid_with_colliders(built):
    report, out = built
    assert validation_errors(out) == []
    stage = Usd.Stage.Open(str(out))
    paths, descs = load_physics(stage)[UsdPhysics.ObjectType.MeshShape]
    assert {"/World/Track/Walls", "/World/Track/Floor"} <= {str(p) for p in paths}
    assert all([str(m) for m in d.materials] == ["/World/Looks/TrackPhysics"] for d in descs)


def test_stage_geometry_matches_the_map(built, ring_yaml):
    """Wall vertices lie on the two ring borders, in map-frame metres."""
    _, out = built
    walls = read_meshes(Usd.Stage.Open(str(out)))["/World/Track/Walls"]
    r = np.hypot(walls.points[:, 0] - 1.0, walls.points[:, 1] - 1.0)  # map centre: -5 + 6 m
    near_in, near_out = np.abs(r - 0.25 * 12), np.abs(r - 0.42 * 12)
    assert np.minimum(near_in, near_out).max() < 0.1
    assert walls.points[:, 2].min() == pytest.approx(0.0) and walls.points[:, 2].max() == pytest.approx(0.5)


def test_metadata(built, ring_yaml):
    _, out = built
    meta = stage_metadata(Usd.Stage.Open(str(out)))
    assert meta["source_map"] == str(ring_yaml)
    assert meta["resolution"] == 0.05 and meta["origin"] == [-5.0, -5.0, 0.0]
    assert BuildConfig.model_validate_json(meta["build_config"]) == BuildConfig()
    assert meta["iou"] >= 0.97


def test_in_memory_map_config_and_start(ring_yaml, tmp_path):
    m = load_map(ring_yaml)
    cfg = BuildConfig.from_dict({"geometry": {"wall_height_m": 0.3}, "materials": {"textures": False}})
    rep = build_environment(m, tmp_path / "a.usda", cfg, start=(1.0 + 0.335 * 12, 1.0))
    assert rep.usd_format == "usda" and rep.textures == []
    walls = read_meshes(Usd.Stage.Open(rep.output))["/World/Track/Walls"]
    assert walls.points[:, 2].max() == pytest.approx(0.3)
    # config as a mapping, start as CLI text
    rep2 = build_environment(ring_yaml, tmp_path / "b.usdc", {"materials": {"textures": False}}, start="5.02,1.0")
    assert rep2.meshes["walls"] == rep.meshes["walls"]


def test_thin_line_ring(tmp_path):
    yaml = write_map(tmp_path, ring_raster(240, style="thin"), name="thin")
    rep = build_environment(yaml, tmp_path / "thin.usdc", {"materials": {"textures": False}})
    assert rep.walls == 2 and rep.iou >= 0.97


def test_bad_inputs_raise_typed_errors_and_write_nothing(tmp_path, ring_yaml):
    blank = write_map(tmp_path, np.full((120, 120), 254, np.uint8), name="blank")
    with pytest.raises(CorridorError):  # no closed corridor, and open maps refused
        build_environment(blank, tmp_path / "blank.usdc", open=False)
    solid = write_map(tmp_path, np.zeros((120, 120), np.uint8), name="solid")
    with pytest.raises(CorridorError):  # not even an open map: nothing is free
        build_environment(solid, tmp_path / "solid.usdc")
    with pytest.raises(MapIOError):
        build_environment(tmp_path / "missing.yaml", tmp_path / "missing.usdc")
    with pytest.raises(ConfigError, match="tube_diameter_m"):
        build_environment(ring_yaml, tmp_path / "cfg.usdc", {"geometry": {"tube_diameter_m": 0}})
    with pytest.raises(ConfigError, match=r"\.obj"):
        build_environment(ring_yaml, tmp_path / "x.obj")
    with pytest.raises(InvalidArgumentError, match="start pose"):
        build_environment(ring_yaml, tmp_path / "s.usdc", start="a,b")
    assert not list(tmp_path.glob("*.usd*")) and not (tmp_path / "textures").exists()
    assert issubclass(CorridorError, ArenaError)


def test_ducts_get_the_cores_texture_coordinates(ring_yaml):
    from roboracer_arena.maps.corridor import extract_corridor

    geo = extract_corridor(ring_yaml)
    g = BuildConfig().geometry
    s = g.tube_segments
    v, t = geo.meshes["ducts"]
    assert len(v) == sum(len(d) * s for d in geo.ducts)
    st, st_idx = geo.duct_st
    assert st.dtype == np.float32 and st.shape[1] == 2
    assert len(st_idx) == 3 * len(t) and st_idx.max() < len(st)
    # u runs 0 .. each duct's length (seam row included), v 0 .. 1 around the tube
    lengths = [np.hypot(*(np.roll(d, -1, 0) - d).T).sum() for d in geo.ducts]
    assert st[:, 0].min() == 0 and st[:, 0].max() == pytest.approx(max(lengths), rel=1e-5)
    assert st[:, 1].min() == 0 and st[:, 1].max() == 1
    # rings: one every ring_spacing_m along each duct, 2 sections of tube_segments vertices
    assert len(geo.meshes["rings"][0]) == sum(int(L // g.ring_spacing_m) for L in lengths) * 2 * s


def test_stage_has_ducts_and_rings(built):
    _, out = built
    stage = Usd.Stage.Open(str(out))
    for name, look in (("Ducts", "Duct"), ("Rings", "Ring")):
        prim = stage.GetPrimAtPath(f"/World/Track/Barriers/{name}")
        assert prim, name
        from pxr import UsdShade

        mat, _ = UsdShade.MaterialBindingAPI(prim).ComputeBoundMaterial()
        assert mat.GetPath() == f"/World/Looks/{look}"
    assert stage.GetPrimAtPath("/World/Looks/Duct/DiffuseTexture")  # the ducts carry st, so they are textured
