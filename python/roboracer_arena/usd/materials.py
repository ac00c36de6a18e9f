"""Materials under ``/World/Looks``: UsdPreviewSurface looks (optionally textured) and the
UsdPhysics material (friction, restitution) bound with the ``physics`` purpose."""

from __future__ import annotations

from pxr import Gf, Sdf, Usd, UsdPhysics, UsdShade

from ..config.build import StagePhysicsConfig
from .textures import SHADE_MEAN

LOOKS = "/World/Looks"
PHYSICS_MATERIAL = f"{LOOKS}/TrackPhysics"
ST = "st"  # the texture-coordinate primvar every textured mesh carries
DUCT_TEXTURE_TILE_M = 0.5  # metres of duct per texture tile (16 ribs → 3 cm rib pitch)


def define_preview_material(
    stage: Usd.Stage,
    name: str,
    colour: tuple[float, float, float],
    *,
    texture: str | None = None,
    roughness: float = 0.6,
    metallic: float = 0.0,
) -> UsdShade.Material:
    """A UsdPreviewSurface material ``/World/Looks/<name>``. With ``texture`` (an asset path
    relative to the stage) the diffuse colour comes from a UsdUVTexture read through the
    ``st`` primvar: a single-channel shade map (mean :data:`SHADE_MEAN`) scaled by
    ``colour / SHADE_MEAN``, so the mean colour is ``colour`` (also the fallback)."""
    mat = UsdShade.Material.Define(stage, f"{LOOKS}/{name}")
    surf = UsdShade.Shader.Define(stage, f"{LOOKS}/{name}/PreviewSurface")
    surf.CreateIdAttr("UsdPreviewSurface")
    surf.CreateInput("roughness", Sdf.ValueTypeNames.Float).Set(float(roughness))
    surf.CreateInput("metallic", Sdf.ValueTypeNames.Float).Set(float(metallic))
    diffuse = surf.CreateInput("diffuseColor", Sdf.ValueTypeNames.Color3f)
    rgb = Gf.Vec3f(*map(float, colour))
    if texture is None:
        diffuse.Set(rgb)
    else:
        st_name = mat.CreateInput("frame:stPrimvarName", Sdf.ValueTypeNames.String)
        st_name.Set(ST)
        reader = UsdShade.Shader.Define(stage, f"{LOOKS}/{name}/StReader")
        reader.CreateIdAttr("UsdPrimvarReader_float2")
        reader.CreateInput("varname", Sdf.ValueTypeNames.String).ConnectToSource(st_name)
        tex = UsdShade.Shader.Define(stage, f"{LOOKS}/{name}/DiffuseTexture")
        tex.CreateIdAttr("UsdUVTexture")
        tex.CreateInput("file", Sdf.ValueTypeNames.Asset).Set(Sdf.AssetPath(texture))
        tex.CreateInput("sourceColorSpace", Sdf.ValueTypeNames.Token).Set("raw")  # linear shade values
        gain = [c / SHADE_MEAN for c in rgb]
        tex.CreateInput("scale", Sdf.ValueTypeNames.Float4).Set(Gf.Vec4f(gain[0], gain[1], gain[2], 1.0))
        tex.CreateInput("wrapS", Sdf.ValueTypeNames.Token).Set("repeat")
        tex.CreateInput("wrapT", Sdf.ValueTypeNames.Token).Set("repeat")
        tex.CreateInput("fallback", Sdf.ValueTypeNames.Float4).Set(Gf.Vec4f(rgb[0], rgb[1], rgb[2], 1.0))
        tex.CreateInput("st", Sdf.ValueTypeNames.Float2).ConnectToSource(reader.ConnectableAPI(), "result")
        tex.CreateOutput("rgb", Sdf.ValueTypeNames.Float3)
        diffuse.ConnectToSource(tex.ConnectableAPI(), "rgb")
    mat.CreateSurfaceOutput().ConnectToSource(surf.ConnectableAPI(), "surface")
    return mat


def define_physics_material(stage: Usd.Stage, physics: StagePhysicsConfig) -> UsdShade.Material:
    """``/World/Looks/TrackPhysics``: static/dynamic friction and restitution of the track
    surfaces (one material, since the paper gives one tyre-surface friction)."""
    mat = UsdShade.Material.Define(stage, PHYSICS_MATERIAL)
    api = UsdPhysics.MaterialAPI.Apply(mat.GetPrim())
    api.CreateStaticFrictionAttr(float(physics.static_friction))
    api.CreateDynamicFrictionAttr(float(physics.dynamic_friction))
    api.CreateRestitutionAttr(float(physics.restitution))
    return mat


def bind(prim: Usd.Prim, material: UsdShade.Material, *, physics: bool = False) -> None:
    """Bind ``material`` to ``prim`` (all purposes, or the ``physics`` purpose)."""
    api = UsdShade.MaterialBindingAPI.Apply(prim)
    if physics:
        api.Bind(material, UsdShade.Tokens.weakerThanDescendants, "physics")
    else:
        api.Bind(material)
