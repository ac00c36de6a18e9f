//! The vehicle model: a rapier rigid chassis carried by four suspended wheels whose
//! forces are computed here and applied as impulses each physics step.
//!
//! Per wheel and step: a ray from the suspension hard-point along the chassis' down axis
//! meets the ground plane z = 0 analytically (the ground is flat, so no scene query is
//! needed); a spring–damper with a bump stop gives the normal load N, applied along the
//! ground normal at the contact point (a wheel transmits no sideways push from its own
//! load however the chassis is tilted). The tyre gives a lateral force
//! `-C_a N atan(v_lat / max(|v_long|, v0))` (cornering stiffness per unit load, the
//! F1TENTH/CommonRoad Traxxas values; `lateral_tyre = brush` gives the brush law of the same
//! slope and peak instead) and a longitudinal force `C_x N kappa` from the
//! wheel's slip ratio `kappa = (r omega - v_long) / max(|v_long|, v0)`; both are scaled
//! together into the friction ellipse `(Fx / mu_x N)^2 + (Fy / mu N)^2 <= 1`; at crawling
//! speed the lateral force is capped to what stops the slip within one step and the
//! longitudinal stiffness is softened by the chassis' response within the step (no jitter).
//!
//! Each wheel spins (`omega`) under a quarter of the motor torque (open differentials),
//! the tyre's reaction and rolling resistance; its update is implicit in the slip so it
//! is stable for the tiny wheel inertia. The motor is a brushless DC machine behind a
//! VESC: a PI loop on wheel speed asks for a current, which lags first-order and is
//! limited by the current limits and by what the battery voltage can drive against the
//! back-EMF (the torque–speed curve), so top speed comes from the motor, drag and
//! rolling resistance. Steering is Ackermann (inner wheel turns more) behind a
//! first-order servo lag and a rate limit. Load transfer, roll and pitch emerge from
//! the rigid body.

use rapier3d::prelude::*;

use super::params::{LateralTyre, PhysicsParams, VehicleParams};

/// Speed below which the slip angle and slip ratio use `V0` as reference speed (m/s).
const V0: f64 = 0.5;
/// Longest drivetrain sub-step (s): the wheel-speed loop with the wheel's small inertia
/// is stable well inside it.
const DRIVE_DT: f64 = 0.005;
/// Air density (kg/m^3) for the drag force.
const AIR_DENSITY: f64 = 1.2;
/// Wheel surface speed (m/s) over which rolling resistance fades in, so a wheel at rest
/// feels none (no chatter around zero).
const ROLL_FADE: f64 = 0.1;

/// Per-vehicle parameters that domain randomisation may change per episode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CarParams {
    /// Tyre–surface friction coefficient mu (lateral; longitudinal is scaled by the
    /// model's `longitudinal_friction_ratio`).
    pub friction: f64,
    /// Total mass (kg); the inertia tensor scales with it.
    pub mass: f64,
    /// Steering servo and motor-current time constants (s).
    pub steer_lag: f64,
    pub throttle_lag: f64,
}

impl CarParams {
    /// The configured (nominal) values.
    pub fn nominal(p: &VehicleParams) -> Self {
        CarParams {
            friction: p.tyre_friction,
            mass: p.mass,
            steer_lag: p.steer_time_constant,
            throttle_lag: p.throttle_time_constant,
        }
    }

    /// Check randomised values: the same rules as the configuration's.
    pub fn validate(&self) -> std::result::Result<(), String> {
        let pos = |x: f64| x.is_finite() && x > 0.0;
        let nonneg = |x: f64| x.is_finite() && x >= 0.0;
        if !pos(self.friction) {
            return Err(format!(
                "friction must be a positive finite number, got {}",
                self.friction
            ));
        }
        if !pos(self.mass) {
            return Err(format!(
                "mass must be a positive finite number, got {}",
                self.mass
            ));
        }
        if !nonneg(self.steer_lag) || !nonneg(self.throttle_lag) {
            return Err(format!(
                "lags must be finite and >= 0, got {} and {}",
                self.steer_lag, self.throttle_lag
            ));
        }
        Ok(())
    }
}

