"""The paper's car as a PhysX vehicle on the stage (``build --car``; the ``physx`` extra).

A four-wheel PhysX vehicle (``PhysxVehicle*`` APIs, drive "basic": one torque shared by
the four driven wheels through a multi-wheel differential, as the Traxxas' 4WD) built
from :class:`~roboracer_arena.sim_config.VehicleConfig`: chassis box, mass, yaw inertia,
axle positions, track width, wheel radius and inertia, suspension spring, damper and
travel, tyre friction and stiffnesses, steering limit. ovphysx drives it on the CPU
(``SimObjectType.VEHICLE``: ``accelerator``, ``brake0``, ``steer``); Isaac Sim reads the
same schemas. Z up, X forward; the body frame sits at the centre of mass.

Prims: ``/World/Car`` (rigid body + vehicle), ``/World/Car/Chassis`` (collision box),
``/World/Car/{FrontLeft,FrontRight,RearLeft,RearRight}Wheel`` (wheel attachments),
``/World/CarParts/*`` (wheel, tyres, suspension, drive, friction table, collision groups).
"""

from __future__ import annotations

import math
from typing import Any

from pxr import Gf, Sdf, Usd, UsdGeom, UsdPhysics

from ..direction import direction_for_map
from ..errors import ConfigError
from ..sim_config import SimConfig
from ..start_grid import centreline_pose, grid_start_s
from ..track import Track
from . import physx_schemas
from .materials import PHYSICS_MATERIAL

CAR = "/World/Car"
PARTS = "/World/CarParts"
WHEELS = ("FrontLeftWheel", "FrontRightWheel", "RearLeftWheel", "RearRightWheel")
#: Peak drive torque at the wheels (N m): 4.885 kg at ~6 m/s^2 on 0.0525 m wheels
#: (1.5 N m), with margin for drag and rolling resistance.
PEAK_TORQUE_NM = 2.0
#: Brake torque per wheel (N m): ~1 g of deceleration on the 1:10 car.
MAX_BRAKE_TORQUE_NM = 0.7
#: Speed (m/s) at which the wheels' linear damping matches our rolling resistance and
#: drag: the reference driver's top speed.
RESISTANCE_SPEED = 5.0
#: PhysX lateral stiffness over our cornering stiffness x load: an empirical calibration
#: (issue #23 note, "Monaco lap"). Mapped 1:1, the PhysX car yawed at 0.85-0.91 of the
#: kinematic rate for its steer, drifted 0.4 m off the line out of Monaco's first bend and
#: hit a wall; x1.5 still hit one; x2, x2.5, x3, x4 lap Monaco with mean deviation 0.129,
#: 0.104, 0.088, 0.071 m (ours 0.076) and lap 82.9, 82.3, 81.95, 81.4 s (ours 81.85).
LATERAL_STIFFNESS_GAIN = 3.0


