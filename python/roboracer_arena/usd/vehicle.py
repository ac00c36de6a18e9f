"""The paper's car as a PhysX vehicle on the stage (``build --car``; the ``physx`` extra).

A four-wheel PhysX vehicle (``PhysxVehicle*`` APIs, drive "basic": one torque shared by the
four driven wheels through a multi-wheel differential with equal ratios, as our open
differentials) built from one :class:`~roboracer_arena.config.sim.VehicleConfig`. No
number in it was chosen to match a lap time: each is derived below from the config, and
:func:`physx_params` returns them. ovphysx drives it on the CPU (``SimObjectType.VEHICLE``:
``accelerator``, ``brake0``, ``steer``), with :mod:`roboracer_arena.physx.drive` running
the same servo, speed loop, motor and losses as our vehicle model around it. Z up, X
forward; the body frame sits at the centre of mass.

Derivation, our model (``arena_core::sim::vehicle``) -> PhysX vehicle 2
(``VhTireFunctions.cpp``, ``VhSteeringFunctions.cpp``):

* **Mass and inertia.** Mass and yaw inertia are the config's; roll and pitch inertia are
  the chassis box's scaled by the ratio that maps the box's yaw inertia to ``yaw_inertia``
  (ours, ``VehicleModel::mass_properties``). No linear or angular damping (PhysX's default
  angular damping 0.05 would be a yaw damper ours has not).
* **Steering.** Ours turns a virtual centre wheel by ``delta`` and sets the front wheels to
  exact Ackermann angles ``atan(L tan d / (L -+ t tan d))`` (``t`` half the track). PhysX's
  ``PhysxVehicleAckermannSteeringAPI`` (strength 1) gives the commanded angle to the inner
  wheel and sets the outer one to ``atan(L / (T + L / tan d_in))`` (``T`` the track), which
  is our outer angle when ``d_in`` is our inner angle. So the Ackermann ``maxSteerAngle`` is
  our inner angle at ``max_steer`` and the drive commands ``inner(delta) / inner(max_steer)``
  (:func:`ackermann_command`); the servo lag and rate limit act on ``delta`` in the drive
  loop, as ours does.
* **Lateral tyre force.** Ours: ``F = C_a N alpha``, clipped to ``mu N`` (the friction
  ellipse), ``alpha = atan(v_lat / max(|v_long|, 0.5))``. PhysX's tyre (the Michigan/brush
  model) is ``F = mu N Fbar(K)``, ``K = k tan(alpha) / (mu N)``, ``Fbar = K - K^2/3 + K^3/27``
  up to ``K = 3``, then 1, with ``alpha = atan(v_lat / (|v_long| + d))``. Its slope at zero
  slip is ``k``, the lateral stiffness, which PhysX takes from the load through a graph
  ``(X, Y)``: ``k = Y f1(3 x / X)``, ``f1`` the same cubic, ``x`` the tyre's load over its rest
  load (measured in ovphysx 0.7: ``X`` is compared with ``x``, not with the load in N). A knee
  ``X`` below any load (:data:`LOAD_KNEE`) makes ``k = Y``; ``Y = C_a N0`` (``N0`` the axle's
  static load per wheel) is ours at ``N0``, and ours summed over an axle under any lateral
  load transfer (``C_a (N_l + N_r) = 2 C_a N0``); measured at 3 m/s: ``k / Y = 0.98``, the
  brush curve's own bend at that slip. The peak is ``mu N`` in both (the friction table holds
  ``tyre_friction`` through the load filter, below; the friction-vs-slip graph is flat at 1).
  With ``VehicleConfig.lateral_tyre = "brush"`` our engine uses this same law
  (``mu N Fbar(C_a N0 tan(alpha) / (mu N))``, the stiffness fixed at the static load), so the
  two tyres are one law; PhysX's load filter and combined slip remain its own. With the
  default ``"linear"`` what is left differs in shape, not in any parameter: the brush curve
  bends over earlier than ours (at our saturation slip ``alpha* = mu / C_a`` it gives
  ``0.70 mu N`` where ours gives ``mu N``) and reaches ``mu N`` at ``3 alpha*``; both share the
  slope at zero slip and the friction limit, and the brush needs about 15 % more slip below
  0.4 mu g (the understeer gradient there; BENCHMARKS.md, "One car, two engines").
  The slip reference ``d`` (``minLateralSlipDenominator``) is 0.05 m/s, so that above
  0.5 m/s PhysX's slip angle is within 10 % of ours (1 % at 5 m/s).
* **Tyre load.** PhysX's tyre does not see the suspension force ``N`` but a filtered load
  ``N_t = R (a + b N / R)`` for ``N <= 3 R`` (``R`` the tyre's rest load; PhysX's default
  filter, not settable through USD: ``a = 0.2308``, ``b = (3 - a) / 3``; measured in ovphysx
  0.7 on a locked wheel, where ``F = mu N_t``), which damps load transfer by ``1 - b`` = 23 %.
  ``R = N0 / 2`` (:data:`REST_LOAD_FRACTION`) keeps loads up to ``1.5 N0`` inside the filter
  and halves the offset ``a R``; the friction table holds ``mu N0 / (a R + b N0)`` so that
  ``mu_t N_t = mu N`` at the static load, and within ``0.11 mu |N - N0|`` elsewhere.
* **Longitudinal tyre force.** Ours: ``C_x N kappa`` to the ellipse; PhysX: the same brush
  law with ``longitudinalStiffness`` in N per unit slip, load independent, so it is
  ``C_x N0`` per axle.
* **Drive and brakes.** The speed loop, motor current lag and current window (back-EMF) run
  in the drive loop; the wheel torque they ask goes to the basic drive, whose peak torque
  is the torque at ``max_motor_current`` (``force_per_amp * I * r``, ``force_per_amp = 60 /
  (2 pi kv) * gear_ratio / r``), and a torque against the wheels' rotation (motor braking)
  to the brakes at up to the ``max_brake_current`` torque per wheel. The wheels' own
  damping is 0. The losses are one wrench on the chassis each step: aerodynamic drag
  (``0.5 rho C_d A v^2``) and each wheel's rolling resistance, ``C_rr N`` from that wheel's
  own suspension load at its own contact patch, faded in over 0.1 m/s of its own surface
  speed, as ours applies it per wheel. (The basic drive splits one torque equally; a
  resistance taken out of that torque would be shared equally too, and in a turn the
  lighter inner wheels would resist as much as the outer ones: that alone made PhysX's
  understeer gradient 10 % lower than ours.)
* **Integration.** :data:`VEHICLE_SUBSTEPS` vehicle sub-steps from 2 m/s: two already
  give the result that more sub-steps or a halved step give; one does not. Below 2 m/s,
  :data:`LOW_SPEED_SUBSTEPS`: fewer let the braked wheels lock and release step after step
  (see the constants).
* **Suspension.** Spring, damper and travel are the config's; tyre and suspension forces
  act at the contact patch at rest (``PhysxVehicleSuspensionComplianceAPI``), as ours
  applies them at the contact point.

Prims: ``/World/Car`` (rigid body + vehicle), ``/World/Car/Chassis`` (collision box),
``/World/Car/{FrontLeft,FrontRight,RearLeft,RearRight}Wheel`` (wheel attachments),
``/World/CarParts/*`` (wheel, tyres, suspension, drive, friction table, collision groups).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pxr import Gf, Sdf, Usd, UsdGeom, UsdPhysics

from ..config.sim import SimConfig, VehicleConfig
from ..errors import ConfigError
from ..foundation.fileio import atomic_paths
from ..maps.direction import direction_for_map
from ..track.drivable import Track
from ..track.start_grid import centreline_pose, grid_start_s
from . import physx_schemas
from .materials import PHYSICS_MATERIAL

CAR = "/World/Car"
PARTS = "/World/CarParts"
WHEELS = ("FrontLeftWheel", "FrontRightWheel", "RearLeftWheel", "RearRightWheel")
#: Gravity (m/s^2) the static loads are computed with: the stage's and our simulator's default.
GRAVITY = 9.81
#: Air density (kg/m^3), as ``arena_core::sim::vehicle::AIR_DENSITY``.
AIR_DENSITY = 1.2
#: Wheel surface speed (m/s) over which rolling resistance fades in (``ROLL_FADE`` in ours).
ROLL_FADE = 0.1
#: The lateral stiffness graph's knee (tyre load over rest load): below any load, so the
#: stiffness is the graph's flat value (module docstring, "Lateral tyre force").
LOAD_KNEE = 1e-3
#: Slip reference speeds (m/s) added to |v_long| in PhysX's slip ratios and angles (ours
#: uses max(|v_long|, 0.5)): small, so that above 0.5 m/s the two slips nearly agree.
LATERAL_SLIP_DENOMINATOR = 0.05
LONGITUDINAL_SLIP_DENOMINATOR = 0.1
#: PhysX's tyre load filter (``PxVehicleTireForceParams::loadFilter``, its default): the
#: filtered load over the rest load is ``a + b x`` for ``x`` = load over rest load in [0, 3].
LOAD_FILTER_A = 0.2308
LOAD_FILTER_B = (3.0 - LOAD_FILTER_A) / 3.0
#: The tyres' rest load over their static load (module docstring, "Tyre load").
REST_LOAD_FRACTION = 0.5
#: PhysX vehicle sub-steps per 5 ms step at every speed. With one (PhysX's usual above
#: 2 m/s) the explicit tyre force oscillates on the heavier cars: measured in a 3 m/s turn,
#: the lateral force per slip fell to 0.75 of the stiffness at mass x1.5 and 0.52-0.63 at
#: x2 (0.98 at x1); two sub-steps or a 2.5 ms step give 0.98 at every mass, as do 3 and 4:
#: converged. Three keep a margin.
VEHICLE_SUBSTEPS = 3
#: PhysX vehicle sub-steps per 5 ms step below :data:`SUBSTEP_SPEED`. Braking to a stop with
#: three, the wheels locked and let go step after step below 0.5 m/s, and the car stopped
#: from 0.3 m/s within 30 ms, 9 % sooner than ours from 5 m/s (mu 1, mass x1.5); with 6 they
#: still lagged the car; 12, 16 and 30 give one smooth trace (speeds within 0.004 m/s):
#: converged. Sixteen keep a margin.
LOW_SPEED_SUBSTEPS = 16
#: Longitudinal speed (m/s) below which PhysX uses :data:`LOW_SPEED_SUBSTEPS`.
SUBSTEP_SPEED = 2.0
#: Wheel width (m) and mass (kg) for PhysX's wheel (no counterpart in ours, whose wheels are
#: massless spin inertias): a 1:10 short-course tyre.
WHEEL_WIDTH = 0.045
WHEEL_MASS = 0.12


def ackermann_inner(delta: float, v: VehicleConfig) -> float:
    """The inner front wheel's angle (rad, signed as ``delta``) for a virtual centre-wheel
    angle ``delta``: our model's Ackermann law."""
    tan = math.tan(abs(delta))
    inner = math.atan2(v.wheelbase * tan, v.wheelbase - v.track_width / 2.0 * tan)
    return math.copysign(inner, delta)