/// One wheel's state within a step: load, directions, longitudinal contact speed, the
/// (capped) lateral force demand and the tyre forces summed over the drivetrain sub-steps.
#[derive(Debug, Clone, Copy, Default)]
struct Wheel {
    n: f64,
    vl: f64,
    fy: f64,
    fw: Vector,
    lw: Vector,
    sum_fx: f64,
    sum_fy: f64,
}

/// Each wheel's suspension load (N, 0 off the ground) and ground contact point.
struct Contacts {
    loads: [f64; 4],
    points: [Vector; 4],
}

/// Fraction of the way a first-order lag of time constant `tau` moves in `dt` (exact).
fn lag_step(tau: f64, dt: f64) -> f64 {
    if tau > 0.0 {
        1.0 - (-dt / tau).exp()
    } else {
        1.0
    }
}

/// Lateral force (N, against the slip) of a tyre with cornering stiffness `c` per unit load
/// under load `n` (static load `n0`), from the contact's lateral speed `vt` and reference
/// speed `vref > 0`. The brush tyre's stiffness `c n0` is the tyre's own, fixed at its static
/// load (as PhysX's lateral stiffness), the linear law's `c n` follows the load.
fn lateral_force(law: LateralTyre, c: f64, mu: f64, n: f64, n0: f64, vt: f64, vref: f64) -> f64 {
    match law {
        LateralTyre::Linear => -c * n * vt.atan2(vref),
        LateralTyre::Brush if n <= 0.0 => 0.0,
        LateralTyre::Brush => {
            let tan_a = vt / vref;
            let k = c * n0 * tan_a.abs() / (mu * n);
            let fbar = if k < 3.0 {
                k - k * k / 3.0 + k * k * k / 27.0
            } else {
                1.0
            };
            -tan_a.signum() * mu * n * fbar
        }
    }
}

/// Constants derived once from the parameters.
#[derive(Debug, Clone)]
pub struct VehicleModel {
    pub p: VehicleParams,
    /// Body-frame hard-points (x, y, z) of FL, FR, RL, RR.
    hardpoints: [[f64; 3]; 4],
    /// Cornering stiffness per unit load for each wheel.
    stiffness: [f64; 4],
    /// Collision box half extents and body-frame centre.
    pub half_extents: [f64; 3],
    pub box_centre: [f64; 3],
    gravity: f64,
    /// Wheel-ground force per motor amp (N/A), equal to the back-EMF in volts per m/s
    /// of wheel surface speed: `60 / (2 pi kv) * gear_ratio / wheel_radius`.
    force_per_amp: f64,
}

/// Per-vehicle actuator and drivetrain state.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Actuators {
    /// Current steering angle of the virtual centre wheel (rad), lagged and rate limited.
    pub steer: f64,
    /// Motor current (A) after the throttle lag.
    pub current: f64,
    /// Integral of the speed error (m) for the PI loop.
    pub integral: f64,
    /// Wheel spin rates (rad/s) of FL, FR, RL, RR.
    pub omega: [f64; 4],
}

impl VehicleModel {
    pub fn new(p: &VehicleParams, physics: &PhysicsParams) -> Self {
        let g = physics.gravity;
        let (lf, lr, l) = (
            p.com_to_front,
            p.com_to_rear,
            p.com_to_front + p.com_to_rear,
        );
        // Static per-wheel loads (front axle carries lr / L of the weight) and the
        // hard-point heights that make the chassis level with its CoM at com_height.
        let nf = p.mass * g * lr / l / 2.0;
        let nr = p.mass * g * lf / l / 2.0;
        let hz = |n: f64| {
            p.wheel_radius + p.suspension_rest_length - n / p.suspension_stiffness - p.com_height
        };
        let (hf, hr) = (hz(nf), hz(nr));
        let y = p.track_width / 2.0;
        VehicleModel {
            p: p.clone(),
            hardpoints: [[lf, y, hf], [lf, -y, hf], [-lr, y, hr], [-lr, -y, hr]],
            stiffness: [
                p.cornering_stiffness_front,
                p.cornering_stiffness_front,
                p.cornering_stiffness_rear,
                p.cornering_stiffness_rear,
            ],
            half_extents: [
                p.chassis_length / 2.0,
                p.chassis_width / 2.0,
                p.chassis_height / 2.0,
            ],
            box_centre: [
                (lf - lr) / 2.0,
                0.0,
                p.chassis_clearance + p.chassis_height / 2.0 - p.com_height,
            ],
            gravity: g,
            force_per_amp: 60.0 / (2.0 * std::f64::consts::PI * p.motor_kv) * p.gear_ratio
                / p.wheel_radius,
        }
    }

