"""``preview --3d``: a lit 3D still of a built stage, rendered offscreen with VTK (the
``render3d`` extra), for everyone without Isaac Sim.

It shows what the stage holds, read back from the USD file: the floor, the ducts with
their rings in the stage's own material colours, the collision walls as the physics sees
them (drawn translucent: they are invisible in the simulator) and, when the source map
named in the stage is still there, the car at the env's grid start. VTK picks an
offscreen context itself: EGL or OSMesa (Mesa's software rasteriser) when there is no
display, so it runs headless on a machine without a GPU."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image, ImageDraw

from ..config.build import BuildConfig
from ..config.sim import SimConfig
from ..errors import ArenaError, ConfigError, MapFormatError
from ..track.drivable import track_from_map_path
from ..track.start_grid import GRID_OFFSET, GRID_SPACING, grid_poses
from ..usd import open_stage, read_meshes
from ..usd.metadata import StageMetadata, checked_source, stage_metadata_of
from .formats import image_format
from .topdown import font, save_image

#: Colour of the translucent collision walls and of the car.
WALL_RGB, CAR_RGB = (0.85, 0.15, 0.15), (0.84, 0.15, 0.16)
BACKGROUND = (0.93, 0.94, 0.96)


@dataclass
class StillSummary:
    """What the 3D still shows (the CLI prints it as JSON)."""

    output: str
    source: str
    size_px: tuple[int, int]
    drawn: list[str] = field(default_factory=list)
    car_pose: list[float] | None = None
    renderer: str = ""


def render_still(usd_path: str | Path, out: str | Path, size: tuple[int, int] = (1280, 800)) -> StillSummary:
    """Render the stage ``usd_path`` to the picture ``out`` (PNG or JPEG) from an oblique
    camera south-west of the track, lit by a light kit plus the camera's headlight."""
    image_format(out)
    vtk = _vtk()

    stage = open_stage(usd_path)
    meshes = read_meshes(stage)
    if not meshes:
        raise MapFormatError(f"{usd_path}: no meshes under /World/Track; not a RoboRacer Arena stage")
    meta = _metadata(stage, usd_path)
    colours = _material_colours(meta, usd_path)
    ren = vtk.vtkRenderer()
    ren.SetBackground(*BACKGROUND)
    drawn: list[str] = []
    for path, m in meshes.items():
        if not len(m.triangles):
            continue
        if path.endswith("/Floor"):
            _add(vtk, ren, m.points, m.triangles, colours["floor"], specular=0.1)
            drawn.append("floor")
        elif path.endswith("/Rings"):
            _add(vtk, ren, m.points, m.triangles, colours["ring"])
            drawn.append("rings")
        elif "/Barriers" in path:
            _add(vtk, ren, m.points, m.triangles, colours["duct"], specular=0.5)
            drawn.append("ducts")
        elif path.endswith("/Walls"):
            _add(vtk, ren, m.points, m.triangles, WALL_RGB, opacity=0.35)
            drawn.append("collision walls")
    car = _car_pose(meta, usd_path)
    if car is not None:
        _add_car(vtk, ren, car)
        drawn.append("car")
    lo = np.min([m.points.min(0) for m in meshes.values() if len(m.points)], axis=0)
    hi = np.max([m.points.max(0) for m in meshes.values() if len(m.points)], axis=0)
    _camera(ren, lo, hi, size)
    kit = vtk.vtkLightKit()
    kit.AddLightsToRenderer(ren)
    rgb, renderer = _render(vtk, ren, size)
    img = Image.fromarray(rgb)
    _caption(
        img, f"{Path(usd_path).name}: {', '.join(drawn)} (collision walls translucent; invisible in the simulator)"
    )
    save_image(img, out)
    return StillSummary(
        str(out), str(usd_path), img.size, drawn, None if car is None else [round(v, 3) for v in car], renderer
    )


def _vtk() -> Any:
    try:
        import vtkmodules.all as vtk  # the VTK wheel: offscreen EGL / OSMesa on Linux
    except ImportError as e:
        raise ConfigError("preview --3d needs the 'render3d' extra (pip install roboracer-arena[render3d])") from e
    vtk.vtkObject.GlobalWarningDisplayOff()  # e.g. "bad X server connection" before the EGL fallback
    return vtk


def _metadata(stage: Any, usd_path: str | Path) -> StageMetadata | None:
    """The stage's typed metadata, or None for a stage whose metadata does not read (a
    foreign or edited stage still renders its shapes, in the default colours)."""
    try:
        return stage_metadata_of(stage, usd_path)
    except ArenaError:
        return None


