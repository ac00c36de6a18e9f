"""Configuration of the native simulator (``_core.Simulator``): vehicle, lidar, physics.

The three models mirror the Rust structs ``arena_core::sim::{VehicleParams, LidarParams,
PhysicsParams}`` field for field (same names, SI units); ``_core.Simulator`` takes a
``SimConfig`` (or a mapping of its fields) as its ``config``. Defaults reproduce the paper's
Traxxas 1:10 RoboRacer vehicle table (see ``DESIGN.md``); where the paper gives no
figure, the docstring of the field says where the value comes from.
"""

from __future__ import annotations

import json
import math
from typing import Literal

from pydantic import ConfigDict, Field, model_validator

from ..foundation.strict import NumbersAreNumbers

_FROZEN = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


#: Floors of every rate (Hz) and time step (s), here and in ``arena_core::sim::params``
#: (MIN_RATE_HZ, MIN_DT): a vanishing rate or step (5e-324 Hz, 1e-300 s) passes "> 0"
#: and then divides by zero; the schema refuses it with the floor in the message.
MIN_RATE_HZ = 0.01
MIN_DT = 1e-4


class VehicleConfig(NumbersAreNumbers):
    """Rigid chassis on four suspended wheels with Ackermann steering behind a lagged servo,
    and a drivetrain: a VESC-like PI speed loop on wheel speed driving a brushless motor
    (current limits and back-EMF give the torque-speed curve), open differentials, wheels
    that spin and slip (slip ratio and slip angle share the friction ellipse), rolling
    resistance and aerodynamic drag. Mass, inertia, geometry, steering limit and tyre
    friction are the paper's Traxxas 1:10 figures; cornering stiffness and rate limits are
    the F1TENTH/CommonRoad Traxxas values; each field says where its value comes from."""

    model_config = _FROZEN

    wheelbase: float = Field(0.3275, gt=0, description="Wheelbase (m); must equal com_to_front + com_to_rear.")
    track_width: float = Field(0.265, gt=0, description="Track width between left and right wheel contact points (m).")
    mass: float = Field(4.885, gt=0, description="Total mass (kg).")
    yaw_inertia: float = Field(0.089, gt=0, description="Yaw moment of inertia about the CoM (kg m^2).")
    com_to_front: float = Field(0.1753, gt=0, description="CoM to front axle (m).")
    com_to_rear: float = Field(0.1522, gt=0, description="CoM to rear axle (m).")
    wheel_radius: float = Field(0.0525, gt=0, description="Wheel radius (m).")
    com_height: float = Field(0.063, gt=0, description="CoM height above the ground at rest (m).")
    max_steer: float = Field(
        0.524, gt=0, lt=1.5, description="Maximum steering angle (rad) of the virtual centre wheel."
    )
    max_steer_rate: float = Field(
        3.2, gt=0, description="Steering-rate limit (rad/s): servo slew, the F1TENTH single-track model's sv_max."
    )
    steer_time_constant: float = Field(
        0.05,
        ge=0,
        description=(
            "First-order steering servo lag (s), before the rate limit; 0 = none. No published figure for the "
            "car's servo: 50 ms is an assumption (hobby servos move 60 deg in 0.1-0.2 s), randomise it for transfer."
        ),
    )
    max_speed: float = Field(
        7.0, gt=0, description="Largest commanded forward speed (m/s); the paper observed at most 6.66 m/s."
    )
    min_speed: float = Field(-3.0, le=0, description="Most negative commanded speed (m/s), i.e. reverse limit.")
    tyre_friction: float = Field(
        0.83,
        gt=0,
        description="Tyre-surface friction coefficient mu, lateral (paper: about 0.83, from a lateral pull test).",
    )
    longitudinal_friction_ratio: float = Field(
        1.0,
        gt=0,
        description=(
            "Longitudinal over lateral friction: the friction ellipse's axis ratio. The paper gives one mu, so 1.0 "
            "(a friction circle)."
        ),
    )
    cornering_stiffness_front: float = Field(
        4.718,
        gt=0,
        description="Front cornering stiffness per unit normal load (1/rad), the F1TENTH/CommonRoad Traxxas C_Sf.",
    )
    cornering_stiffness_rear: float = Field(
        5.4562,
        gt=0,
        description="Rear cornering stiffness per unit normal load (1/rad), the F1TENTH/CommonRoad Traxxas C_Sr.",
    )
    lateral_tyre: Literal["linear", "brush"] = Field(
        "linear",
        description=(
            "The lateral tyre law up to the friction limit. 'linear': C_a N alpha clipped to mu N (the F1TENTH "
            "single-track model's tyre). 'brush': mu N Fbar(C_a N0 tan(alpha) / (mu N)), Fbar(K) = K - K^2/3 + "
            "K^3/27 up to K = 3, N0 the wheel's static load: the same slope at zero slip and the same peak, bending "
            "over earlier; PhysX's lateral law, so the PhysX car built from this config is the same car "
            "(BENCHMARKS.md, 'One car, two engines')."
        ),
    )
    longitudinal_stiffness: float = Field(
        8.0,
        gt=0,
        description=(
            "Longitudinal slip stiffness per unit normal load (force / load per unit slip ratio). No published "
            "Traxxas figure: 8 lies between the car's cornering stiffness per load (4.7-5.5 /rad) and road tyres' "
            "10-20 (Pacejka, Tyre and Vehicle Dynamics); peak grip at about 10 % slip."
        ),
    )
    rolling_resistance: float = Field(
        0.015,
        ge=0,
        description="Rolling-resistance coefficient (force per unit load): rubber tyres on a hard floor, 0.01-0.02.",
    )
    drag_area: float = Field(
        0.035,
        ge=0,
        description=(
            "Aerodynamic drag area C_d A (m^2), air density 1.2 kg/m^3: a 0.29 m x 0.15 m bluff body frontal "
            "area (0.044 m^2) with C_d 0.8."
        ),
    )
    wheel_inertia: float = Field(
        2.5e-4,
        gt=0,
        description=(
            "Spin inertia of one wheel (kg m^2): a 1:10 short-course wheel and tyre (about 0.12 kg at 0.0525 m, "
            "~0.6 m r^2 = 2e-4) plus a quarter of the motor rotor through the gear ratio squared; an estimate."
        ),
    )
    chassis_length: float = Field(0.55, gt=0, description="Collision box length (m), Traxxas body about 0.55 m.")
    chassis_width: float = Field(0.29, gt=0, description="Collision box width (m), Traxxas body about 0.29 m.")
    chassis_height: float = Field(0.10, gt=0, description="Collision box height (m).")
    chassis_clearance: float = Field(
        0.03,
        ge=0,
        description="Gap between the collision box and the ground at rest (m), about the Traxxas chassis clearance.",
    )
    suspension_rest_length: float = Field(0.08, gt=0, description="Unloaded suspension length (m).")
    suspension_travel: float = Field(0.05, gt=0, description="Maximum compression before the bump stop (m).")
    suspension_stiffness: float = Field(
        600.0, gt=0, description="Spring rate per wheel (N/m): about 2 cm static sag, 3.5 Hz heave."
    )
    suspension_damping: float = Field(
        30.0, ge=0, description="Damper rate per wheel (N s/m): damping ratio about 0.55 at the default spring."
    )
    speed_kp: float = Field(
        100.0,
        gt=0,
        description=(
            "Speed PI proportional gain (motor amps per m/s of wheel-speed error), like the VESC speed PID acting "
            "on ERPM; 100 A per m/s is about 66 N per m/s at the wheels (saturates beyond 0.7 m/s of error)."
        ),
    )
    speed_ki: float = Field(
        100.0, ge=0, description="Speed PI integral gain (motor amps per m of accumulated error), with anti-windup."
    )
    throttle_time_constant: float = Field(
        0.02,
        ge=0,
        description="First-order lag of the motor current behind the speed loop (s): VESC current loop and command latency; 0 = none.",
    )
    motor_kv: float = Field(
        3500.0, gt=0, description="Motor speed constant (rpm/V): the Traxxas Velineon 3500 brushless motor."
    )
    motor_resistance: float = Field(
        0.02, gt=0, description="Motor winding plus ESC resistance (ohm); an estimate for a 3500 kV 540-size motor."
    )
    max_motor_current: float = Field(
        70.0,
        gt=0,
        description=(
            "VESC motor current limit while driving (A): with the defaults 70 A gives 46 N at the wheels, "
            "9.5 m/s^2 at 4.885 kg, the F1TENTH single-track model's a_max 9.51 m/s^2."
        ),
    )
    max_brake_current: float = Field(
        70.0, gt=0, description="VESC motor current limit while braking (A), symmetric with driving by default."
    )
    battery_voltage: float = Field(11.1, gt=0, description="Battery voltage (V): the F1TENTH car's 3S LiPo, nominal.")
    max_duty: float = Field(0.95, gt=0, le=1, description="Largest VESC duty cycle (the VESC default l_max_duty 0.95).")
    gear_ratio: float = Field(
        12.68,
        gt=0,
        description=(
            "Motor turns per wheel turn: from the F1TENTH VESC speed_to_erpm_gain 4614 ERPM per m/s with the "
            "4-pole Velineon (2 pole pairs) and the 0.0525 m wheel: 4614 x 2 pi r / (60 x 2). With 11.1 V x 3500 "
            "rpm/V this gives a no-load speed of 16.8 m/s."
        ),
    )

    @model_validator(mode="after")
    def _consistent_geometry(self) -> VehicleConfig:
        if abs(self.com_to_front + self.com_to_rear - self.wheelbase) > 1e-3:
            raise ValueError(
                f"com_to_front + com_to_rear = {self.com_to_front + self.com_to_rear:.4f} m "
                f"must equal wheelbase = {self.wheelbase:.4f} m"
            )
        if self.max_speed <= self.min_speed:
            raise ValueError("max_speed must exceed min_speed")
        return self