    /// Motor current window (A) at wheel surface speed `v_wheel`: the current limits
    /// (drive when the torque is along the rotation, brake when against it) and what
    /// duty cycles in [-max_duty, max_duty] can drive against the back-EMF.
    pub fn current_window(&self, v_wheel: f64) -> (f64, f64) {
        let p = &self.p;
        let emf = self.force_per_amp * v_wheel;
        let v_max = p.max_duty * p.battery_voltage;
        let (pos, neg) = if v_wheel >= 0.0 {
            (p.max_motor_current, p.max_brake_current)
        } else {
            (p.max_brake_current, p.max_motor_current)
        };
        let lo = (-neg).max((-v_max - emf) / p.motor_resistance);
        let hi = pos.min((v_max - emf) / p.motor_resistance).max(lo);
        (lo, hi)
    }

    /// Total wheel-ground force per motor amp (N/A).
    pub fn force_per_amp(&self) -> f64 {
        self.force_per_amp
    }

    /// Mass properties: the paper's mass and yaw inertia; roll and pitch inertia from the
    /// chassis box, scaled by the same ratio that maps the box's yaw inertia to the paper's.
    /// With another `mass`, the whole inertia tensor scales with it (same geometry).
    pub fn mass_properties(&self, mass: f64) -> MassProperties {
        let p = &self.p;
        let scale = mass / p.mass;
        let (a, b, c) = (p.chassis_length, p.chassis_width, p.chassis_height);
        let box_yaw = p.mass / 12.0 * (a * a + b * b);
        let k = p.yaw_inertia / box_yaw;
        let roll = k * p.mass / 12.0 * (b * b + c * c);
        let pitch = k * p.mass / 12.0 * (a * a + c * c);
        MassProperties::new(
            Vector::ZERO,
            mass as f32,
            Vector::new(
                (roll * scale) as f32,
                (pitch * scale) as f32,
                (p.yaw_inertia * scale) as f32,
            ),
        )
    }

    /// How far ahead (m) contacts are predicted for a step of `dt`: one step at top speed
    /// with a 50 % margin.
    pub fn contact_lookahead(&self, dt: f64) -> f64 {
        self.p.max_speed.max(-self.p.min_speed) * dt * 1.5
    }

    /// The chassis rigid body at rest at `(x, y, yaw)` (CoM at com_height, level).
    /// Soft CCD (predictive contacts along the path) covers one step at top speed, so a
    /// car meets a wall at the step it reaches it instead of one step into it.
    pub fn body(&self, pose: [f64; 3], ccd: bool, dt: f64) -> RigidBody {
        RigidBodyBuilder::dynamic()
            .soft_ccd_prediction(self.contact_lookahead(dt) as f32)
            .pose(self.spawn_pose(pose))
            .additional_mass_properties(self.mass_properties(self.p.mass))
            .can_sleep(false)
            .ccd_enabled(ccd)
            .build()
    }

    pub fn spawn_pose(&self, pose: [f64; 3]) -> Pose {
        Pose::from_parts(
            Vector::new(pose[0] as f32, pose[1] as f32, self.p.com_height as f32),
            Rotation::from_rotation_z(pose[2] as f32),
        )
    }

    /// The chassis collision box (massless: the body carries the mass properties).
    pub fn collider(&self) -> Collider {
        let [hx, hy, hz] = self.half_extents;
        let [cx, cy, cz] = self.box_centre;
        ColliderBuilder::cuboid(hx as f32, hy as f32, hz as f32)
            .translation(Vector::new(cx as f32, cy as f32, cz as f32))
            .density(0.0)
            .friction(0.5)
            .build()
    }

    /// The one action rule, for every caller (the envs, the ROS 2 bridge, the core's own
    /// step): NaN means no command and becomes 0 (straight / stop); every other value,
    /// ±inf included, is clipped to ±max_steer and [min_speed, max_speed] (so +inf is
    /// full throttle, as any value past the bound is). Idempotent: a sanitised action
    /// passes unchanged.
    pub fn sanitise(&self, steer: f64, speed: f64) -> (f64, f64) {
        let clip = |x: f64, lo: f64, hi: f64| if x.is_nan() { 0.0 } else { x.clamp(lo, hi) };
        (
            clip(steer, -self.p.max_steer, self.p.max_steer),
            clip(speed, self.p.min_speed, self.p.max_speed),
        )
    }