def author_car(stage: Usd.Stage, sim: SimConfig, pose: tuple[float, float, float]) -> str:
    """Author the car at ``pose`` (x, y, yaw on the floor); returns the car's prim path.
    Raises :class:`ConfigError` without the ``physx`` extra (the vehicle schemas)."""
    if not physx_schemas.register():
        raise ConfigError(
            "build --car needs the 'physx' extra for the PhysX vehicle schemas: pip install 'roboracer-arena[physx]'"
        )
    from physx_usd_schemas import PhysxSchema as P

    v = sim.vehicle
    g = 9.81
    scene = stage.GetPrimAtPath("/World/PhysicsScene")
    ctx: Any = P.PhysxVehicleContextAPI.Apply(scene)
    ctx.CreateUpdateModeAttr("velocityChange")
    ctx.CreateVerticalAxisAttr("posZ")
    ctx.CreateLongitudinalAxisAttr("posX")

    UsdGeom.Scope.Define(stage, PARTS)
    # Suspension raycasts must not see the car's own chassis.
    chassis_group = UsdPhysics.CollisionGroup.Define(stage, f"{PARTS}/ChassisGroup")
    query_group = UsdPhysics.CollisionGroup.Define(stage, f"{PARTS}/GroundQueryGroup")
    query_group.CreateFilteredGroupsRel().AddTarget(chassis_group.GetPath())

    table: Any = P.PhysxVehicleTireFrictionTable.Define(stage, f"{PARTS}/TireFriction")
    table.CreateGroundMaterialsRel().AddTarget(Sdf.Path(PHYSICS_MATERIAL))
    table.CreateFrictionValuesAttr([float(v.tyre_friction)])
    table.CreateDefaultFrictionValueAttr(float(v.tyre_friction))

    wheel: Any = P.PhysxVehicleWheelAPI.Apply(UsdGeom.Scope.Define(stage, f"{PARTS}/Wheel").GetPrim())
    wheel.CreateRadiusAttr(float(v.wheel_radius))
    wheel.CreateWidthAttr(0.045)
    wheel.CreateMassAttr(0.12)
    wheel.CreateMoiAttr(float(v.wheel_inertia))
    wheel.CreateDampingRateAttr(_wheel_damping(sim))

    load = v.mass * g / 4.0  # static load per wheel (N)
    tyres = {}
    for name, c_alpha in (("FrontTire", v.cornering_stiffness_front), ("RearTire", v.cornering_stiffness_rear)):
        tyre: Any = P.PhysxVehicleTireAPI.Apply(UsdGeom.Scope.Define(stage, f"{PARTS}/{name}").GetPrim())
        # (load in N where the graph flattens, lateral stiffness there in N/rad): linear in the
        # load up to twice the static load, so at rest it is the cornering stiffness x load
        # (x the measured LATERAL_STIFFNESS_GAIN).
        tyre.CreateLateralStiffnessGraphAttr(
            Gf.Vec2f(float(2.0 * load), float(LATERAL_STIFFNESS_GAIN * c_alpha * 2.0 * load))
        )
        tyre.CreateLongitudinalStiffnessAttr(float(v.longitudinal_stiffness * load))
        tyre.CreateCamberStiffnessAttr(0.0)
        tyre.CreateFrictionVsSlipGraphAttr([Gf.Vec2f(0.0, 1.0), Gf.Vec2f(0.1, 1.0), Gf.Vec2f(1.0, 1.0)])
        tyre.CreateFrictionTableRel().AddTarget(table.GetPath())
        tyres[name] = tyre.GetPrim().GetPath()

    susp: Any = P.PhysxVehicleSuspensionAPI.Apply(UsdGeom.Scope.Define(stage, f"{PARTS}/Suspension").GetPrim())
    susp.CreateSpringStrengthAttr(float(v.suspension_stiffness))
    susp.CreateSpringDamperRateAttr(float(v.suspension_damping))
    susp.CreateTravelDistanceAttr(float(v.suspension_travel))

    drive: Any = P.PhysxVehicleDriveBasicAPI.Apply(UsdGeom.Scope.Define(stage, f"{PARTS}/Drive").GetPrim())
    drive.CreatePeakTorqueAttr(PEAK_TORQUE_NM)

    # The body frame at the centre of mass, `com_height` above the floor.
    x, y, yaw = pose
    car = UsdGeom.Xform.Define(stage, CAR)
    car.AddTranslateOp().Set(Gf.Vec3d(x, y, v.com_height))
    car.AddOrientOp().Set(Gf.Quatf(math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2)))
    prim = car.GetPrim()
    UsdPhysics.RigidBodyAPI.Apply(prim)
    mass = UsdPhysics.MassAPI.Apply(prim)
    mass.CreateMassAttr(float(v.mass))
    mass.CreateCenterOfMassAttr(Gf.Vec3f(0.0, 0.0, 0.0))
    # Yaw inertia is the paper's; roll and pitch those of the chassis box.
    ixx = v.mass * (v.chassis_width**2 + v.chassis_height**2) / 12.0
    iyy = v.mass * (v.chassis_length**2 + v.chassis_height**2) / 12.0
    mass.CreateDiagonalInertiaAttr(Gf.Vec3f(ixx, iyy, float(v.yaw_inertia)))
    mass.CreatePrincipalAxesAttr(Gf.Quatf(1.0, 0.0, 0.0, 0.0))
    body: Any = P.PhysxRigidBodyAPI.Apply(prim)
    body.CreateEnableCCDAttr(True)
    body.CreateSleepThresholdAttr(0.0)
    body.CreateStabilizationThresholdAttr(0.0)
    body.CreateDisableGravityAttr(True)  # the vehicle's suspension carries the weight (PhysX vehicle convention)

    veh: Any = P.PhysxVehicleAPI.Apply(prim)
    veh.CreateVehicleEnabledAttr(True)
    veh.CreateDriveRel().AddTarget(drive.GetPrim().GetPath())
    veh.CreateSuspensionLineQueryTypeAttr("raycast")
    veh.CreateSubStepThresholdLongitudinalSpeedAttr(2.0)
    veh.CreateLowForwardSpeedSubStepCountAttr(3)
    veh.CreateHighForwardSpeedSubStepCountAttr(1)
    veh.CreateMinPassiveLongitudinalSlipDenominatorAttr(1.0)
    veh.CreateMinActiveLongitudinalSlipDenominatorAttr(0.1)
    veh.CreateMinLateralSlipDenominatorAttr(0.5)
    ctl: Any = P.PhysxVehicleControllerAPI.Apply(prim)
    for attr in (ctl.CreateAcceleratorAttr, ctl.CreateBrake0Attr, ctl.CreateBrake1Attr, ctl.CreateSteerAttr):
        attr(0.0)
    ctl.CreateTargetGearAttr(1)
    brakes: Any = P.PhysxVehicleBrakesAPI.Apply(prim, "brakes0")
    brakes.CreateMaxBrakeTorqueAttr(MAX_BRAKE_TORQUE_NM)
    brakes.CreateWheelsAttr([0, 1, 2, 3])
    steer: Any = P.PhysxVehicleSteeringAPI.Apply(prim)
    steer.CreateMaxSteerAngleAttr(float(v.max_steer))
    steer.CreateWheelsAttr([0, 1])
    diff: Any = P.PhysxVehicleMultiWheelDifferentialAPI.Apply(prim)
    diff.CreateWheelsAttr([0, 1, 2, 3])
    diff.CreateTorqueRatiosAttr([0.25, 0.25, 0.25, 0.25])
    diff.CreateAverageWheelSpeedRatiosAttr([0.25, 0.25, 0.25, 0.25])

    box = UsdGeom.Cube.Define(stage, f"{CAR}/Chassis")
    box.CreateSizeAttr(1.0)
    bx = UsdGeom.Xformable(box)
    bx.AddTranslateOp().Set(Gf.Vec3d(0.0, 0.0, v.chassis_clearance + v.chassis_height / 2.0 - v.com_height))
    bx.AddScaleOp().Set(Gf.Vec3f(v.chassis_length, v.chassis_width, v.chassis_height))
    UsdPhysics.CollisionAPI.Apply(box.GetPrim())
    chassis_group.GetCollidersCollectionAPI().CreateIncludesRel().AddTarget(box.GetPath())

    # The suspension frame is the wheel centre at full compression; at rest the spring is
    # compressed by the static sag, so the wheel centre sits at its radius above the floor.
    sag = min(load / v.suspension_stiffness, 0.9 * v.suspension_travel)
    frame_z = v.wheel_radius + (v.suspension_travel - sag) - v.com_height
    half = v.track_width / 2.0
    spots = ((v.com_to_front, half), (v.com_to_front, -half), (-v.com_to_rear, half), (-v.com_to_rear, -half))
    for k, (name, (wx, wy)) in enumerate(zip(WHEELS, spots)):
        w = UsdGeom.Xform.Define(stage, f"{CAR}/{name}")
        att: Any = P.PhysxVehicleWheelAttachmentAPI.Apply(w.GetPrim())
        att.CreateIndexAttr(k)
        att.CreateWheelRel().AddTarget(wheel.GetPrim().GetPath())
        att.CreateTireRel().AddTarget(tyres["FrontTire" if k < 2 else "RearTire"])
        att.CreateSuspensionRel().AddTarget(susp.GetPrim().GetPath())
        att.CreateCollisionGroupRel().AddTarget(query_group.GetPath())
        att.CreateSuspensionTravelDirectionAttr(Gf.Vec3f(0.0, 0.0, -1.0))
        att.CreateSuspensionFramePositionAttr(Gf.Vec3f(wx, wy, frame_z))
        att.CreateSuspensionFrameOrientationAttr(Gf.Quatf(1.0, 0.0, 0.0, 0.0))
        w.AddTranslateOp().Set(Gf.Vec3d(wx, wy, frame_z - (v.suspension_travel - sag)))
    return CAR


