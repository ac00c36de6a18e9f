//! Simulator parameters, deserialised from the JSON that
//! `roboracer_arena.envs.config.SimConfig.to_json()` writes. Field names and defaults
//! mirror the pydantic models exactly (SI units); unknown fields are rejected so a typo
//! in a config never silently falls back to a default.

use serde::{Deserialize, Serialize};

use crate::error::{ArenaError, Result};

/// Largest accepted physics time step (s). Steps above [`MAX_INTERNAL_DT`] are split
/// into equal internal sub-steps, so every accepted dt is as stable as 10 ms.
pub const MAX_DT: f64 = 0.02;
/// Smallest accepted physics time step (s): below it a second of simulation is more
/// than ten thousand steps, and a vanishing dt (1e-300) divides by zero downstream.
pub const MIN_DT: f64 = 1e-4;
/// Smallest accepted rate (Hz) of anything periodic (lidar, and in Python the control
/// and bridge rates): a period above 100 s is no rate, and 5e-324 Hz overflows 1/rate.
pub const MIN_RATE_HZ: f64 = 0.01;
/// Largest step the vehicle model integrates in one go (s).
pub const MAX_INTERNAL_DT: f64 = 0.01;

/// The lateral tyre law (issue 36): the force against the slip angle up to the friction limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LateralTyre {
    /// `C_a N alpha`, clipped to `mu N` (the F1TENTH single-track model's tyre).
    #[default]
    Linear,
    /// The brush tyre `mu N Fbar(C_a N0 tan(alpha) / (mu N))`, `Fbar(K) = K - K^2/3 + K^3/27`
    /// up to `K = 3`, then 1, `N0` the wheel's static load: the same slope at zero slip and the
    /// same peak, bending over earlier (PhysX's lateral law; see
    /// `roboracer_arena.usd.vehicle.physx_params`).
    Brush,
}

/// The Traxxas 1:10 RoboRacer vehicle (paper's table) plus model constants.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct VehicleParams {
    pub wheelbase: f64,
    pub track_width: f64,
    pub mass: f64,
    pub yaw_inertia: f64,
    pub com_to_front: f64,
    pub com_to_rear: f64,
    pub wheel_radius: f64,
    pub com_height: f64,
    pub max_steer: f64,
    /// Steering-rate limit (rad/s); 3.2 is the F1TENTH single-track model's `sv_max`.
    pub max_steer_rate: f64,
    /// First-order steering servo time constant (s); 0 = no lag.
    pub steer_time_constant: f64,
    pub max_speed: f64,
    pub min_speed: f64,
    pub tyre_friction: f64,
    /// Longitudinal over lateral friction (the friction ellipse's axis ratio).
    pub longitudinal_friction_ratio: f64,
    /// Cornering stiffness per unit normal load (1/rad), front and rear axles.
    pub cornering_stiffness_front: f64,
    pub cornering_stiffness_rear: f64,
    /// The lateral tyre law; the longitudinal law is linear in slip in both.
    pub lateral_tyre: LateralTyre,
    /// Longitudinal slip stiffness per unit normal load (per unit slip ratio).
    pub longitudinal_stiffness: f64,
    /// Rolling-resistance coefficient (force per unit normal load).
    pub rolling_resistance: f64,
    /// Aerodynamic drag area C_d A (m^2), with air density 1.2 kg/m^3.
    pub drag_area: f64,
    /// Spin inertia of one wheel including its share of the motor rotor (kg m^2).
    pub wheel_inertia: f64,
    pub chassis_length: f64,
    pub chassis_width: f64,
    pub chassis_height: f64,
    pub chassis_clearance: f64,
    pub suspension_rest_length: f64,
    pub suspension_travel: f64,
    pub suspension_stiffness: f64,
    pub suspension_damping: f64,
    /// Speed PI controller on wheel speed: motor amps per m/s of error, per m of error.
    pub speed_kp: f64,
    pub speed_ki: f64,
    /// First-order lag of the motor current behind the controller (s); 0 = none.
    pub throttle_time_constant: f64,
    /// Brushless motor: speed constant (rpm/V), winding resistance (ohm), current limits
    /// (A) for driving and braking; battery voltage (V), largest duty cycle; reduction
    /// from motor to wheel.
    pub motor_kv: f64,
    pub motor_resistance: f64,
    pub max_motor_current: f64,
    pub max_brake_current: f64,
    pub battery_voltage: f64,
    pub max_duty: f64,
    pub gear_ratio: f64,
}