    /// Advance the actuators and wheels by `dt` toward the (sanitised) command and apply
    /// one step's wheel and drag impulses to `body`.
    pub fn apply(
        &self,
        body: &mut RigidBody,
        act: &mut Actuators,
        car: &CarParams,
        cmd: (f64, f64),
        dt: f64,
    ) {
        let p = &self.p;
        let max_d = p.max_steer_rate * dt;
        act.steer += ((cmd.0 - act.steer) * lag_step(car.steer_lag, dt)).clamp(-max_d, max_d);

        let contacts = self.suspension(body);
        let m_wheel = 0.5 * car.mass / 4.0;
        let mut wheels = self.tyre_demands(body, act.steer, car, &contacts, dt, m_wheel);

        // Pass 3: the drivetrain (speed loop, motor current, wheel spin) is faster than
        // the chassis, so it runs in sub-steps of at most DRIVE_DT against the chassis
        // velocities of this step; the chassis gets the mean tyre forces.
        let subs = (dt / DRIVE_DT - 1e-9).ceil().max(1.0) as usize;
        let h = dt / subs as f64;
        for _ in 0..subs {
            self.drive_substep(act, car, cmd.1, &mut wheels, h, dt, m_wheel);
        }

        let (force, torque) = self.chassis_load(body, &wheels, &contacts.points, subs);
        let dtf = dt as f32;
        body.apply_impulse(force * dtf, true);
        body.apply_torque_impulse(torque * dtf, true);
    }

    /// Pass 1: each wheel's suspension load (N) and ground contact point; no load for a
    /// wheel in the air, nor for any when the car lies on its side.
    fn suspension(&self, body: &RigidBody) -> Contacts {
        let p = &self.p;
        let pose = *body.position();
        let com = pose.translation;
        let v = body.linvel();
        let w = body.angvel();
        let up = pose.rotation * Vector::Z;
        let mut loads = [0.0f64; 4];
        let mut contact = [Vector::ZERO; 4];
        let upz = up.z as f64;
        for (k, hp) in self.hardpoints.iter().enumerate() {
            let h = pose.transform_point(Vector::new(hp[0] as f32, hp[1] as f32, hp[2] as f32));
            if upz < 0.2 || h.z < 0.0 {
                continue; // on its side or below ground: no wheel contact
            }
            let dist = h.z as f64 / upz; // hard-point to ground along -up
            let len = dist - p.wheel_radius;
            let c = p.suspension_rest_length - len;
            if c <= 0.0 {
                continue; // wheel in the air
            }
            let vp = v + w.cross(h - com);
            let c_dot = -(vp.z as f64) / upz;
            let mut n = p.suspension_stiffness * c + p.suspension_damping * c_dot;
            if c > p.suspension_travel {
                n += 10.0 * p.suspension_stiffness * (c - p.suspension_travel);
            }
            loads[k] = n.max(0.0);
            contact[k] = h - up * dist as f32;
        }
        Contacts {
            loads,
            points: contact,
        }
    }