class LidarConfig(NumbersAreNumbers):
    """Planar scanning lidar (Hokuyo UST-10LX on the real car): 1081 beams over 270 deg,
    30 m range; ranges are exact 2D ray casts against the walls and other vehicles'
    chassis outlines, plus optional Gaussian noise from a per-vehicle seeded RNG."""

    model_config = _FROZEN

    num_beams: int = Field(1081, ge=1, le=100_000, description="Beams per scan (paper: 1081).")
    fov: float = Field(
        1.5 * math.pi, gt=0, le=2 * math.pi, description="Field of view (rad), centred on the heading (paper: 270 deg)."
    )
    range_max: float = Field(30.0, gt=0, description="Maximum range (m); a beam that hits nothing reads range_max.")
    range_min: float = Field(0.0, ge=0, description="Readings below this are clamped up to it (m).")
    noise_std: float = Field(0.0, ge=0, description="Std of additive Gaussian range noise (m); 0 = exact.")
    mount_x: float = Field(0.12, description="Forward offset of the scanner from the CoM (m).")
    mount_z: float = Field(0.12, description="Scanner height above the ground (m); informational in the 2D scan.")
    rate_hz: float = Field(
        40.0,
        ge=MIN_RATE_HZ,
        description=(
            "Scan rate (Hz; paper: 39.9 Hz). Under a faster control loop the env holds the latest scan "
            "until the next is due; at or below the scan rate every step gets a fresh scan."
        ),
    )

    @model_validator(mode="after")
    def _range_order(self) -> LidarConfig:
        if self.range_min >= self.range_max:
            raise ValueError(f"range_min ({self.range_min}) must be below range_max ({self.range_max})")
        return self


