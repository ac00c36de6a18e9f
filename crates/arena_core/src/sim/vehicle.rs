//! The vehicle model: a rapier rigid chassis carried by four suspended wheels whose
//! forces are computed here and applied as impulses each physics step.
//!
//! Per wheel and step: a ray from the suspension hard-point along the chassis' down axis
//! meets the ground plane z = 0 analytically (the ground is flat, so no scene query is
//! needed); a spring–damper with a bump stop gives the normal load N; the tyre gives a
//! lateral force `-C N atan(v_lat / max(|v_long|, v0))` (cornering stiffness per unit load,
//! the F1TENTH/CommonRoad Traxxas values), a longitudinal force from the speed controller
//! shared by load (the Traxxas is four-wheel drive), both limited to the friction circle
//! `mu N` and, at crawling speed, to what stops the slip within one step (no jitter).
//! Steering is Ackermann (inner wheel turns more) with an angle and a rate limit.
//! The speed controller is a VESC-like P loop on forward speed with separate drive and
//! brake force limits. Load transfer, roll and pitch emerge from the rigid body.

use rapier3d::prelude::*;

use super::params::{PhysicsParams, VehicleParams};

/// Speed below which the slip angle uses `V0` as reference speed (m/s).
const V0: f64 = 0.5;

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
}

/// Per-vehicle actuator state.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Actuators {
    /// Current steering angle of the virtual centre wheel (rad), rate limited.
    pub steer: f64,
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
        }
    }

    /// Mass properties: the paper's mass and yaw inertia; roll and pitch inertia from the
    /// chassis box, scaled by the same ratio that maps the box's yaw inertia to the paper's.
    pub fn mass_properties(&self) -> MassProperties {
        let p = &self.p;
        let (a, b, c) = (p.chassis_length, p.chassis_width, p.chassis_height);
        let box_yaw = p.mass / 12.0 * (a * a + b * b);
        let k = p.yaw_inertia / box_yaw;
        let roll = k * p.mass / 12.0 * (b * b + c * c);
        let pitch = k * p.mass / 12.0 * (a * a + c * c);
        MassProperties::new(
            Vector::ZERO,
            p.mass as f32,
            Vector::new(roll as f32, pitch as f32, p.yaw_inertia as f32),
        )
    }

    /// The chassis rigid body at rest at `(x, y, yaw)` (CoM at com_height, level).
    /// Soft CCD (predictive contacts along the path) covers one step at top speed, so a
    /// car meets a wall at the step it reaches it instead of one step into it.
    pub fn body(&self, pose: [f64; 3], ccd: bool, dt: f64) -> RigidBody {
        RigidBodyBuilder::dynamic()
            .soft_ccd_prediction((self.p.max_speed.max(-self.p.min_speed) * dt * 1.5) as f32)
            .pose(self.spawn_pose(pose))
            .additional_mass_properties(self.mass_properties())
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

    /// Clip a raw action to the documented domain: NaN or ±inf become 0 (straight /
    /// stop), finite values are clipped to ±max_steer and [min_speed, max_speed].
    pub fn sanitise(&self, steer: f64, speed: f64) -> (f64, f64) {
        let s = if steer.is_finite() {
            steer.clamp(-self.p.max_steer, self.p.max_steer)
        } else {
            0.0
        };
        let v = if speed.is_finite() {
            speed.clamp(self.p.min_speed, self.p.max_speed)
        } else {
            0.0
        };
        (s, v)
    }

    /// Advance the actuators by `dt` toward the (sanitised) command and apply one step's
    /// wheel impulses to `body`.
    pub fn apply(&self, body: &mut RigidBody, act: &mut Actuators, cmd: (f64, f64), dt: f64) {
        let p = &self.p;
        let max_d = p.max_steer_rate * dt;
        act.steer += (cmd.0 - act.steer).clamp(-max_d, max_d);

        let pose = *body.position();
        let com = pose.translation;
        let rot = pose.rotation;
        let v = body.linvel();
        let w = body.angvel();
        let up = rot * Vector::Z;
        let fwd = rot * Vector::X;
        let v_long = v.dot(fwd) as f64;

        // Speed controller: P on forward speed, drive/brake limits, and never more than
        // what reaches the target within this step.
        let err = cmd.1 - v_long;
        let limit = if err * v_long >= 0.0 || v_long.abs() < 1e-3 {
            p.max_drive_force
        } else {
            p.max_brake_force
        };
        let f_total = (p.speed_kp * err).clamp(-limit, limit);
        let f_total = f_total.clamp(-p.mass * err.abs() / dt, p.mass * err.abs() / dt);

        // Ackermann angles of the left and right front wheels.
        let (l, t) = (p.com_to_front + p.com_to_rear, p.track_width / 2.0);
        let tan = act.steer.tan();
        let left = (l * tan / (l - t * tan)).atan();
        let right = (l * tan / (l + t * tan)).atan();
        let angles = [left, right, 0.0, 0.0];

        // Pass 1: suspension loads.
        let mut loads = [0.0f64; 4];
        let mut contact = [Vector::ZERO; 4];
        let mut hard = [Vector::ZERO; 4];
        let upz = up.z as f64;
        for (k, hp) in self.hardpoints.iter().enumerate() {
            let h = pose.transform_point(Vector::new(hp[0] as f32, hp[1] as f32, hp[2] as f32));
            hard[k] = h;
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
        let n_sum: f64 = loads.iter().sum();

        let mut force = Vector::ZERO;
        let mut torque = Vector::ZERO;
        let m_wheel = 0.5 * p.mass / 4.0;
        for k in 0..4 {
            let n = loads[k];
            if n <= 0.0 {
                continue;
            }
            let fs = up * n as f32;
            force += fs;
            torque += (hard[k] - com).cross(fs);

            let (ca, sa) = (angles[k].cos() as f32, angles[k].sin() as f32);
            let mut fw = rot * Vector::new(ca, sa, 0.0);
            fw.z = 0.0;
            let fw = fw.normalize_or_zero();
            let lw = Vector::new(-fw.y, fw.x, 0.0);
            let vc = v + w.cross(contact[k] - com);
            let (vl, vt) = (vc.dot(fw) as f64, vc.dot(lw) as f64);
            let mut fy = -self.stiffness[k] * n * vt.atan2(vl.abs().max(V0));
            let cap = m_wheel * vt.abs() / dt;
            fy = fy.clamp(-cap, cap);
            let mut fx = if n_sum > 0.0 {
                f_total * n / n_sum
            } else {
                0.0
            };
            let mu_n = p.tyre_friction * n;
            let mag = fx.hypot(fy);
            if mag > mu_n {
                let s = mu_n / mag;
                fx *= s;
                fy *= s;
            }
            let ft = fw * fx as f32 + lw * fy as f32;
            force += ft;
            torque += (contact[k] - com).cross(ft);
        }
        let dtf = dt as f32;
        body.apply_impulse(force * dtf, true);
        body.apply_torque_impulse(torque * dtf, true);
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
        assert_eq!(m.sanitise(f64::NAN, f64::INFINITY), (0.0, 0.0));
        assert_eq!(m.sanitise(9.0, 99.0), (0.524, 7.0));
        assert_eq!(m.sanitise(-9.0, -99.0), (-0.524, -3.0));
        assert_eq!(m.sanitise(0.1, 2.0), (0.1, 2.0));
        assert!(m.static_load_front() > 10.0 && m.static_load_front() < 13.0);
    }
}