def ackermann_command(delta: float, v: VehicleConfig) -> float:
    """PhysX's normalised steer for our centre-wheel angle ``delta`` (Ackermann API: the
    command times ``maxSteerAngle`` is the inner wheel's angle)."""
    return max(-1.0, min(1.0, ackermann_inner(delta, v) / ackermann_inner(v.max_steer, v)))


@dataclass(frozen=True)
class PhysxCarParams:
    """The PhysX car's numbers, each derived from one ``VehicleConfig`` (module docstring)."""

    force_per_amp: float
    """Total wheel-ground force per motor amp (N/A), as ours."""
    peak_torque: float
    """Basic drive's total wheel torque at full accelerator (N m): ``max_motor_current``."""
    max_brake_torque: float
    """Brake torque per wheel at full brake (N m): the larger motor current's torque."""
    max_inner_steer: float
    """Ackermann ``maxSteerAngle``: the inner wheel at ``max_steer`` (rad)."""
    rest_load_front: float
    rest_load_rear: float
    """Static load per wheel (N), front and rear."""
    friction: float
    """The friction table's value: ``tyre_friction`` through the load filter (module docstring)."""
    lateral_graph_front: tuple[float, float]
    lateral_graph_rear: tuple[float, float]
    """``lateralStiffnessGraph`` (knee as load over rest load, stiffness N/rad), front and rear."""
    longitudinal_stiffness_front: float
    longitudinal_stiffness_rear: float
    """``longitudinalStiffness`` (N per unit slip ratio)."""
    inertia: tuple[float, float, float]
    """Roll, pitch and yaw inertia (kg m^2), as ours."""


