"""The PhysX check of a built stage (``roboracer-arena physx-check``).

Loads the stage in PhysX (ovphysx, CPU) and measures what an Isaac Sim user relies on:

* **lidar parity**: a single-sided PhysX raycast scan (as a PhysX lidar casts it) from
  the env's grid start, beam for beam against our env's own scan;
* **containment**: car-sized rigid bodies (the chassis box of :class:`VehicleConfig`,
  its mass) sent at the walls from points along the track, at several angles and at
  speeds up to the car's top speed, on a frictionless contact so they arrive at full
  speed; none may leave the drivable corridor or fall below the floor;
* **load time** of the stage in PhysX.

The track our env drives is rebuilt from the stage's own metadata (source map and build
configuration), so both sides see the walls of the same build.

An open map (``map_kind`` "open" in the metadata: walls only, no centreline) is rebuilt
as the build made it (the same start and ``unknown_cells``); our scan is taken at the
env's start on it, the probes start from free points with room for the box spread over
the floor plan, and "inside" is the free region connected to the start
(:mod:`.open_probes`).
"""

from __future__ import annotations

import math
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import Field

from ..config.sim import SimConfig
from ..envs.env_config import EnvConfig
from ..envs.single import RoboRacerEnv
from ..errors import ConfigError
from ..foundation.fileio import require_regular
from ..foundation.frozen_model import FrozenModel
from ..maps.corridor import extract_corridor
from ..maps.direction import direction_for_map
from ..track.drivable import Track, track_from_corridor
from ..track.start_grid import centreline_pose
from ..usd.metadata import checked_source, read_stage_metadata
from .open_probes import FreeRegion, WallSegments, open_stations
from .runtime import PhysxScene, native_stdout_to_stderr, require

#: A beam agrees when PhysX and our lidar differ by at most this (m).
BEAM_TOLERANCE_M = 0.01
#: Fraction of agreeing beams the check requires.
MIN_BEAM_FRACTION = 0.99
#: Probe bodies lower than this (m, centre) have fallen through the floor.
FLOOR_LIMIT_M = -0.02
PROBE_ROOT = "/RoboRacerArenaProbes"
#: The car ``build --car`` authors: its chassis holds the sensor, so beams pass through it.
CAR_PATH = "/World/Car"


class LidarParity(FrozenModel):
    """PhysX single-sided scan vs our env's scan from the same pose."""

    beams: int
    within_tolerance: int
    fraction: float
    max_abs_error_m: float
    pose: tuple[float, float, float]
    ok: bool


class Escape(FrozenModel):
    """One probe body that left the corridor."""

    s_m: float = Field(description="Arc length of its start point along the centreline (0 on an open map).")
    start_xy: tuple[float, float] | None = Field(None, description="Its start point (map frame, m).")
    angle_deg: float = Field(description="Direction relative to the track heading.")
    speed_m_s: float
    final_xyz: tuple[float, float, float]
    reason: str


class Containment(FrozenModel):
    """Car-sized bodies sent at the walls."""

    bodies: int
    contained: int
    seconds_simulated: float
    points: int
    angles_deg: list[float]
    speeds_m_s: list[float]
    escapes: list[Escape] = Field(default_factory=list, description="At most the first 20.")
    ok: bool


class PhysxCheckReport(FrozenModel):
    """The whole check; ``ok`` only when every part holds."""

    stage: str
    map_kind: str = Field("track", description="'track' (a closed corridor) or 'open' (an open map).")
    physx_version: str
    load_seconds: float
    lidar: LidarParity
    containment: Containment
    seconds: float
    ok: bool

    def summary(self) -> str:
        """Human-readable lines."""
        lid, con = self.lidar, self.containment
        region = "free region" if self.map_kind == "open" else "corridor"
        where = "stations over the floor plan" if self.map_kind == "open" else "points"
        lines = [
            f"stage {self.stage} ({'open map' if self.map_kind == 'open' else 'track'}) in PhysX {self.physx_version} (CPU): loaded in {self.load_seconds:.2f} s",
            f"lidar parity: {lid.within_tolerance}/{lid.beams} single-sided beams within "
            f"{BEAM_TOLERANCE_M * 100:.0f} cm of our scan ({lid.fraction:.2%}, need {MIN_BEAM_FRACTION:.0%}; "
            f"max error {lid.max_abs_error_m:.4f} m) {'ok' if lid.ok else 'FAILED'}",
            f"containment: {con.contained}/{con.bodies} car-sized bodies stayed in the {region} "
            f"({con.points} {where} x {len(con.angles_deg)} angles x speeds {con.speeds_m_s} m/s, "
            f"{con.seconds_simulated:.1f} s) {'ok' if con.ok else 'FAILED'}",
        ]
        lines += [
            f"  escaped: from ({e.start_xy[0]:.2f}, {e.start_xy[1]:.2f}) angle={e.angle_deg:+.0f} deg "
            f"{e.speed_m_s:.1f} m/s -> {e.reason} at ({e.final_xyz[0]:.2f}, {e.final_xyz[1]:.2f}, {e.final_xyz[2]:.2f})"
            if self.map_kind == "open" and e.start_xy is not None
            else f"  escaped: s={e.s_m:.1f} m angle={e.angle_deg:+.0f} deg {e.speed_m_s:.1f} m/s -> {e.reason} "
            f"at ({e.final_xyz[0]:.2f}, {e.final_xyz[1]:.2f}, {e.final_xyz[2]:.2f})"
            for e in con.escapes[:5]
        ]
        lines.append(f"PhysX check {'passed' if self.ok else 'FAILED'} in {self.seconds:.1f} s")
        return "\n".join(lines)