class PhysicsConfig(NumbersAreNumbers):
    """Rapier world settings. dt = 5 ms keeps the stiffest force (suspension, tyre
    relaxation) well inside the explicit-integration stability limit and moves the car
    at most 3.5 cm per step at 7 m/s, far less than its half-length, so walls never tunnel."""

    model_config = _FROZEN

    dt: float = Field(
        0.005,
        ge=MIN_DT,
        le=0.02,
        description="Physics time step (s). Steps above 10 ms are split into equal internal steps, so every accepted dt is stable.",
    )
    gravity: float = Field(9.81, gt=0, description="Gravity (m/s^2).")
    wall_friction: float = Field(0.3, ge=0, description="Chassis-wall friction coefficient.")
    ground_friction: float = Field(
        0.83, ge=0, description="Ground collider friction (chassis on ground only; tyres use tyre_friction)."
    )
    solver_iterations: int = Field(2, ge=1, le=16, description="Rapier solver iterations per step.")
    ccd: bool = Field(False, description="Continuous collision detection on the chassis (not needed at dt <= 10 ms).")
    shortcut_free_steps: bool = Field(
        True,
        description=(
            "Skip the rapier pipeline for a world step in which no chassis can touch anything (walls, other "
            "cars, ground: checked with twice the step's travel as margin) and integrate the free bodies with "
            "rapier's own symplectic Euler. Contacts always go through rapier. False = rapier every step."
        ),
    )


class SimConfig(NumbersAreNumbers):
    """Everything the native simulator needs besides tracks, counts and the seed."""

    model_config = _FROZEN

    vehicle: VehicleConfig = Field(default_factory=VehicleConfig)
    lidar: LidarConfig = Field(default_factory=LidarConfig)
    physics: PhysicsConfig = Field(default_factory=PhysicsConfig)

    def to_json(self) -> str:
        """The config as JSON text (files, logs); ``_core.Simulator`` takes the model itself."""
        return json.dumps(self.model_dump(mode="json"))