def physx_params(v: VehicleConfig, gravity: float = GRAVITY) -> PhysxCarParams:
    """Every PhysX number of the car from ``v`` (no free factor)."""
    length = v.com_to_front + v.com_to_rear
    n_front = v.mass * gravity * v.com_to_rear / length / 2.0
    n_rear = v.mass * gravity * v.com_to_front / length / 2.0
    fpa = 60.0 / (2.0 * math.pi * v.motor_kv) * v.gear_ratio / v.wheel_radius

    def graph(c_alpha: float, n0: float) -> tuple[float, float]:
        return LOAD_KNEE, c_alpha * n0

    a, b, c = v.chassis_length, v.chassis_width, v.chassis_height
    k = v.yaw_inertia / (a * a + b * b)
    return PhysxCarParams(
        force_per_amp=fpa,
        peak_torque=fpa * v.max_motor_current * v.wheel_radius,
        max_brake_torque=fpa * max(v.max_brake_current, v.max_motor_current) * v.wheel_radius / 4.0,
        max_inner_steer=ackermann_inner(v.max_steer, v),
        rest_load_front=n_front,
        rest_load_rear=n_rear,
        friction=v.tyre_friction / (LOAD_FILTER_A * REST_LOAD_FRACTION + LOAD_FILTER_B),
        lateral_graph_front=graph(v.cornering_stiffness_front, n_front),
        lateral_graph_rear=graph(v.cornering_stiffness_rear, n_rear),
        longitudinal_stiffness_front=v.longitudinal_stiffness * n_front,
        longitudinal_stiffness_rear=v.longitudinal_stiffness * n_rear,
        inertia=(k * (b * b + c * c), k * (a * a + c * c), v.yaw_inertia),
    )