def track_of_stage(stage_path: str | Path) -> Any:
    """The :class:`~roboracer_arena.track.drivable.Track` of a built stage (source map and build
    configuration from its metadata), in the map's racing direction. An open map's stage
    (``map_kind`` "open") gives the open map the build made: the same start pose and
    ``unknown_cells``; its ``source`` is the corridor geometry (raster and free mask)."""
    path = Path(stage_path)
    meta = read_stage_metadata(path)
    src = checked_source(path, meta)  # the map it was built from, unchanged, or an error naming both
    cfg = meta.build_config_model(path)
    start = meta.start
    if meta.map_kind == "open":
        geo = extract_corridor(
            src,
            params=cfg.geometry_params(),
            start=tuple(start) if start else None,
            open=True,
            unknown=meta.unknown_cells,
        )
        return track_from_corridor(geo, src.stem)
    geo = extract_corridor(src, params=cfg.geometry_params(), start=tuple(start) if start else None)
    track = Track.from_polylines(list(geo.walls), geo.centreline, name=src.stem, wall_height=cfg.geometry.wall_height_m)
    return track.oriented(direction_for_map(src))


def env_scan(track: Any, sim: SimConfig) -> tuple[np.ndarray, tuple[float, float, float]]:
    """Our env's first scan (raw ranges, m) at its grid start, and the car's pose."""
    env = RoboRacerEnv(track=track, config=EnvConfig(sim=sim))
    try:
        obs, _ = env.reset(seed=0)
        state, idx = env.simulator_state
        pose = (float(state[0, idx["x"]]), float(state[0, idx["y"]]), float(state[0, idx["yaw"]]))
        return np.asarray(obs["scan"], dtype=np.float64).reshape(-1), pose
    finally:
        env.close()


def physx_scan(scene: PhysxScene, pose: tuple[float, float, float], sim: SimConfig) -> np.ndarray:
    """Single-sided PhysX raycasts laid out as our lidar's beams (same mount, angles, range)."""
    lid = sim.lidar
    x, y, yaw = pose
    ox, oy = x + lid.mount_x * math.cos(yaw), y + lid.mount_x * math.sin(yaw)
    n = lid.num_beams
    inc = lid.fov / (n - 1) if n > 1 else 0.0
    start = -0.5 * lid.fov if n > 1 else 0.0
    out = np.empty(n)
    for k in range(n):
        a = yaw + start + k * inc
        ray = scene.raycast((ox, oy, lid.mount_z), (math.cos(a), math.sin(a), 0.0), lid.range_max, ignore=CAR_PATH)
        out[k] = min(ray, lid.range_max)
    return out


def compare_scans(ours: np.ndarray, physx: np.ndarray, pose: tuple[float, float, float]) -> LidarParity:
    """Beam-by-beam agreement within :data:`BEAM_TOLERANCE_M`."""
    err = np.abs(ours - physx)
    within = int(np.count_nonzero(err <= BEAM_TOLERANCE_M))
    frac = within / len(ours) if len(ours) else 0.0
    return LidarParity(
        beams=len(ours),
        within_tolerance=within,
        fraction=frac,
        max_abs_error_m=float(err.max()) if len(err) else 0.0,
        pose=pose,
        ok=frac >= MIN_BEAM_FRACTION,
    )


def inside_corridor(walls: list[np.ndarray], xy: np.ndarray) -> np.ndarray:
    """Even–odd point-in-region over every wall loop: True where drivable."""
    inside = np.zeros(len(xy), dtype=bool)
    px, py = xy[:, 0][:, None], xy[:, 1][:, None]
    for w in walls:
        a, b = w, np.roll(w, -1, axis=0)
        ax, ay, bx, by = a[:, 0][None], a[:, 1][None], b[:, 0][None], b[:, 1][None]
        crosses = (ay > py) != (by > py)
        with np.errstate(divide="ignore", invalid="ignore"):
            xint = ax + (py - ay) / (by - ay) * (bx - ax)
        inside ^= (np.count_nonzero(crosses & (px < xint), axis=1) % 2).astype(bool)
    return inside


