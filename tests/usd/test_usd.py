"""The USD layer on a synthetic ring track (numpy meshes): structure, validation, the
physics parse, metadata, encodings and atomic writing."""

from __future__ import annotations

import json

import numpy as np
import pytest
from pxr import Usd, UsdGeom, UsdPhysics, UsdShade

from builder.synthetic import load_physics, ring_meshes
from roboracer_arena.config.build import BuildConfig
from roboracer_arena.errors import ConfigError, MapIOError
from roboracer_arena.usd import METADATA_KEY, read_meshes, stage_metadata, validate_stage, write_stage

META = {"source_map": "/maps/ring.yaml", "resolution": 0.05, "origin": [-5.0, -5.0, 0.0], "build_config": "{}"}


@pytest.fixture(scope="module")
def ring_stage(tmp_path_factory):
    out = tmp_path_factory.mktemp("ring") / "ring.usdc"
    cfg = BuildConfig()
    written = write_stage(out, ring_meshes(), cfg, {**META, "build_config": cfg.model_dump_json()})
    return written, Usd.Stage.Open(str(out))


def test_stage_conventions(ring_stage):
    written, stage = ring_stage
    assert written.usd_format == "usdc" and written.usd_bytes == written.path.stat().st_size
    assert written.path.read_bytes()[:8] == b"PXR-USDC"
    assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.z
    assert UsdGeom.GetStageMetersPerUnit(stage) == 1.0
    assert UsdPhysics.GetStageKilogramsPerUnit(stage) == 1.0
    assert stage.GetDefaultPrim().GetPath() == "/World"
    scene = UsdPhysics.Scene(stage.GetPrimAtPath("/World/PhysicsScene"))
    assert scene and scene.GetGravityMagnitudeAttr().Get() == pytest.approx(9.81)


def test_walls_floor_barriers(ring_stage):
    _, stage = ring_stage
    walls = stage.GetPrimAtPath("/World/Track/Walls")
    assert walls.HasAPI(UsdPhysics.CollisionAPI) and walls.HasAPI(UsdPhysics.MeshCollisionAPI)
    assert UsdPhysics.MeshCollisionAPI(walls).GetApproximationAttr().Get() == "none"
    img = UsdGeom.Imageable(walls)
    assert img.ComputePurpose() == UsdGeom.Tokens.guide
    assert img.ComputeVisibility() == UsdGeom.Tokens.invisible
    floor = stage.GetPrimAtPath("/World/Track/Floor")
    assert floor.HasAPI(UsdPhysics.CollisionAPI)
    assert UsdGeom.Imageable(floor).ComputeVisibility() != UsdGeom.Tokens.invisible
    for prim in Usd.PrimRange(stage.GetPrimAtPath("/World/Track/Barriers")):
        assert not prim.HasAPI(UsdPhysics.CollisionAPI), f"{prim.GetPath()} must be visual only"
    # visual looks are UsdPreviewSurface; the floor's is textured through a relative asset path
    mat, _ = UsdShade.MaterialBindingAPI(floor).ComputeBoundMaterial()
    assert mat.GetPath() == "/World/Looks/Floor"
    tex = UsdShade.Shader(stage.GetPrimAtPath("/World/Looks/Floor/DiffuseTexture"))
    asset = tex.GetInput("file").Get()
    assert asset.path.startswith("./textures/") and asset.resolvedPath
    surf = UsdShade.Shader(stage.GetPrimAtPath("/World/Looks/Floor/PreviewSurface"))
    assert surf.GetIdAttr().Get() == "UsdPreviewSurface"


def test_physics_material_bound_with_physics_purpose(ring_stage):
    _, stage = ring_stage
    for path in ("/World/Track/Walls", "/World/Track/Floor"):
        mat, _ = UsdShade.MaterialBindingAPI(stage.GetPrimAtPath(path)).ComputeBoundMaterial("physics")
        assert mat.GetPath() == "/World/Looks/TrackPhysics"
        api = UsdPhysics.MaterialAPI(mat.GetPrim())
        assert api.GetStaticFrictionAttr().Get() == pytest.approx(0.83)


def test_validation_has_zero_findings(ring_stage):
    written, _ = ring_stage
    findings = validate_stage(written.path)
    assert [f for f in findings if f.severity == "Error"] == []
    assert findings == [], [str(f) for f in findings]  # not even warnings


def test_validation_catches_a_broken_stage(tmp_path):
    """The validator is live: a stage without metadata fails it."""
    stage = Usd.Stage.CreateInMemory()
    UsdGeom.Xform.Define(stage, "/World")
    names = {f.name for f in validate_stage(stage) if f.severity == "Error"}
    assert {"MissingDefaultPrim", "MissingUpAxisMetadata"} <= names