    /// Pass 2: each wheel's heading (Ackermann angles on the front axle), its contact
    /// velocity along the heading and the lateral force its tyre demands, capped at what
    /// stops its share of the mass `m_wheel` sideways within `dt`.
    fn tyre_demands(
        &self,
        body: &RigidBody,
        steer: f64,
        car: &CarParams,
        contacts: &Contacts,
        dt: f64,
        m_wheel: f64,
    ) -> [Wheel; 4] {
        let p = &self.p;
        let pose = *body.position();
        let com = pose.translation;
        let rot = pose.rotation;
        let v = body.linvel();
        let w = body.angvel();
        // Ackermann angles of the left and right front wheels.
        let (l, t) = (p.com_to_front + p.com_to_rear, p.track_width / 2.0);
        let tan = steer.tan();
        let left = (l * tan / (l - t * tan)).atan();
        let right = (l * tan / (l + t * tan)).atan();
        let angles = [left, right, 0.0, 0.0];
        let per_wheel = car.mass * self.gravity / (2.0 * l);
        let n0_axle = [per_wheel * p.com_to_rear, per_wheel * p.com_to_front];
        let mut wheels = [Wheel::default(); 4];
        for (k, wh) in wheels.iter_mut().enumerate() {
            let n = contacts.loads[k];
            let (ca, sa) = (angles[k].cos() as f32, angles[k].sin() as f32);
            let mut fw = rot * Vector::new(ca, sa, 0.0);
            fw.z = 0.0;
            wh.fw = fw.normalize_or_zero();
            wh.lw = Vector::new(-wh.fw.y, wh.fw.x, 0.0);
            let vc = v + w.cross(contacts.points[k] - com);
            let (vl, vt) = (vc.dot(wh.fw) as f64, vc.dot(wh.lw) as f64);
            let cap = m_wheel * vt.abs() / dt;
            let vref = vl.abs().max(V0);
            let n0 = n0_axle[k / 2];
            wh.fy = lateral_force(
                p.lateral_tyre,
                self.stiffness[k],
                car.friction,
                n,
                n0,
                vt,
                vref,
            )
            .clamp(-cap, cap);
            wh.vl = vl;
            wh.n = n;
        }
        wheels
    }

    /// The step's force and torque on the chassis (about the CoM): aerodynamic drag on
    /// the horizontal velocity, and at each loaded wheel's contact its load along the
    /// ground normal plus its tyre forces averaged over the `subs` drivetrain sub-steps.
    fn chassis_load(
        &self,
        body: &RigidBody,
        wheels: &[Wheel; 4],
        contact: &[Vector; 4],
        subs: usize,
    ) -> (Vector, Vector) {
        let p = &self.p;
        let com = body.position().translation;
        let v = body.linvel();
        let vh = Vector::new(v.x, v.y, 0.0);
        let mut force = vh * (-(0.5 * AIR_DENSITY * p.drag_area * vh.length() as f64) as f32);
        let mut torque = Vector::ZERO;
        let inv = 1.0 / subs as f64;
        for (k, wh) in wheels.iter().enumerate() {
            if wh.n <= 0.0 {
                continue;
            }
            // The load acts along the ground normal at the contact point.
            let ft = Vector::Z * wh.n as f32
                + wh.fw * (wh.sum_fx * inv) as f32
                + wh.lw * (wh.sum_fy * inv) as f32;
            force += ft;
            torque += (contact[k] - com).cross(ft);
        }
        (force, torque)
    }

    /// One drivetrain sub-step of length `h` (the chassis step is `dt`): the PI loop on
    /// wheel speed, as the VESC measures it (ERPM), with the integral held while the
    /// output is saturated in the error's direction (anti-windup); the lagged motor
    /// current within its window; each wheel's spin and tyre forces, accumulated.
    #[allow(clippy::too_many_arguments)]
    fn drive_substep(
        &self,
        act: &mut Actuators,
        car: &CarParams,
        target: f64,
        wheels: &mut [Wheel; 4],
        h: f64,
        dt: f64,
        m_wheel: f64,
    ) {
        let p = &self.p;
        let r = p.wheel_radius;
        let v_wheel = r * act.omega.iter().sum::<f64>() / 4.0;
        let err = target - v_wheel;
        let (lo, hi) = self.current_window(v_wheel);
        let want = p.speed_kp * err + p.speed_ki * act.integral;
        if (want < hi || err < 0.0) && (want > lo || err > 0.0) {
            act.integral += err * h;
        }
        act.current += (want.clamp(lo, hi) - act.current) * lag_step(car.throttle_lag, h);
        act.current = act.current.clamp(lo, hi);
        let wheel_torque = self.force_per_amp * act.current * r / 4.0;
        let mu_x = car.friction * p.longitudinal_friction_ratio;
        let iw = p.wheel_inertia;
        for (k, wh) in wheels.iter_mut().enumerate() {
            let (n, vl, omega) = (wh.n, wh.vl, act.omega[k]);
            let roll = -p.rolling_resistance * n * r * (omega * r / ROLL_FADE).clamp(-1.0, 1.0);
            let tq = wheel_torque + roll;
            if n <= 0.0 {
                act.omega[k] = omega + h * tq / iw; // free wheel
                continue;
            }
            // Longitudinal: linear slip stiffness (N per m/s of slip speed), softened by the
            // chassis' own response within its step (implicit in the chassis velocity
            // too: F = k s' with s' = s - dt F / m gives F = k s / (1 + k dt / m)), and
            // the wheel spin solved implicitly with it: iw (w' - w) = h (tq - r kx (r w' - vl)).
            let k0 = p.longitudinal_stiffness * n / vl.abs().max(V0);
            let kx = k0 / (1.0 + k0 * dt / m_wheel);
            let mut implicit = (iw * omega + h * (tq + r * kx * vl)) / (iw + h * r * r * kx);
            // A braking torque (against the direction of travel) locks a wheel at most;
            // it never spins it backwards under a sliding tyre.
            let braking = tq * vl < 0.0;
            let locked = braking && implicit * vl < 0.0;
            if locked {
                implicit = 0.0;
            }
            let slip = r * implicit - vl;
            let fx_lin = kx * slip;
            let (mut fx, mut fy) = (fx_lin, wh.fy);
            let e = (fx / (mu_x * n)).powi(2) + (fy / (car.friction * n)).powi(2);
            if e > 1.0 {
                let s = 1.0 / e.sqrt();
                fx *= s;
                fy *= s;
            }
            act.omega[k] = if fx == fx_lin || locked {
                implicit
            } else {
                let w = omega + h * (tq - r * fx) / iw;
                if braking && w * vl < 0.0 {
                    0.0
                } else {
                    w
                }
            };
            wh.sum_fx += fx;
            wh.sum_fy += fy;
        }
    }