def probe_plan(
    track: Any, sim: SimConfig, points: int, free: FreeRegion | None = None
) -> list[tuple[float, float, float, float, float, float]]:
    """``(s, x, y, yaw, angle, speed)`` of each probe: ``points`` stations along the
    centreline, eight directions about the local heading, three speeds up to the top speed.
    On an open map (``free``: its free region) the stations are :func:`open_stations`
    (``s`` 0, the heading along the nearest wall)."""
    angles = (-150.0, -90.0, -45.0, -20.0, 20.0, 45.0, 90.0, 150.0)
    top = float(sim.vehicle.max_speed)
    speeds = (top / 3.0, 2.0 * top / 3.0, top)
    if free is not None:
        veh = sim.vehicle
        x0, y0 = (float(v) for v in track.centreline[0])
        half_diagonal = 0.5 * math.hypot(veh.chassis_length, veh.chassis_width)
        stations = [(0.0, *p) for p in open_stations(free, (x0, y0), points, half_diagonal)]
    else:
        stations = [
            (track.length * (i + 0.5) / points, *centreline_pose(track, track.length * (i + 0.5) / points))
            for i in range(points)
        ]
    plan = []
    for s, x, y, yaw in stations:
        for a in angles:
            for v in speeds:
                plan.append((s, x, y, yaw, a, v))
    return plan


def write_probe_stage(track_stage: Path, plan: Sequence[tuple[float, ...]], sim: SimConfig, out: Path) -> list[str]:
    """A stage that sublayers the track stage and adds one chassis-sized box per probe,
    launched by its initial velocity. Probes do not collide with each other (a filtered
    collision group) and touch the floor without friction. Returns the probe prim paths."""
    from pxr import Gf, Sdf, Usd, UsdGeom, UsdPhysics, UsdShade

    veh = sim.vehicle
    stage = Usd.Stage.CreateNew(str(out))
    stage.GetRootLayer().subLayerPaths.append(str(track_stage.resolve()))
    UsdGeom.Scope.Define(stage, PROBE_ROOT)
    mat = UsdShade.Material.Define(stage, f"{PROBE_ROOT}/Frictionless")
    mapi = UsdPhysics.MaterialAPI.Apply(mat.GetPrim())
    mapi.CreateStaticFrictionAttr(0.0)
    mapi.CreateDynamicFrictionAttr(0.0)
    mapi.CreateRestitutionAttr(0.0)
    from physx_usd_schemas import PhysxSchema

    pm: Any = PhysxSchema.PhysxMaterialAPI.Apply(mat.GetPrim())
    pm.CreateFrictionCombineModeAttr("min")
    group = UsdPhysics.CollisionGroup.Define(stage, f"{PROBE_ROOT}/Group")
    group.CreateFilteredGroupsRel().AddTarget(group.GetPath())
    includes = group.GetCollidersCollectionAPI().CreateIncludesRel()
    z = veh.chassis_clearance + veh.chassis_height / 2.0
    paths = []
    for k, (_, x, y, yaw, angle, speed) in enumerate(plan):
        path = f"{PROBE_ROOT}/Body{k:04d}"
        cube = UsdGeom.Cube.Define(stage, path)
        cube.CreateSizeAttr(1.0)
        heading = yaw + math.radians(angle)
        xf = UsdGeom.Xformable(cube)
        xf.AddTranslateOp().Set(Gf.Vec3d(x, y, z))
        xf.AddRotateZOp().Set(math.degrees(heading))
        xf.AddScaleOp().Set(Gf.Vec3f(veh.chassis_length, veh.chassis_width, veh.chassis_height))
        prim = cube.GetPrim()
        UsdPhysics.CollisionAPI.Apply(prim)
        body = UsdPhysics.RigidBodyAPI.Apply(prim)
        body.CreateVelocityAttr(Gf.Vec3f(speed * math.cos(heading), speed * math.sin(heading), 0.0))
        UsdPhysics.MassAPI.Apply(prim).CreateMassAttr(float(veh.mass))
        UsdShade.MaterialBindingAPI.Apply(prim).Bind(mat, UsdShade.Tokens.weakerThanDescendants, "physics")
        includes.AddTarget(Sdf.Path(path))
        paths.append(path)
    stage.GetRootLayer().Save()
    return paths