def test_physics_parse_finds_colliders_with_the_material(ring_stage):
    _, stage = ring_stage
    parsed = load_physics(stage)
    paths, descs = parsed[UsdPhysics.ObjectType.MeshShape]
    by_path = {str(p): d for p, d in zip(paths, descs)}
    assert set(by_path) == {"/World/Track/Walls", "/World/Track/Floor"}
    for d in by_path.values():
        assert d.collisionEnabled and d.approximation == "none"
        assert [str(m) for m in d.materials] == ["/World/Looks/TrackPhysics"]
    mpaths, mdescs = parsed[UsdPhysics.ObjectType.RigidBodyMaterial]
    assert [str(p) for p in mpaths] == ["/World/Looks/TrackPhysics"]
    assert mdescs[0].staticFriction == pytest.approx(0.83) and mdescs[0].restitution == pytest.approx(0.1)
    assert len(parsed[UsdPhysics.ObjectType.Scene][0]) == 1


def test_metadata_records_source_and_config(ring_stage):
    _, stage = ring_stage
    meta = stage_metadata(stage)
    assert meta["source_map"] == "/maps/ring.yaml"
    assert meta["resolution"] == 0.05 and meta["origin"] == [-5.0, -5.0, 0.0]
    assert BuildConfig.model_validate_json(meta["build_config"]) == BuildConfig()
    assert METADATA_KEY in stage.GetRootLayer().customLayerData


def test_meshes_read_back_exactly(ring_stage):
    _, stage = ring_stage
    read = read_meshes(stage)
    for m in ring_meshes():
        got = read[m.path]
        np.testing.assert_allclose(got.points, m.points, atol=1e-6)
        np.testing.assert_array_equal(got.triangles, m.triangles)
    assert read["/World/Track/Walls"].purpose == "guide" and not read["/World/Track/Walls"].visible


def test_usda_and_plain_usd(tmp_path):
    cfg = BuildConfig(usd_format="usda")
    a = write_stage(tmp_path / "a.usda", ring_meshes(), BuildConfig(), META)
    assert a.path.read_text().startswith("#usda 1.0")
    b = write_stage(tmp_path / "b.usd", ring_meshes(), cfg, META)
    assert b.usd_format == "usda" and b.path.read_bytes().startswith(b"#usda")
    c = write_stage(tmp_path / "c.usd", ring_meshes(), BuildConfig(), META)
    assert c.path.read_bytes()[:8] == b"PXR-USDC"
    assert c.usd_bytes < a.usd_bytes  # the crate is the compact encoding
    with pytest.raises(ConfigError, match=r"c\.obj: output must end in \.usdc"):
        write_stage(tmp_path / "c.obj", ring_meshes(), BuildConfig(), META)


def test_no_textures_means_single_file(tmp_path):
    cfg = BuildConfig.from_dict({"materials": {"textures": False}})
    w = write_stage(tmp_path / "plain.usdc", ring_meshes(), cfg, META)
    assert w.textures == [] and not (tmp_path / "textures").exists()
    assert validate_stage(w.path) == []


def test_textures_are_deterministic(tmp_path):
    a = write_stage(tmp_path / "a" / "s.usdc", ring_meshes(), BuildConfig(), META)
    b = write_stage(tmp_path / "b" / "s.usdc", ring_meshes(), BuildConfig(), META)
    assert [p.name for p in a.textures] == [p.name for p in b.textures]
    for p, q in zip(a.textures, b.textures):
        assert p.read_bytes() == q.read_bytes()


def test_failed_write_leaves_nothing(tmp_path):
    """A failure after the stage was encoded (here: textures/ cannot be created because a
    file is in the way) leaves neither the stage nor a temporary file behind."""
    (tmp_path / "textures").write_text("in the way")
    before = set(tmp_path.iterdir())
    with pytest.raises(MapIOError):
        write_stage(tmp_path / "track.usdc", ring_meshes(), BuildConfig(), META)
    assert set(tmp_path.iterdir()) == before


def test_failed_write_keeps_the_previous_stage(tmp_path):
    out = tmp_path / "track.usdc"
    write_stage(out, ring_meshes(), BuildConfig.from_dict({"materials": {"textures": False}}), META)
    old = out.read_bytes()
    (tmp_path / "textures").write_text("in the way")
    with pytest.raises(MapIOError):
        write_stage(out, ring_meshes(), BuildConfig(), {**META, "source_map": "other"})
    assert out.read_bytes() == old
    assert sorted(p.name for p in tmp_path.iterdir()) == ["textures", "track.usdc"]


def test_metadata_json_is_parseable(ring_stage):
    _, stage = ring_stage
    assert json.loads(stage_metadata(stage)["build_config"])["physics"]["static_friction"] == 0.83


def test_stage_folder_is_relocatable(ring_stage, tmp_path):
    """Textures are referenced relative to the stage, so the folder can be moved."""
    import shutil

    written, _ = ring_stage
    moved = tmp_path / "moved"
    shutil.copytree(written.path.parent, moved)
    stage = Usd.Stage.Open(str(moved / written.path.name))
    asset = UsdShade.Shader(stage.GetPrimAtPath("/World/Looks/Floor/DiffuseTexture")).GetInput("file").Get()
    assert asset.resolvedPath.startswith(str(moved))
    assert validate_stage(stage) == []