def _material_colours(meta: StageMetadata | None, usd_path: str | Path) -> dict[str, tuple[float, float, float]]:
    """Floor, duct and ring colours the stage was built with (its build config), else the defaults."""
    cfg = BuildConfig()
    if meta is not None and meta.build_config:
        try:
            cfg = meta.build_config_model(usd_path)
        except ArenaError:
            pass  # an older or foreign stage: default colours still show the shapes
    mc = cfg.materials
    return {"floor": mc.floor_colour, "duct": mc.duct_colour, "ring": mc.ring_colour}


def _car_pose(meta: StageMetadata | None, usd_path: str | Path) -> tuple[float, float, float] | None:
    """(x, y, yaw) of the env's grid start on the stage's source map, if it is still there
    as built (absolute path, same checksums; never a same-named map in the current folder)."""
    if meta is None:
        return None
    try:
        src = checked_source(usd_path, meta)
    except ArenaError:
        return None
    x, y, yaw = grid_poses(track_from_map_path(str(src)), 1, GRID_SPACING, GRID_OFFSET)[0]
    return float(x), float(y), float(yaw)


def _polydata(vtk: Any, points: np.ndarray, triangles: np.ndarray) -> Any:
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray

    pts = vtk.vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=np.float64), deep=True))
    tri = np.asarray(triangles, dtype=np.int64)
    cells = np.c_[np.full(len(tri), 3, np.int64), tri].ravel()
    arr = vtk.vtkCellArray()
    arr.SetCells(len(tri), numpy_to_vtkIdTypeArray(cells, deep=True))  # 64-bit ids in the VTK wheels
    poly = vtk.vtkPolyData()
    poly.SetPoints(pts)
    poly.SetPolys(arr)
    normals = vtk.vtkPolyDataNormals()
    normals.SetInputData(poly)
    normals.SplittingOff()
    normals.Update()
    return normals.GetOutput()


def _add(
    vtk: Any,
    ren: Any,
    points: np.ndarray,
    triangles: np.ndarray,
    rgb: tuple[float, float, float],
    opacity: float = 1.0,
    specular: float = 0.2,
) -> None:
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(_polydata(vtk, points, triangles))
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetColor(*rgb)
    prop.SetOpacity(opacity)
    prop.SetSpecular(specular)
    prop.SetSpecularPower(30)
    if opacity < 1:
        prop.BackfaceCullingOff()
    ren.AddActor(actor)


def _add_car(vtk: Any, ren: Any, pose: tuple[float, float, float]) -> None:
    """The env's car body (chassis length × width, 0.15 m tall) at ``pose``."""
    veh = SimConfig().vehicle
    box = vtk.vtkCubeSource()
    box.SetXLength(veh.chassis_length)
    box.SetYLength(veh.chassis_width)
    box.SetZLength(0.15)
    box.SetCenter(0.0, 0.0, 0.1)
    actor = vtk.vtkActor()
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(box.GetOutputPort())
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(*CAR_RGB)
    actor.SetPosition(pose[0], pose[1], 0.0)
    actor.SetOrientation(0.0, 0.0, math.degrees(pose[2]))
    ren.AddActor(actor)


def _camera(ren: Any, lo: np.ndarray, hi: np.ndarray, size: tuple[int, int]) -> None:
    """An oblique view from the south-west, 40° above the floor, framing the whole stage."""
    centre = (lo + hi) / 2
    centre[2] = 0.0
    extent = float(np.linalg.norm((hi - lo)[:2]))
    cam = ren.GetActiveCamera()
    cam.SetFocalPoint(*centre)
    elev, d = math.radians(40.0), 1.1 * extent
    sw = np.array([-math.sqrt(0.5), -math.sqrt(0.5)])  # looking north-east
    cam.SetPosition(centre[0] + d * math.cos(elev) * sw[0], centre[1] + d * math.cos(elev) * sw[1], d * math.sin(elev))
    cam.SetViewUp(0.0, 0.0, 1.0)
    cam.SetViewAngle(30.0)
    ren.ResetCamera()
    cam.Zoom(1.25)
    ren.ResetCameraClippingRange()


def _render(vtk: Any, ren: Any, size: tuple[int, int]) -> tuple[np.ndarray, str]:
    """Render offscreen; (H, W, 3) uint8 image, top row first, and the window class used."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetMultiSamples(8)
    win.AddRenderer(ren)
    win.SetSize(*size)
    win.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(win)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.Update()
    out = grab.GetOutput()
    w, h, _ = out.GetDimensions()
    rgb = vtk_to_numpy(out.GetPointData().GetScalars()).reshape(h, w, -1)[::-1, :, :3]
    name = type(win).__name__
    win.Finalize()
    return np.ascontiguousarray(rgb, dtype=np.uint8), name


def _caption(img: Image.Image, text: str) -> None:
    d = ImageDraw.Draw(img)
    d.text((12, 10), text, fill=(20, 20, 20), font=font(18), stroke_width=2, stroke_fill=(255, 255, 255))
