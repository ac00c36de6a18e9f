"""Author the track stage with usd-core and write it atomically.

Layout (Z up, metres, kilograms, default prim ``/World``)::

    /World                      Xform
    /World/PhysicsScene         UsdPhysics.Scene (gravity -Z); PhysxSceneAPI with the `physx` extra
    /World/Track                Xform
    /World/Track/Floor          Mesh, visual + collider (approximation none), physics material
    /World/Track/Walls          Mesh, collider (approximation none), purpose guide, invisible
    /World/Track/Barriers       the ducts, visual only: air-duct tubes and rings (Xform of Meshes Ducts, Rings)
    /World/Looks/...            UsdPreviewSurface looks + the UsdPhysics material

The geometry arrives as :class:`StageMesh` records (already in world coordinates); this
module knows nothing about maps or corridors.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from pxr import Gf, Sdf, Usd, UsdGeom, UsdPhysics, Vt

from ..config.build import BuildConfig
from ..config.sim import SimConfig
from ..errors import ConfigError, MapIOError
from ..foundation.fileio import atomic_paths, write_failure
from . import materials as looks
from . import physx_schemas
from .textures import Texture, duct_texture, floor_texture
from .vehicle import author_car

METADATA_KEY = "roboracerArena"
USD_SUFFIXES = {".usdc": "usdc", ".usda": "usda", ".usd": None}


@dataclass(frozen=True)
class StageMesh:
    """One triangle mesh to author.

    ``look`` names a material in ``/World/Looks`` (``Floor``, ``Wall``, ``Duct``, ``Ring``);
    ``collider`` applies CollisionAPI + MeshCollisionAPI (approximation ``none``) and binds
    the physics material; ``guide`` makes the prim purpose ``guide`` and invisible;
    ``st`` are texture coordinates: (V, 2) per vertex, or — with ``st_indices`` (3 T,) —
    indexed face-varying values (for seams)."""

    path: str
    points: np.ndarray
    triangles: np.ndarray
    look: str
    collider: bool = False
    guide: bool = False
    st: np.ndarray | None = None
    st_indices: np.ndarray | None = None


@dataclass
class WrittenStage:
    """What :func:`write_stage` produced."""

    path: Path
    usd_bytes: int
    usd_format: str
    textures: list[Path] = field(default_factory=list)
    seconds_author: float = 0.0
    seconds_write: float = 0.0


def resolve_format(out_path: Path, config: BuildConfig) -> str:
    """``.usdc``/``.usda`` decide the encoding; ``.usd`` takes ``config.usd_format``."""
    suffix = out_path.suffix.lower()
    if suffix not in USD_SUFFIXES:
        raise ConfigError(f"{out_path}: output must end in .usdc, .usda or .usd, not {suffix or '(none)'!r}")
    return USD_SUFFIXES[suffix] or config.usd_format


def author_stage(
    meshes: list[StageMesh],
    config: BuildConfig,
    metadata: Mapping[str, Any],
    car_pose: tuple[float, float, float] | None = None,
) -> tuple[Usd.Stage, list[Texture]]:
    """Build the stage in memory; returns it and the textures its materials reference.
    ``car_pose`` (x, y, yaw) adds the PhysX vehicle there (:mod:`.vehicle`, the ``physx`` extra)."""
    stage = Usd.Stage.CreateInMemory()
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    UsdPhysics.SetStageKilogramsPerUnit(stage, 1.0)
    world = UsdGeom.Xform.Define(stage, "/World")
    stage.SetDefaultPrim(world.GetPrim())
    layer = stage.GetRootLayer()
    layer.documentation = (
        "RoboRacer Arena track: floor, invisible collision walls, visible ducts (air-duct tubes with rings)."
    )
    layer.customLayerData = {METADATA_KEY: _vt_dict(metadata)}

    scene = UsdPhysics.Scene.Define(stage, "/World/PhysicsScene")
    scene.CreateGravityDirectionAttr(Gf.Vec3f(0.0, 0.0, -1.0))
    scene.CreateGravityMagnitudeAttr(float(config.physics.gravity_m_s2))
    physx_schemas.apply_scene(scene.GetPrim(), config.physics)

    UsdGeom.Xform.Define(stage, "/World/Track")
    UsdGeom.Scope.Define(stage, looks.LOOKS)
    with_st = {m.look for m in meshes if m.st is not None}  # only these can show a texture
    mats, textures = _define_looks(stage, config, {m.look for m in meshes}, with_st)
    physics_mat = looks.define_physics_material(stage, config.physics)

    for m in meshes:
        _ensure_parents(stage, m.path)
        prim = _define_mesh(stage, m)
        looks.bind(prim, mats[m.look])
        if m.collider:
            UsdPhysics.CollisionAPI.Apply(prim)
            UsdPhysics.MeshCollisionAPI.Apply(prim).CreateApproximationAttr(UsdPhysics.Tokens.none)
            looks.bind(prim, physics_mat, physics=True)
            physx_schemas.apply_collider(prim, config.physics)
    if car_pose is not None:
        author_car(stage, SimConfig(), car_pose)
    return stage, textures


def write_stage(
    out_path: str | Path,
    meshes: list[StageMesh],
    config: BuildConfig,
    metadata: Mapping[str, Any],
    car_pose: tuple[float, float, float] | None = None,
) -> WrittenStage:
    """Author and write the stage atomically; textures go to ``textures/`` beside it.
    The stage and every texture not already there with identical bytes are written to
    temporary files and renamed together: on any error nothing new is left behind."""
    import time

    out = Path(out_path)
    fmt = resolve_format(out, config)
    t0 = time.perf_counter()
    stage, textures = author_stage(meshes, config, metadata, car_pose)
    t1 = time.perf_counter()
    written = [out.parent / tex.relpath for tex in textures]
    fresh = [(p, tex) for p, tex in zip(written, textures) if not tex.present(out.parent)]
    with atomic_paths([out, *(p for p, _ in fresh)]) as (tmp, *tex_tmps):
        args = {"format": fmt} if out.suffix.lower() == ".usd" else {}
        try:
            exported = stage.GetRootLayer().Export(os.fspath(tmp), args=args)
        except Exception as e:  # usd-core's Tf.ErrorException: a full disk, a file-size limit, ...
            raise write_failure(out, e) from None
        if not exported:
            raise MapIOError(f"{out}: usd-core could not write the stage")
        for t, (_, tex) in zip(tex_tmps, fresh):
            t.write_bytes(tex.png)
        size = tmp.stat().st_size
    return WrittenStage(out, size, fmt, written, t1 - t0, time.perf_counter() - t1)


# --- helpers ------------------------------------------------------------------------


def _define_looks(
    stage: Usd.Stage, config: BuildConfig, wanted: set[str], with_st: set[str]
) -> tuple[dict[str, Any], list[Texture]]:
    mc = config.materials
    colour = {"Floor": mc.floor_colour, "Wall": mc.wall_colour, "Duct": mc.duct_colour, "Ring": mc.ring_colour}
    tex_for: dict[str, Texture] = {}
    if mc.textures and "Floor" in with_st:
        tex_for["Floor"] = floor_texture(mc.texture_size_px)
    if mc.textures and "Duct" in with_st:
        tex_for["Duct"] = duct_texture(mc.texture_size_px)
    params = {"Floor": (0.8, 0.0), "Wall": (0.9, 0.0), "Duct": (0.35, 0.6), "Ring": (0.7, 0.0)}
    mats: dict[str, Any] = {}
    used: list[Texture] = []
    for name in sorted(wanted):
        if name not in colour:
            raise ValueError(f"unknown look {name!r}; expected one of {sorted(colour)}")
        tex = tex_for.get(name)
        if tex is not None:
            used.append(tex)
        rough, metal = params[name]
        mats[name] = looks.define_preview_material(
            stage, name, colour[name], texture=f"./{tex.relpath}" if tex else None, roughness=rough, metallic=metal
        )
    return mats, used


def _ensure_parents(stage: Usd.Stage, path: str) -> None:
    parent = Sdf.Path(path).GetParentPath()
    while parent != Sdf.Path.absoluteRootPath and not stage.GetPrimAtPath(parent):
        UsdGeom.Xform.Define(stage, parent)
        parent = parent.GetParentPath()


def _define_mesh(stage: Usd.Stage, m: StageMesh) -> Usd.Prim:
    pts = np.ascontiguousarray(m.points, dtype=np.float32).reshape(-1, 3)
    tris = np.ascontiguousarray(m.triangles, dtype=np.int32).reshape(-1, 3)
    mesh = UsdGeom.Mesh.Define(stage, m.path)
    mesh.CreatePointsAttr(Vt.Vec3fArray.FromNumpy(pts))
    mesh.CreateFaceVertexCountsAttr(Vt.IntArray.FromNumpy(np.full(len(tris), 3, dtype=np.int32)))
    mesh.CreateFaceVertexIndicesAttr(Vt.IntArray.FromNumpy(tris.ravel()))
    mesh.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)
    mesh.CreateDoubleSidedAttr(True)
    if len(pts):
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        mesh.CreateExtentAttr(Vt.Vec3fArray([Gf.Vec3f(*map(float, lo)), Gf.Vec3f(*map(float, hi))]))
    if m.st is not None:
        st = np.ascontiguousarray(m.st, dtype=np.float32).reshape(-1, 2)
        interp = UsdGeom.Tokens.vertex if m.st_indices is None else UsdGeom.Tokens.faceVarying
        pv = UsdGeom.PrimvarsAPI(mesh).CreatePrimvar(looks.ST, Sdf.ValueTypeNames.TexCoord2fArray, interp)
        pv.Set(Vt.Vec2fArray.FromNumpy(st))
        if m.st_indices is not None:
            pv.SetIndices(Vt.IntArray.FromNumpy(np.ascontiguousarray(m.st_indices, dtype=np.int32).ravel()))
    if m.guide:
        mesh.CreatePurposeAttr(UsdGeom.Tokens.guide)
        mesh.CreateVisibilityAttr(UsdGeom.Tokens.invisible)
    return mesh.GetPrim()


def _vt_dict(d: Mapping[str, Any]) -> dict[str, Any]:
    """Metadata values usd-core can store: nested dicts, str, bool, int, float, float lists."""
    out: dict[str, Any] = {}
    for k, v in d.items():
        if isinstance(v, Mapping):
            out[k] = _vt_dict(v)
        elif isinstance(v, (str, bool, int, float)):
            out[k] = v
        elif isinstance(v, (list, tuple, np.ndarray)):
            out[k] = Vt.DoubleArray([float(x) for x in v])
        elif v is None:
            continue
        else:
            out[k] = str(v)
    return out


def warm_up() -> None:
    """Author a throw-away stage with every schema the builder uses, so usd-core loads
    its plugins now (~30 ms, once per process) rather than inside the first timed build.
    ``bench build`` calls it; importing the package does not (no import-time work)."""
    stage = Usd.Stage.CreateInMemory()
    mesh = UsdGeom.Mesh.Define(stage, "/W/M")
    UsdPhysics.Scene.Define(stage, "/W/P")
    UsdPhysics.CollisionAPI.Apply(mesh.GetPrim())
    UsdPhysics.MeshCollisionAPI.Apply(mesh.GetPrim())
    mat = looks.define_preview_material(stage, "Floor", (0.5, 0.5, 0.5), texture="./t.png")
    looks.bind(mesh.GetPrim(), mat)
    UsdPhysics.MaterialAPI.Apply(mat.GetPrim())
    stage.GetRootLayer().ExportToString()
