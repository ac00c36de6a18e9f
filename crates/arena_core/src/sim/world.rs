//! One rapier world per environment: its vehicles, the shared wall mesh of its track
//! and a ground half-space. Steps physics, reports contacts, keeps odometry and progress.

use std::sync::Arc;

use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rapier3d::prelude::*;

use super::lidar::{Footprint, ScanNoise, Scanner};
use super::params::{PhysicsParams, MAX_INTERNAL_DT};
use super::progress::Progress;
use super::shared_track::Track;
use super::vehicle::{Actuators, CarParams, VehicleModel};

/// Columns of the state array, in order.
pub const STATE_FIELDS: [&str; 13] = [
    "x",
    "y",
    "yaw",
    "vx",
    "vy",
    "yaw_rate",
    "steer",
    "speed",
    "progress_s",
    "travel",
    "laps",
    "lap_time",
    "last_lap_time",
];
pub const STATE_SIZE: usize = STATE_FIELDS.len();

/// Event bits (per vehicle, per `step` call).
pub const EVENT_WALL: u8 = 1;
pub const EVENT_VEHICLE: u8 = 2;
pub const EVENT_LAP: u8 = 4;
/// The physics produced a non-finite state; the vehicle was put back at its last finite
/// pose at rest (never expected; reported so it cannot pass silently).
pub const EVENT_FAULT: u8 = 8;

/// Half side of the ground cuboid (m): larger than any track.
const GROUND_HALF_SIZE: f32 = 5000.0;

/// Contact margin (m) of the free-step shortcut and rapier's window for re-using a
/// pair's contacts while it barely moves; well below the chassis ground clearance.
const PREDICTION_DISTANCE: f32 = 0.005;

/// Unbiased velocity passes after each solver iteration's position update (rapier's
/// default is 1). A chassis face hitting a wall flat-on touches several wall triangles,
/// each its own manifold of up to 4 points, so the constraints are highly redundant; one
/// pass did not undo the penetration-recovery velocity of the biased pass: the car
/// rebounded at about 0.5 m/s off a 7 m/s hit with a restitution of 0, rolling at 2.5 rad/s
/// from the uneven split, drove back in slightly askew and spun at up to 1.2 rad/s on the
/// second hit (issue 13, defect 3). Two passes leave at most 0.1 m/s; crash-heavy
/// pipeline steps cost about 9 % more (BENCHMARKS.md).
const STABILIZATION_ITERATIONS: usize = 2;

struct Car {
    body: RigidBodyHandle,
    collider: ColliderHandle,
    act: Actuators,
    params: CarParams,
    cmd: (f64, f64),
    progress: Progress,
    rng: ChaCha8Rng,
    events: u8,
    last_good: Pose,
}