@dataclass(frozen=True)
class _CarParts:
    """The shared parts every wheel of the car points at (prims under ``PARTS``)."""

    chassis_group: Any
    query_group: Any
    wheel: Any
    tyres: dict[str, Any]
    suspension: Any
    drive: Any


def author_car(stage: Usd.Stage, sim: SimConfig, pose: tuple[float, float, float]) -> str:
    """Author the car at ``pose`` (x, y, yaw on the floor); returns the car's prim path.
    Raises :class:`ConfigError` without the ``physx`` extra (the vehicle schemas)."""
    if not physx_schemas.register():
        raise ConfigError(
            "build --car needs the 'physx' extra for the PhysX vehicle schemas: pip install 'roboracer-arena[physx]'"
        )
    from physx_usd_schemas import PhysxSchema as P

    v = sim.vehicle
    par = physx_params(v, float(sim.physics.gravity))
    _vehicle_context(stage, P)
    parts = _car_parts(stage, P, v, par)
    _car_body(stage, P, v, par, pose, parts)
    _chassis(stage, v, parts)
    _wheels(stage, P, v, par, parts)
    return CAR


def _vehicle_context(stage: Usd.Stage, P: Any) -> None:
    """The physics scene's vehicle context: velocity-change updates, z up, x forward."""
    scene = stage.GetPrimAtPath("/World/PhysicsScene")
    ctx: Any = P.PhysxVehicleContextAPI.Apply(scene)
    ctx.CreateUpdateModeAttr("velocityChange")
    ctx.CreateVerticalAxisAttr("posZ")
    ctx.CreateLongitudinalAxisAttr("posX")