def _wheel_damping(sim: SimConfig) -> float:
    """Wheel damping rate (N m s/rad per wheel): PhysX's only speed-dependent loss on a
    basic-drive wheel, set so that at :data:`RESISTANCE_SPEED` it resists as much as our
    rolling resistance plus aerodynamic drag. (The former fixed 0.0025 cost 16 N at
    4.5 m/s, 14 times ours: the car topped out there on a 5 m/s command.)"""
    v, g = sim.vehicle, 9.81
    force = v.rolling_resistance * v.mass * g + 0.5 * 1.2 * v.drag_area * RESISTANCE_SPEED**2
    omega = RESISTANCE_SPEED / v.wheel_radius
    return force * v.wheel_radius / omega / 4.0


def grid_start_pose(geo: Any, cfg: Any, source: str) -> tuple[float, float, float]:
    """The env's grid start (x, y, yaw) on a freshly built corridor: the same track the
    env drives (walls, centreline in the map's racing direction) and the same rule."""
    from pathlib import Path

    track = Track.from_polylines(list(geo.walls), geo.centreline, wall_height=cfg.geometry.wall_height_m)
    if source and Path(source).is_file():
        track = track.oriented(direction_for_map(Path(source)))
    return tuple(float(c) for c in centreline_pose(track, grid_start_s(track)))  # type: ignore[return-value]