/// Per-vehicle RNG seed from (seed, env index, vehicle index): independent of N.
pub fn vehicle_seed(seed: u64, env: usize, vehicle: usize) -> u64 {
    fn mix(mut z: u64) -> u64 {
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    mix(mix(mix(seed) ^ env as u64) ^ vehicle as u64)
}

pub struct World {
    pw: PhysicsWorld,
    wall: ColliderHandle,
    cars: Vec<Car>,
    track: Arc<Track>,
    track_id: usize,
    /// The internal step: `physics.dt / inner`.
    dt: f64,
    /// Internal steps per configured step (`physics.dt` split so none exceeds
    /// `MAX_INTERNAL_DT`).
    inner: usize,
    gravity: f64,
    shortcut: bool,
    scratch: Vec<[f64; 3]>,
    /// This env's own stream for reset draws (start pose, track, speed, noise level), so
    /// that resetting env e never consumes another env's draws.
    reset_rng: ChaCha8Rng,
    /// This episode's lidar randomisation (drawn at reset from `reset_rng`).
    noise: ScanNoise,
    /// World steps through the rapier pipeline, and contact-free shortcut steps.
    counts: [u64; 2],
}

impl World {
    /// A world on `track` with `vehicles` cars parked along the centreline (call
    /// [`World::reset_vehicle`] to place them).
    pub fn new(
        track: Arc<Track>,
        track_id: usize,
        vehicles: usize,
        model: &VehicleModel,
        physics: &PhysicsParams,
        seed: u64,
        env: usize,
    ) -> Self {
        let inner = (physics.dt / MAX_INTERNAL_DT - 1e-9).ceil().max(1.0) as usize;
        let dt = physics.dt / inner as f64;
        let mut pw = PhysicsWorld::new();
        pw.gravity = Vector::new(0.0, 0.0, -(physics.gravity as f32));
        pw.integration_parameters.dt = dt as f32;
        pw.integration_parameters.num_solver_iterations = physics.solver_iterations;
        pw.integration_parameters
            .num_internal_stabilization_iterations = STABILIZATION_ITERATIONS;
        // Speculative contacts reach as far as the chassis' soft CCD (one step at top
        // speed). Rapier reduces a contact patch of more than 4 points (a chassis face on
        // two or more wall triangles) to the deepest point plus the points within this
        // distance: with a shorter one, a flat-on hit kept one speculative corner and the
        // whole impact went through it, spinning the car at up to 10 rad/s (issue 13).
        // It brings no ground contacts to a car driving level 30 mm above the ground:
        // with soft CCD rapier drops a pair whose tight boxes, one swept over the step,
        // do not meet. Crash-heavy pipeline steps cost about 25 % more (BENCHMARKS.md).
        pw.integration_parameters.normalized_prediction_distance =
            PREDICTION_DISTANCE.max(model.contact_lookahead(dt) as f32);
        // Rapier re-uses a contact-free pair's (empty) manifold until it has moved the
        // prediction distance capped by this window; its 5 cm default let a car at 7 m/s
        // cross a wall's first 3 cm unseen once the prediction distance is that long.
        pw.integration_parameters
            .normalized_contact_recycle_distance = PREDICTION_DISTANCE;
        // Ground: a big cuboid with its top face at z = 0 (not a half-space, whose
        // unbounded AABB would keep a chassis–ground contact pair alive in every step;
        // the chassis box rides above the ground on its wheels, so normally no pair exists).
        let ground = ColliderBuilder::cuboid(GROUND_HALF_SIZE, GROUND_HALF_SIZE, 0.5)
            .translation(Vector::new(0.0, 0.0, -0.5))
            .friction(physics.ground_friction as f32)
            .build();
        pw.colliders.insert(ground);
        let wall = pw.colliders.insert(
            ColliderBuilder::new(track.wall_shape.clone())
                .friction(physics.wall_friction as f32)
                .build(),
        );
        let mut cars = Vec::with_capacity(vehicles);
        for v in 0..vehicles {
            let pose = track.centreline.pose_at(v as f64 * 1.0);
            let (body, collider) = pw.insert(model.body(pose, physics.ccd, dt), model.collider());
            // Mass properties take effect at the first pipeline step unless computed now;
            // the wheel impulses of that first step need them.
            pw.bodies[body].recompute_mass_properties_from_colliders(&pw.colliders);
            let mut rng = ChaCha8Rng::seed_from_u64(vehicle_seed(seed, env, v));
            rng.set_stream(v as u64);
            cars.push(Car {
                body,
                collider,
                act: Actuators::default(),
                params: CarParams::nominal(&model.p),
                cmd: (0.0, 0.0),
                progress: Progress::reset(&track.centreline, [pose[0], pose[1]]),
                rng,
                events: 0,
                last_good: model.spawn_pose(pose),
            });
        }
        World {
            pw,
            wall,
            cars,
            track,
            track_id,
            dt,
            inner,
            gravity: physics.gravity,
            shortcut: physics.shortcut_free_steps,
            scratch: Vec::with_capacity(vehicles),
            reset_rng: {
                let mut r = ChaCha8Rng::seed_from_u64(vehicle_seed(seed, env, usize::MAX));
                r.set_stream(u64::MAX);
                r
            },
            noise: ScanNoise::default(),
            counts: [0, 0],
        }
    }

    pub fn track_id(&self) -> usize {
        self.track_id
    }

    /// This env's reset stream (see the field).
    pub fn reset_rng(&mut self) -> &mut ChaCha8Rng {
        &mut self.reset_rng
    }

    /// Set this episode's lidar randomisation.
    pub fn set_scan_noise(&mut self, noise: ScanNoise) {
        self.noise = noise;
    }

    pub fn track(&self) -> &Arc<Track> {
        &self.track
    }

    /// Full 3D pose and (linear, angular) velocity of vehicle `v`'s chassis.
    pub fn chassis(&self, v: usize) -> (Pose, Vector, Vector) {
        let b = &self.pw.bodies[self.cars[v].body];
        (*b.position(), b.linvel(), b.angvel())
    }

    /// (world steps through the rapier pipeline, contact-free shortcut steps) so far.
    pub fn step_counts(&self) -> [u64; 2] {
        self.counts
    }

    pub fn num_vehicles(&self) -> usize {
        self.cars.len()
    }

    /// Swap the track (the wall collider now references the new shared mesh). Vehicles
    /// keep their poses: reset them afterwards.
    pub fn set_track(&mut self, track: Arc<Track>, track_id: usize) {
        if track_id == self.track_id {
            return;
        }
        if let Some(c) = self.pw.colliders.get_mut(self.wall) {
            c.set_shape(track.wall_shape.clone());
        }
        self.track = track;
        self.track_id = track_id;
    }

    /// Put vehicle `v` at rest at `pose` = (x, y, yaw); non-finite poses are refused by
    /// the caller. Clears progress, laps and events.
    pub fn reset_vehicle(&mut self, v: usize, pose: [f64; 3], model: &VehicleModel) {
        let spawn = model.spawn_pose(pose);
        let car = &mut self.cars[v];
        if let Some(b) = self.pw.bodies.get_mut(car.body) {
            b.set_position(spawn, true);
            b.set_linvel(Vector::ZERO, true);
            b.set_angvel(Vector::ZERO, true);
            b.reset_forces(true);
            b.reset_torques(true);
        }
        car.act = Actuators::default();
        car.cmd = (0.0, 0.0);
        car.progress = Progress::reset(&self.track.centreline, [pose[0], pose[1]]);
        car.events = 0;
        car.last_good = spawn;
    }

    /// Give vehicle `v` a forward speed (m/s) along its heading, its wheels rolling at
    /// it: a rolling start right after [`World::reset_vehicle`]. The speed controller
    /// takes over at the next step.
    pub fn set_forward_speed(&mut self, v: usize, speed: f64, model: &VehicleModel) {
        let car = &mut self.cars[v];
        if let Some(b) = self.pw.bodies.get_mut(car.body) {
            let mut fwd = b.position().rotation * Vector::X;
            fwd.z = 0.0;
            b.set_linvel(fwd.normalize_or_zero() * speed as f32, true);
            car.act.omega = [model.rolling_omega(speed); 4];
        }
    }

    /// Set vehicle `v`'s per-episode parameters (friction, mass, lags); the chassis'
    /// mass properties follow the mass. Takes effect at the next step.
    pub fn set_car_params(&mut self, v: usize, params: CarParams, model: &VehicleModel) {
        let car = &mut self.cars[v];
        if params.mass != car.params.mass {
            if let Some(b) = self.pw.bodies.get_mut(car.body) {
                b.set_additional_mass_properties(model.mass_properties(params.mass), true);
                b.recompute_mass_properties_from_colliders(&self.pw.colliders);
            }
        }
        car.params = params;
    }

    /// Add a constant world-frame force (N) at vehicle `v`'s CoM for the next steps
    /// (tests: a lateral pull test).
    #[cfg(test)]
    pub(crate) fn push(&mut self, v: usize, force: [f64; 3]) {
        if let Some(b) = self.pw.bodies.get_mut(self.cars[v].body) {
            b.reset_forces(true);
            let f = Vector::new(force[0] as f32, force[1] as f32, force[2] as f32);
            b.add_force(f, true);
        }
    }

    /// Vehicle `v`'s current per-episode parameters.
    pub fn car_params(&self, v: usize) -> CarParams {
        self.cars[v].params
    }

    /// Run `substeps` physics steps with the given (already sanitised) commands, then
    /// update progress and events.
    pub fn step(&mut self, cmds: &[(f64, f64)], substeps: usize, model: &VehicleModel) {
        for (car, &cmd) in self.cars.iter_mut().zip(cmds) {
            car.cmd = cmd;
            car.events = 0;
        }
        for _ in 0..substeps * self.inner {
            for car in &mut self.cars {
                if let Some(b) = self.pw.bodies.get_mut(car.body) {
                    model.apply(b, &mut car.act, &car.params, car.cmd, self.dt);
                }
            }
            if self.shortcut && self.free_of_contacts(model) {
                self.integrate_free();
                self.counts[1] += 1;
            } else {
                self.pw.step();
                self.collect_contacts();
                self.counts[0] += 1;
            }
        }
        let elapsed = (substeps * self.inner) as f64 * self.dt;
        for car in &mut self.cars {
            let Some(b) = self.pw.bodies.get_mut(car.body) else {
                continue;
            };
            let finite =
                b.position().is_finite() && b.linvel().is_finite() && b.angvel().is_finite();
            if !finite {
                b.set_position(car.last_good, true);
                b.set_linvel(Vector::ZERO, true);
                b.set_angvel(Vector::ZERO, true);
                car.act = Actuators::default();
                car.events |= EVENT_FAULT;
            } else {
                car.last_good = *b.position();
            }
            let t = b.translation();
            let speed = b.linvel().length() as f64;
            if car.progress.update(
                &self.track.centreline,
                [t.x as f64, t.y as f64],
                elapsed,
                speed * elapsed,
            ) {
                car.events |= EVENT_LAP;
            }
        }
    }

    /// True when no chassis can touch anything (walls, other chassis, ground) during the
    /// next step: every chassis box, grown by twice its travel in one step plus the
    /// contact margin, is clear of the wall segments (2D: the walls are vertical
    /// extrusions of them), of the other boxes' bounding circles and of the ground.
    /// Rapier may hold speculative contacts farther out (its prediction distance covers a
    /// step at top speed), but one acts only when the step's approach closes its gap, so
    /// skipping them is exact.
    fn free_of_contacts(&mut self, model: &VehicleModel) -> bool {
        let [hx, hy, hz] = model.half_extents;
        let [bx, by, bz] = model.box_centre;
        let r_xy = hx.hypot(hy);
        let margin = 2.0 * PREDICTION_DISTANCE as f64 + 0.02;
        self.scratch.clear();
        for car in &self.cars {
            let b = &self.pw.bodies[car.body];
            let p = b.position();
            let reach = 2.0 * b.linvel().length() as f64 * self.dt + margin;
            let c = p.transform_point(Vector::new(bx as f32, by as f32, bz as f32));
            let (ax, ay, az) = (
                p.rotation * Vector::X,
                p.rotation * Vector::Y,
                p.rotation * Vector::Z,
            );
            let low = c.z as f64
                - (ax.z.abs() as f64 * hx + ay.z.abs() as f64 * hy + az.z.abs() as f64 * hz);
            let reach_z =
                2.0 * b.linvel().z.abs() as f64 * self.dt + 1.5 * PREDICTION_DISTANCE as f64;
            if low <= reach_z
                || !self
                    .track
                    .grid
                    .clear_of(c.x as f64, c.y as f64, r_xy + reach)
            {
                return false;
            }
            self.scratch.push([c.x as f64, c.y as f64, reach]);
        }
        for (i, a) in self.scratch.iter().enumerate() {
            for b in &self.scratch[i + 1..] {
                if (a[0] - b[0]).hypot(a[1] - b[1]) <= 2.0 * r_xy + a[2] + b[2] {
                    return false;
                }
            }
        }
        true
    }

    /// One contact-free step without the rapier pipeline, replaying what rapier's solver
    /// does to a body without contacts: `num_solver_iterations` substeps of dt / n, each
    /// adding gravity, applying the gyroscopic correction, then integrating the pose
    /// linearised (quaternion first order) about the CoM. The wheel impulses were
    /// already applied to the velocities, as before a pipeline step.
    fn integrate_free(&mut self) {
        let n = self.pw.integration_parameters.num_solver_iterations.max(1);
        let h = self.dt as f32 / n as f32;
        let g = Vector::new(0.0, 0.0, -(self.gravity as f32) * h);
        for car in &self.cars {
            let b = &mut self.pw.bodies[car.body];
            let (mut v, mut p) = (b.linvel(), *b.position());
            for _ in 0..n {
                v += g;
                let w = if b.gyroscopic_forces_enabled() {
                    b.angvel_with_gyroscopic_forces(h)
                } else {
                    b.angvel()
                };
                let half = w * (0.5 * h);
                p.rotation =
                    (Rotation::from_xyzw(half.x, half.y, half.z, 1.0) * p.rotation).normalize();
                p.translation += v * h;
                b.set_angvel(w, false);
                b.set_position(p, false);
            }
            b.set_linvel(v, true);
        }
    }

    fn collect_contacts(&mut self) {
        let np = &self.pw.narrow_phase;
        for car in &mut self.cars {
            for pair in np.contact_pairs_with(car.collider) {
                // A contact event means touching: rapier also keeps speculative points out
                // to the prediction distance (which covers a step at top speed), and a car
                // passing a few cm from a wall is not a collision.
                let touching = pair.has_any_active_contact()
                    && pair
                        .manifolds()
                        .iter()
                        .any(|m| m.points.iter().any(|c| c.dist <= PREDICTION_DISTANCE));
                if !touching {
                    continue;
                }
                let other = if pair.collider1 == car.collider {
                    pair.collider2
                } else {
                    pair.collider1
                };
                if other == self.wall {
                    car.events |= EVENT_WALL;
                } else if self
                    .pw
                    .colliders
                    .get(other)
                    .is_some_and(|c| c.parent().is_some())
                {
                    car.events |= EVENT_VEHICLE;
                }
            }
        }
    }

    fn planar(&self, v: usize) -> ([f64; 3], [f64; 3]) {
        let b = &self.pw.bodies[self.cars[v].body];
        let p = b.position();
        let fwd = p.rotation * Vector::X;
        let yaw = (fwd.y as f64).atan2(fwd.x as f64);
        let (c, s) = (yaw.cos(), yaw.sin());
        let lv = b.linvel();
        let (vx, vy) = (
            lv.x as f64 * c + lv.y as f64 * s,
            -(lv.x as f64) * s + lv.y as f64 * c,
        );
        (
            [p.translation.x as f64, p.translation.y as f64, yaw],
            [vx, vy, b.angvel().z as f64],
        )
    }

    /// Write state rows (`STATE_SIZE` per vehicle) and event bytes.
    pub fn write_state(&self, state: &mut [f64], events: &mut [u8]) {
        for (v, car) in self.cars.iter().enumerate() {
            let (pose, vel) = self.planar(v);
            let pr = &car.progress;
            let speed = vel[0].hypot(vel[1]).copysign(vel[0]);
            let row = [
                pose[0],
                pose[1],
                pose[2],
                vel[0],
                vel[1],
                vel[2],
                car.act.steer,
                speed,
                pr.s,
                pr.travel,
                pr.laps as f64,
                pr.lap_time,
                pr.last_lap_time,
            ];
            state[v * STATE_SIZE..(v + 1) * STATE_SIZE].copy_from_slice(&row);
            events[v] = car.events;
        }
    }

    /// One scan per vehicle into `scans` (`num_beams` per vehicle); other vehicles'
    /// chassis rectangles are visible.
    pub fn scan(&mut self, scanner: &Scanner, model: &VehicleModel, scans: &mut [f32]) {
        let n = scanner.num_beams();
        let [hx, hy, _] = model.half_extents;
        let cx = model.box_centre[0];
        let poses: Vec<[f64; 3]> = (0..self.cars.len()).map(|v| self.planar(v).0).collect();
        let prints: Vec<Footprint> = poses
            .iter()
            .map(|p| {
                let (c, s) = (p[2].cos(), p[2].sin());
                Footprint {
                    x: p[0] + cx * c,
                    y: p[1] + cx * s,
                    cos: c,
                    sin: s,
                    half_length: hx,
                    half_width: hy,
                }
            })
            .collect();
        let mut others = Vec::with_capacity(prints.len());
        for (v, car) in self.cars.iter_mut().enumerate() {
            others.clear();
            others.extend(
                prints
                    .iter()
                    .enumerate()
                    .filter(|(u, _)| *u != v)
                    .map(|(_, f)| *f),
            );
            scanner.scan(
                poses[v],
                &self.track.grid,
                &others,
                self.noise,
                &mut car.rng,
                &mut scans[v * n..(v + 1) * n],
            );
        }
    }
}