def containment(
    stage_path: Path, track: Any, sim: SimConfig, points: int, seconds: float, workdir: Path
) -> Containment:
    """Send the probes, step ``seconds`` at the simulator's dt, check every 10 steps (every
    2 on an open map, whose bodies must also not pass through a wall between checks)."""
    free = FreeRegion.of_geometry(track.source, tuple(track.centreline[0])) if track.is_open else None
    plan = probe_plan(track, sim, points, free)
    if not plan:
        raise ConfigError(f"{stage_path}: no free point of the open map has room for a car-sized probe body")
    probe_file = workdir / "probes.usda"
    paths = write_probe_stage(stage_path, plan, sim, probe_file)
    walls = [np.asarray(w, dtype=np.float64) for w in track.walls]
    segments = WallSegments(walls) if free is not None else None
    dt = float(sim.physics.dt)
    steps = max(1, round(seconds / dt))
    reasons: dict[int, tuple[str, np.ndarray]] = {}
    left = "left the free region" if free is not None else "left the corridor"
    index = {p: k for k, p in enumerate(paths)}
    # an open map's bodies are also followed along their paths (crosses_walls), so they are
    # sampled often enough that a bounce never spans a wall
    every = 2 if free is not None else 10
    last = np.array([(x, y) for _, x, y, *_ in plan], dtype=np.float64)
    with PhysxScene(probe_file) as scene:
        done = 0
        while done < steps:
            n = min(every, steps - done)
            scene.step(dt, n)
            done += n
            bodies = scene.read_bodies(["position"])
            pos = np.zeros((len(paths), 3))
            for p, attrs in bodies.items():
                if p in index:
                    pos[index[p]] = attrs["position"][:3]
            if free is None:
                out = ~inside_corridor(walls, pos[:, :2])
                through = np.zeros(len(pos), dtype=bool)
            else:
                out = ~free.contains(pos[:, :2])
                assert segments is not None
                through = segments.crossed(last, pos[:, :2])
                last = pos[:, :2].copy()
            low = pos[:, 2] < FLOOR_LIMIT_M
            for k in np.flatnonzero(out | low | through):
                why = "below the floor" if low[k] else left if out[k] else "passed through a wall"
                reasons.setdefault(int(k), (why, pos[k].copy()))
    escapes = [
        Escape(
            s_m=plan[k][0],
            start_xy=(plan[k][1], plan[k][2]),
            angle_deg=plan[k][4],
            speed_m_s=plan[k][5],
            final_xyz=(float(p[0]), float(p[1]), float(p[2])),
            reason=why,
        )
        for k, (why, p) in sorted(reasons.items())[:20]
    ]
    return Containment(
        bodies=len(plan),
        contained=len(plan) - len(reasons),
        seconds_simulated=steps * dt,
        points=points if free is None else len({(x, y) for _, x, y, *_ in plan}),
        angles_deg=sorted({a for *_, a, _ in plan}),
        speeds_m_s=sorted({round(v, 3) for *_, v in plan}),
        escapes=escapes,
        ok=not reasons,
    )


def check_stage(
    stage_path: str | Path, sim: SimConfig | None = None, points: int = 12, seconds: float = 2.0
) -> PhysxCheckReport:
    """Run the whole check on a stage file; raises :class:`ConfigError` without the
    ``physx`` extra, :class:`MapIOError` for an unreadable stage (naming a directory or a
    symlink loop as such) or a source map that is missing or has changed since the build,
    :class:`MapFormatError` for metadata that does not read. Whatever the native engine
    prints on stdout meanwhile goes to stderr (:func:`native_stdout_to_stderr`)."""
    path = Path(stage_path)
    require_regular(path, "USD stage")  # names a directory, a FIFO, a symlink loop, a missing file
    with native_stdout_to_stderr():  # the engine's own prints (e.g. its GPU warnings) never reach stdout
        ovphysx, _ = require()
        t0 = time.perf_counter()
        sim = sim or SimConfig()
        track = track_of_stage(path)
        ours, pose = env_scan(track, sim)
        with PhysxScene(path) as scene:
            load = scene.load_seconds
            theirs = physx_scan(scene, pose, sim)
        lidar = compare_scans(ours, theirs, pose)
        with tempfile.TemporaryDirectory(prefix="roboracer-physx-") as tmp:
            cont = containment(path, track, sim, points, seconds, Path(tmp))
    return PhysxCheckReport(
        stage=str(path),
        map_kind=str(track.kind),
        physx_version=str(ovphysx.__version__),
        load_seconds=load,
        lidar=lidar,
        containment=cont,
        seconds=time.perf_counter() - t0,
        ok=lidar.ok and cont.ok,
    )