    /// The wheel spin rate (rad/s) that rolls without slip at forward speed `v`.
    pub fn rolling_omega(&self, v: f64) -> f64 {
        v / self.p.wheel_radius
    }

    /// Static load per wheel (N) at rest, for tests.
    pub fn static_load_front(&self) -> f64 {
        self.p.mass * self.gravity * self.p.com_to_rear
            / (self.p.com_to_front + self.p.com_to_rear)
            / 2.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sanitise_documented_domain() {
        let m = VehicleModel::new(&VehicleParams::default(), &PhysicsParams::default());
        assert_eq!(m.sanitise(f64::NAN, f64::NAN), (0.0, 0.0));
        assert_eq!(m.sanitise(f64::INFINITY, f64::INFINITY), (0.524, 7.0));
        assert_eq!(
            m.sanitise(f64::NEG_INFINITY, f64::NEG_INFINITY),
            (-0.524, -3.0)
        );
        assert_eq!(m.sanitise(9.0, 99.0), (0.524, 7.0));
        assert_eq!(m.sanitise(-9.0, -99.0), (-0.524, -3.0));
        assert_eq!(m.sanitise(0.1, 2.0), (0.1, 2.0));
        assert!(m.static_load_front() > 10.0 && m.static_load_front() < 13.0);
    }

    #[test]
    fn brush_tyre_has_the_linear_slope_and_peak_and_bends_over_earlier() {
        let (c, mu, n) = (4.718, 0.83, 12.0);
        let f = |law, vt: f64| lateral_force(law, c, mu, n, n, vt, 3.0);
        // The same slope at zero slip (within the cubic's curvature at 1e-6).
        let small = 1e-6;
        let ratio = f(LateralTyre::Brush, small) / f(LateralTyre::Linear, small);
        assert!((ratio - 1.0).abs() < 1e-5, "{ratio}");
        // Odd in the slip, and against it.
        assert!(f(LateralTyre::Brush, 0.1) < 0.0);
        assert_eq!(f(LateralTyre::Brush, 0.1), -f(LateralTyre::Brush, -0.1));
        // Saturated at mu N from K = 3 on, i.e. tan(alpha) = 3 mu / c.
        let sat = 3.0 * mu / c * 3.0;
        assert!((f(LateralTyre::Brush, sat * 1.01) + mu * n).abs() < 1e-9);
        assert!((f(LateralTyre::Brush, sat * 5.0) + mu * n).abs() < 1e-9);
        // At the linear law's saturation slip (K = 1) the brush gives 19/27 of mu N.
        let k1 = mu / c * 3.0;
        let want = -mu * n * (1.0 - 1.0 / 3.0 + 1.0 / 27.0);
        assert!((f(LateralTyre::Brush, k1) - want).abs() < 1e-9);
    }
}