def _car_parts(stage: Usd.Stage, P: Any, v: VehicleConfig, par: PhysxCarParams) -> _CarParts:
    """Collision groups, tyre friction, wheel, tyres, suspension and drive, under ``PARTS``."""
    UsdGeom.Scope.Define(stage, PARTS)
    # Suspension raycasts must not see the car's own chassis.
    chassis_group = UsdPhysics.CollisionGroup.Define(stage, f"{PARTS}/ChassisGroup")
    query_group = UsdPhysics.CollisionGroup.Define(stage, f"{PARTS}/GroundQueryGroup")
    query_group.CreateFilteredGroupsRel().AddTarget(chassis_group.GetPath())

    table: Any = P.PhysxVehicleTireFrictionTable.Define(stage, f"{PARTS}/TireFriction")
    table.CreateGroundMaterialsRel().AddTarget(Sdf.Path(PHYSICS_MATERIAL))
    table.CreateFrictionValuesAttr([float(par.friction)])
    table.CreateDefaultFrictionValueAttr(float(par.friction))

    wheel: Any = P.PhysxVehicleWheelAPI.Apply(UsdGeom.Scope.Define(stage, f"{PARTS}/Wheel").GetPrim())
    wheel.CreateRadiusAttr(float(v.wheel_radius))
    wheel.CreateWidthAttr(WHEEL_WIDTH)
    wheel.CreateMassAttr(WHEEL_MASS)
    wheel.CreateMoiAttr(float(v.wheel_inertia))
    wheel.CreateDampingRateAttr(0.0)  # losses are torques and forces of the drive loop

    tyres = {}
    for name, n0, graph, k_long in (
        ("FrontTire", par.rest_load_front, par.lateral_graph_front, par.longitudinal_stiffness_front),
        ("RearTire", par.rest_load_rear, par.lateral_graph_rear, par.longitudinal_stiffness_rear),
    ):
        tyre: Any = P.PhysxVehicleTireAPI.Apply(UsdGeom.Scope.Define(stage, f"{PARTS}/{name}").GetPrim())
        tyre.CreateRestLoadAttr(float(REST_LOAD_FRACTION * n0))
        tyre.CreateLateralStiffnessGraphAttr(Gf.Vec2f(float(graph[0]), float(graph[1])))
        tyre.CreateLongitudinalStiffnessAttr(float(k_long))
        tyre.CreateCamberStiffnessAttr(0.0)
        tyre.CreateFrictionVsSlipGraphAttr([Gf.Vec2f(0.0, 1.0), Gf.Vec2f(0.5, 1.0), Gf.Vec2f(1.0, 1.0)])
        tyre.CreateFrictionTableRel().AddTarget(table.GetPath())
        tyres[name] = tyre.GetPrim().GetPath()

    susp: Any = P.PhysxVehicleSuspensionAPI.Apply(UsdGeom.Scope.Define(stage, f"{PARTS}/Suspension").GetPrim())
    susp.CreateSpringStrengthAttr(float(v.suspension_stiffness))
    susp.CreateSpringDamperRateAttr(float(v.suspension_damping))
    susp.CreateTravelDistanceAttr(float(v.suspension_travel))

    drive: Any = P.PhysxVehicleDriveBasicAPI.Apply(UsdGeom.Scope.Define(stage, f"{PARTS}/Drive").GetPrim())
    drive.CreatePeakTorqueAttr(float(par.peak_torque))
    return _CarParts(chassis_group, query_group, wheel, tyres, susp, drive)