impl Default for VehicleParams {
    fn default() -> Self {
        VehicleParams {
            wheelbase: 0.3275,
            track_width: 0.265,
            mass: 4.885,
            yaw_inertia: 0.089,
            com_to_front: 0.1753,
            com_to_rear: 0.1522,
            wheel_radius: 0.0525,
            com_height: 0.063,
            max_steer: 0.524,
            max_steer_rate: 3.2,
            steer_time_constant: 0.05,
            max_speed: 7.0,
            min_speed: -3.0,
            tyre_friction: 0.83,
            longitudinal_friction_ratio: 1.0,
            cornering_stiffness_front: 4.718,
            cornering_stiffness_rear: 5.4562,
            lateral_tyre: LateralTyre::Linear,
            longitudinal_stiffness: 8.0,
            rolling_resistance: 0.015,
            drag_area: 0.035,
            wheel_inertia: 2.5e-4,
            chassis_length: 0.55,
            chassis_width: 0.29,
            chassis_height: 0.10,
            chassis_clearance: 0.03,
            suspension_rest_length: 0.08,
            suspension_travel: 0.05,
            suspension_stiffness: 600.0,
            suspension_damping: 30.0,
            speed_kp: 100.0,
            speed_ki: 100.0,
            throttle_time_constant: 0.02,
            motor_kv: 3500.0,
            motor_resistance: 0.02,
            max_motor_current: 70.0,
            max_brake_current: 70.0,
            battery_voltage: 11.1,
            max_duty: 0.95,
            gear_ratio: 12.68,
        }
    }
}

/// The planar scanner (Hokuyo UST-10LX on the real car).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LidarParams {
    pub num_beams: usize,
    pub fov: f64,
    pub range_max: f64,
    pub range_min: f64,
    pub noise_std: f64,
    pub mount_x: f64,
    pub mount_z: f64,
    pub rate_hz: f64,
}

impl Default for LidarParams {
    fn default() -> Self {
        LidarParams {
            num_beams: 1081,
            fov: 1.5 * std::f64::consts::PI,
            range_max: 30.0,
            range_min: 0.0,
            noise_std: 0.0,
            mount_x: 0.12,
            mount_z: 0.12,
            rate_hz: 40.0,
        }
    }
}

/// Rapier world settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PhysicsParams {
    pub dt: f64,
    pub gravity: f64,
    pub wall_friction: f64,
    pub ground_friction: f64,
    pub solver_iterations: usize,
    pub ccd: bool,
    /// Skip the rapier pipeline for a world step in which no chassis can touch anything
    /// (integrating the free bodies with rapier's own scheme); see `World::step`.
    pub shortcut_free_steps: bool,
}

impl Default for PhysicsParams {
    fn default() -> Self {
        PhysicsParams {
            dt: 0.005,
            gravity: 9.81,
            wall_friction: 0.3,
            ground_friction: 0.83,
            solver_iterations: 2,
            ccd: false,
            shortcut_free_steps: true,
        }
    }
}

/// The whole `config_json`: `{"vehicle": {...}, "lidar": {...}, "physics": {...}}`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SimParams {
    pub vehicle: VehicleParams,
    pub lidar: LidarParams,
    pub physics: PhysicsParams,
}