def _car_body(
    stage: Usd.Stage, P: Any, v: VehicleConfig, par: PhysxCarParams, pose: tuple[float, float, float], parts: _CarParts
) -> None:
    """The car's rigid body at ``pose`` with its vehicle, controller, brakes, steering and differential."""
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
    mass.CreateDiagonalInertiaAttr(Gf.Vec3f(*(float(i) for i in par.inertia)))
    mass.CreatePrincipalAxesAttr(Gf.Quatf(1.0, 0.0, 0.0, 0.0))
    body: Any = P.PhysxRigidBodyAPI.Apply(prim)
    body.CreateEnableCCDAttr(True)
    body.CreateSleepThresholdAttr(0.0)
    body.CreateStabilizationThresholdAttr(0.0)
    body.CreateLinearDampingAttr(0.0)
    body.CreateAngularDampingAttr(0.0)
    body.CreateDisableGravityAttr(True)  # the vehicle's suspension carries the weight (PhysX vehicle convention)

    veh: Any = P.PhysxVehicleAPI.Apply(prim)
    veh.CreateVehicleEnabledAttr(True)
    veh.CreateDriveRel().AddTarget(parts.drive.GetPrim().GetPath())
    veh.CreateSuspensionLineQueryTypeAttr("raycast")
    veh.CreateSubStepThresholdLongitudinalSpeedAttr(SUBSTEP_SPEED)
    veh.CreateLowForwardSpeedSubStepCountAttr(LOW_SPEED_SUBSTEPS)
    veh.CreateHighForwardSpeedSubStepCountAttr(VEHICLE_SUBSTEPS)
    veh.CreateMinPassiveLongitudinalSlipDenominatorAttr(LONGITUDINAL_SLIP_DENOMINATOR)
    veh.CreateMinActiveLongitudinalSlipDenominatorAttr(LONGITUDINAL_SLIP_DENOMINATOR)
    veh.CreateMinLateralSlipDenominatorAttr(LATERAL_SLIP_DENOMINATOR)
    ctl: Any = P.PhysxVehicleControllerAPI.Apply(prim)
    for attr in (ctl.CreateAcceleratorAttr, ctl.CreateBrake0Attr, ctl.CreateBrake1Attr, ctl.CreateSteerAttr):
        attr(0.0)
    ctl.CreateTargetGearAttr(1)
    brakes: Any = P.PhysxVehicleBrakesAPI.Apply(prim, "brakes0")
    brakes.CreateMaxBrakeTorqueAttr(float(par.max_brake_torque))
    brakes.CreateWheelsAttr([0, 1, 2, 3])
    steer: Any = P.PhysxVehicleAckermannSteeringAPI.Apply(prim)
    steer.CreateMaxSteerAngleAttr(float(par.max_inner_steer))
    steer.CreateWheel0Attr(1)  # the wheel on the negative lateral side: front right
    steer.CreateWheel1Attr(0)
    steer.CreateWheelBaseAttr(float(v.com_to_front + v.com_to_rear))
    steer.CreateTrackWidthAttr(float(v.track_width))
    steer.CreateStrengthAttr(1.0)
    diff: Any = P.PhysxVehicleMultiWheelDifferentialAPI.Apply(prim)
    diff.CreateWheelsAttr([0, 1, 2, 3])
    diff.CreateTorqueRatiosAttr([0.25, 0.25, 0.25, 0.25])
    diff.CreateAverageWheelSpeedRatiosAttr([0.25, 0.25, 0.25, 0.25])


def _chassis(stage: Usd.Stage, v: VehicleConfig, parts: _CarParts) -> None:
    """The chassis box, a collider the wheels' suspension raycasts do not see."""
    box = UsdGeom.Cube.Define(stage, f"{CAR}/Chassis")
    box.CreateSizeAttr(1.0)
    bx = UsdGeom.Xformable(box)
    bx.AddTranslateOp().Set(Gf.Vec3d(0.0, 0.0, v.chassis_clearance + v.chassis_height / 2.0 - v.com_height))
    bx.AddScaleOp().Set(Gf.Vec3f(v.chassis_length, v.chassis_width, v.chassis_height))
    UsdPhysics.CollisionAPI.Apply(box.GetPrim())
    parts.chassis_group.GetCollidersCollectionAPI().CreateIncludesRel().AddTarget(box.GetPath())


def _wheels(stage: Usd.Stage, P: Any, v: VehicleConfig, par: PhysxCarParams, parts: _CarParts) -> None:
    """The four wheel attachments, each at rest on the floor under its static sag."""
    # The suspension frame is the wheel centre at full compression; at rest the spring is
    # compressed by the static sag, so the wheel centre sits at its radius above the floor.
    half = v.track_width / 2.0
    spots = ((v.com_to_front, half), (v.com_to_front, -half), (-v.com_to_rear, half), (-v.com_to_rear, -half))
    for k, (name, (wx, wy)) in enumerate(zip(WHEELS, spots)):
        load = par.rest_load_front if k < 2 else par.rest_load_rear
        sag = min(load / v.suspension_stiffness, 0.9 * v.suspension_travel)
        frame_z = v.wheel_radius + (v.suspension_travel - sag) - v.com_height
        w = UsdGeom.Xform.Define(stage, f"{CAR}/{name}")
        att: Any = P.PhysxVehicleWheelAttachmentAPI.Apply(w.GetPrim())
        att.CreateIndexAttr(k)
        att.CreateWheelRel().AddTarget(parts.wheel.GetPrim().GetPath())
        att.CreateTireRel().AddTarget(parts.tyres["FrontTire" if k < 2 else "RearTire"])
        att.CreateSuspensionRel().AddTarget(parts.suspension.GetPrim().GetPath())
        att.CreateCollisionGroupRel().AddTarget(parts.query_group.GetPath())
        att.CreateSuspensionTravelDirectionAttr(Gf.Vec3f(0.0, 0.0, -1.0))
        att.CreateSuspensionFramePositionAttr(Gf.Vec3f(wx, wy, frame_z))
        att.CreateSuspensionFrameOrientationAttr(Gf.Quatf(1.0, 0.0, 0.0, 0.0))
        # Forces at the contact patch at rest (relative to the suspension frame), as ours.
        patch = Gf.Vec4f(0.0, 0.0, 0.0, -(v.suspension_travel - sag) - v.wheel_radius)
        comp: Any = P.PhysxVehicleSuspensionComplianceAPI.Apply(w.GetPrim())
        comp.CreateSuspensionForceAppPointAttr([patch])
        comp.CreateTireForceAppPointAttr([patch])
        w.AddTranslateOp().Set(Gf.Vec3d(wx, wy, frame_z - (v.suspension_travel - sag)))


def replace_car(stage_path: str | Path, sim: SimConfig) -> None:
    """Re-author a built stage's car (``build --car``) from ``sim`` at the same pose, in place
    (written atomically): the same stage for another ``VehicleConfig``."""
    path = Path(stage_path)
    stage = Usd.Stage.Open(str(path))
    car = stage.GetPrimAtPath(CAR) if stage else None
    if not car:
        raise ConfigError(f"{path}: no car at {CAR} (build the stage with --car)")
    xf = UsdGeom.Xformable(car).ComputeLocalToWorldTransform(Usd.TimeCode.Default())
    t = xf.ExtractTranslation()
    fwd = xf.TransformDir(Gf.Vec3d(1.0, 0.0, 0.0))
    pose = (float(t[0]), float(t[1]), math.atan2(fwd[1], fwd[0]))
    stage.RemovePrim(CAR)
    stage.RemovePrim(PARTS)
    author_car(stage, sim, pose)
    fmt = path.suffix.lower().lstrip(".")
    args = {"format": fmt} if fmt in ("usdc", "usda") else {}
    with atomic_paths([path]) as (tmp,):
        if not stage.GetRootLayer().Export(str(tmp), args=args):
            raise ConfigError(f"{path}: could not write the stage")


def grid_start_pose(geo: Any, cfg: Any, source: str) -> tuple[float, float, float]:
    """The env's grid start (x, y, yaw) on a freshly built corridor: the same track the
    env drives (walls, centreline in the map's racing direction) and the same rule."""
    track = Track.from_polylines(list(geo.walls), geo.centreline, wall_height=cfg.geometry.wall_height_m)
    if source and Path(source).is_file():
        track = track.oriented(direction_for_map(Path(source)))
    return tuple(float(c) for c in centreline_pose(track, grid_start_s(track)))  # type: ignore[return-value]