fn check(ok: bool, what: &str) -> Result<()> {
    if ok {
        Ok(())
    } else {
        Err(ArenaError::config(format!("simulator config: {what}")))
    }
}

fn pos(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

impl SimParams {
    /// Parse and validate `config_json` (an empty object gives the defaults).
    pub fn from_json(text: &str) -> Result<Self> {
        let p: SimParams = serde_json::from_str(text)
            .map_err(|e| ArenaError::config(format!("simulator config JSON: {e}")))?;
        p.validate()?;
        Ok(p)
    }

    /// Reject values the model cannot run with (the pydantic models check the same).
    /// The first failing rule is reported, in this order.
    pub fn validate(&self) -> Result<()> {
        for (name, x) in self.positive_fields() {
            check(
                pos(x),
                &format!("{name} must be a positive finite number, got {x}"),
            )?;
        }
        self.vehicle.check_ranges()?;
        self.lidar.check_ranges()?;
        self.check_rates()?;
        self.physics.check_ranges()
    }

    /// Every field that must be a positive finite number, by its config name.
    fn positive_fields(&self) -> [(&'static str, f64); 36] {
        let v = &self.vehicle;
        [
            ("vehicle.wheelbase", v.wheelbase),
            ("vehicle.track_width", v.track_width),
            ("vehicle.mass", v.mass),
            ("vehicle.yaw_inertia", v.yaw_inertia),
            ("vehicle.com_to_front", v.com_to_front),
            ("vehicle.com_to_rear", v.com_to_rear),
            ("vehicle.wheel_radius", v.wheel_radius),
            ("vehicle.com_height", v.com_height),
            ("vehicle.max_steer", v.max_steer),
            ("vehicle.max_steer_rate", v.max_steer_rate),
            ("vehicle.max_speed", v.max_speed),
            ("vehicle.tyre_friction", v.tyre_friction),
            (
                "vehicle.cornering_stiffness_front",
                v.cornering_stiffness_front,
            ),
            (
                "vehicle.cornering_stiffness_rear",
                v.cornering_stiffness_rear,
            ),
            ("vehicle.chassis_length", v.chassis_length),
            ("vehicle.chassis_width", v.chassis_width),
            ("vehicle.chassis_height", v.chassis_height),
            ("vehicle.suspension_rest_length", v.suspension_rest_length),
            ("vehicle.suspension_travel", v.suspension_travel),
            ("vehicle.suspension_stiffness", v.suspension_stiffness),
            (
                "vehicle.longitudinal_friction_ratio",
                v.longitudinal_friction_ratio,
            ),
            ("vehicle.longitudinal_stiffness", v.longitudinal_stiffness),
            ("vehicle.wheel_inertia", v.wheel_inertia),
            ("vehicle.speed_kp", v.speed_kp),
            ("vehicle.motor_kv", v.motor_kv),
            ("vehicle.motor_resistance", v.motor_resistance),
            ("vehicle.max_motor_current", v.max_motor_current),
            ("vehicle.max_brake_current", v.max_brake_current),
            ("vehicle.battery_voltage", v.battery_voltage),
            ("vehicle.max_duty", v.max_duty),
            ("vehicle.gear_ratio", v.gear_ratio),
            ("lidar.fov", self.lidar.fov),
            ("lidar.range_max", self.lidar.range_max),
            ("lidar.rate_hz", self.lidar.rate_hz),
            ("physics.dt", self.physics.dt),
            ("physics.gravity", self.physics.gravity),
        ]
    }

    /// The physics step and the lidar rate within the simulator's bounds.
    fn check_rates(&self) -> Result<()> {
        let (p, l) = (&self.physics, &self.lidar);
        check(
            p.dt <= MAX_DT,
            &format!("physics.dt must be at most {MAX_DT} s, got {}", p.dt),
        )?;
        check(
            p.dt >= MIN_DT,
            &format!("physics.dt must be at least {MIN_DT} s, got {}", p.dt),
        )?;
        check(
            l.rate_hz >= MIN_RATE_HZ,
            &format!(
                "lidar.rate_hz must be at least {MIN_RATE_HZ} Hz, got {}",
                l.rate_hz
            ),
        )
    }
}

impl VehicleParams {
    /// The vehicle's rules beyond positivity: steering limit, axle split, signs, duty.
    fn check_ranges(&self) -> Result<()> {
        let v = self;
        check(v.max_steer < 1.5, "vehicle.max_steer must be below 1.5 rad")?;
        check(
            (v.com_to_front + v.com_to_rear - v.wheelbase).abs() <= 1e-3,
            "vehicle.com_to_front + vehicle.com_to_rear must equal vehicle.wheelbase",
        )?;
        check(
            v.min_speed.is_finite() && v.min_speed <= 0.0,
            "vehicle.min_speed must be <= 0",
        )?;
        check(
            v.chassis_clearance.is_finite() && v.chassis_clearance >= 0.0,
            "vehicle.chassis_clearance must be >= 0",
        )?;
        for (name, x) in [
            ("vehicle.suspension_damping", v.suspension_damping),
            ("vehicle.steer_time_constant", v.steer_time_constant),
            ("vehicle.throttle_time_constant", v.throttle_time_constant),
            ("vehicle.speed_ki", v.speed_ki),
            ("vehicle.rolling_resistance", v.rolling_resistance),
            ("vehicle.drag_area", v.drag_area),
        ] {
            check(
                x.is_finite() && x >= 0.0,
                &format!("{name} must be a finite number >= 0, got {x}"),
            )?;
        }
        check(v.max_duty <= 1.0, "vehicle.max_duty must be at most 1")
    }
}

impl LidarParams {
    /// The lidar's rules beyond positivity: beam count, field of view, ranges, noise,
    /// mount.
    fn check_ranges(&self) -> Result<()> {
        let l = self;
        check(
            l.num_beams >= 1 && l.num_beams <= 100_000,
            "lidar.num_beams must be in 1..=100000",
        )?;
        check(
            l.fov <= 2.0 * std::f64::consts::PI + 1e-9,
            "lidar.fov must be at most 2 pi",
        )?;
        check(
            l.range_min.is_finite() && l.range_min >= 0.0 && l.range_min < l.range_max,
            "lidar.range_min must be in [0, range_max)",
        )?;
        check(
            l.noise_std.is_finite() && l.noise_std >= 0.0,
            "lidar.noise_std must be >= 0",
        )?;
        check(
            l.mount_x.is_finite() && l.mount_z.is_finite(),
            "lidar mount offsets must be finite",
        )
    }
}

impl PhysicsParams {
    /// The solver's iteration count and the contact frictions.
    fn check_ranges(&self) -> Result<()> {
        let p = self;
        check(
            p.solver_iterations >= 1 && p.solver_iterations <= 16,
            "physics.solver_iterations must be in 1..=16",
        )?;
        check(
            p.wall_friction.is_finite() && p.wall_friction >= 0.0,
            "physics.wall_friction must be >= 0",
        )?;
        check(
            p.ground_friction.is_finite() && p.ground_friction >= 0.0,
            "physics.ground_friction must be >= 0",
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_json_gives_defaults_and_unknown_fields_fail() {
        assert_eq!(SimParams::from_json("{}").unwrap(), SimParams::default());
        let p = SimParams::from_json(r#"{"lidar": {"num_beams": 64}}"#).unwrap();
        assert_eq!(p.lidar.num_beams, 64);
        assert!(SimParams::from_json(r#"{"vehicle": {"mas": 3.0}}"#).is_err());
        assert!(SimParams::from_json(r#"{"physics": {"dt": -1.0}}"#).is_err());
        assert!(SimParams::from_json(r#"{"vehicle": {"wheelbase": 0.5}}"#).is_err());
    }
}
