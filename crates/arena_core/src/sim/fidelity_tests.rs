//! Vehicle fidelity tests in a walled hall, against physics rather than our own output:
//! the friction limit (mu g), stability over the accepted time steps, and a head-on wall
//! hit that must not spin the car.

use std::sync::Arc;

use super::params::{SimParams, MAX_INTERNAL_DT};
use super::shapes::square_room;
use super::shared_track::Track;
use super::vehicle::VehicleModel;
use super::world::{World, EVENT_WALL, STATE_SIZE};

/// A world with one car in a square hall of half-side `half` (walls from `walls`).
fn hall_with(params: &SimParams, walls: Vec<Vec<[f64; 2]>>) -> (World, VehicleModel) {
    let track = Arc::new(
        Track::new(
            &walls,
            &square_room(1.0),
            crate::track::params::DEFAULT_WALL_HEIGHT_M,
        )
        .unwrap(),
    );
    let model = VehicleModel::new(&params.vehicle, &params.physics);
    let world = World::new(track, 0, 1, &model, &params.physics, 0, 0);
    (world, model)
}

fn hall(params: &SimParams, half: f64) -> (World, VehicleModel) {
    hall_with(params, vec![square_room(half)])
}

fn state(w: &World) -> ([f64; STATE_SIZE], u8) {
    let (mut s, mut e) = ([0.0; STATE_SIZE], [0u8]);
    w.write_state(&mut s, &mut e);
    (s, e[0])
}

/// Tilt of the chassis from level (rad).
fn tilt(w: &World) -> f64 {
    let (pose, _, _) = w.chassis(0);
    let up = pose.rotation * rapier3d::prelude::Vector::Z;
    (up.z as f64).clamp(-1.0, 1.0).acos()
}

/// Steps per control interval of `period` seconds at the world's dt.
fn steps(p: &SimParams, period: f64) -> usize {
    ((period / p.physics.dt).round() as usize).max(1)
}

/// Sideways speed after pulling the car at rest sideways at its CoM for 2 s with
/// `ratio` times its weight.
fn pull(ratio: f64) -> f64 {
    let mut p = SimParams::default();
    p.physics.shortcut_free_steps = false; // the shortcut ignores external forces
    let (mut w, m) = hall(&p, 20.0);
    w.reset_vehicle(0, [0.0, 0.0, 0.0], &m);
    w.step(&[(0.0, 0.0)], steps(&p, 0.5), &m); // settle on the springs
    w.push(0, [0.0, ratio * p.vehicle.mass * p.physics.gravity, 0.0]);
    w.step(&[(0.0, 0.0)], steps(&p, 2.0), &m);
    state(&w).0[4].abs()
}

/// The paper's friction measurement, a lateral pull test: the car holds (tyres creep at
/// a few cm/s) up to a pull of mu times its weight and slides beyond. With the
/// suspension force along the tilted chassis the body roll adds a sideways push and the
/// car slid about 7 % early.
#[test]
fn lateral_pull_test_gives_mu() {
    let mu = SimParams::default().vehicle.tyre_friction;
    let (below, above) = (pull(0.97 * mu), pull(1.03 * mu));
    eprintln!("pull 0.97 mu W: {below:.3} m/s, 1.03 mu W: {above:.3} m/s");
    assert!(below < 0.2, "slides at 0.97 mu W ({below:.3} m/s)");
    assert!(above > 0.4, "holds at 1.03 mu W ({above:.3} m/s)");
}

/// Steady yaw rate after 6 s at (steer, speed) with time step `dt`, and the largest
/// chassis tilt over the last 3 s.
fn steady_turn(dt: f64, steer: f64, speed: f64) -> (f64, f64) {
    let mut p = SimParams::default();
    p.physics.dt = dt;
    let (mut w, m) = hall(&p, 80.0);
    w.reset_vehicle(0, [0.0, 0.0, 0.0], &m);
    let n = steps(&p, 0.05);
    let mut max_tilt = 0.0f64;
    for i in 0..120 {
        w.step(&[(steer, speed)], n, &m);
        if i >= 60 {
            max_tilt = max_tilt.max(tilt(&w));
        }
    }
    (state(&w).0[5], max_tilt)
}

/// Time and distance from 6 m/s down to `v_end` with a 0 m/s command at time step `dt`.
fn stop_from_6(dt: f64, v_end: f64) -> (f64, f64) {
    let mut p = SimParams::default();
    p.physics.dt = dt;
    let (mut w, m) = hall(&p, 80.0);
    w.reset_vehicle(0, [-60.0, 0.0, 0.0], &m);
    w.set_forward_speed(0, 6.0, &m);
    let (mut t, x0) = (0.0, state(&w).0[0]);
    while state(&w).0[3] > v_end && t < 5.0 {
        w.step(&[(0.0, 0.0)], 1, &m);
        t += dt;
    }
    (t, state(&w).0[0] - x0)
}

/// Every accepted dt is stable: at the largest one the car neither rocks on a straight
/// nor turns at a different rate from dt = 5 ms.
#[test]
fn largest_accepted_dt_is_stable() {
    let dt_max = 0.02;
    let mut p = SimParams::default();
    p.physics.dt = dt_max;
    assert!(p.validate().is_ok(), "dt {dt_max} should be accepted");
    let (_, straight_tilt) = steady_turn(dt_max, 0.0, 5.0);
    let (_, ref_tilt) = steady_turn(0.005, 0.0, 5.0);
    eprintln!("straight 5 m/s tilt: dt {dt_max} {straight_tilt:.5}, dt 0.005 {ref_tilt:.5} rad");
    assert!(
        straight_tilt < 0.2f64.to_radians(),
        "the car rocks {:.2} deg on a straight at dt = {dt_max}",
        straight_tilt.to_degrees()
    );
    // Distance within 3 %, time down to 0.1 m/s within 5 % (the PI loop's linear tail to
    // 0.01 m/s is left out: its length is a threshold effect).
    let (t0, d0) = stop_from_6(0.005, 0.1);
    for dt in [0.01, dt_max] {
        let (t, d) = stop_from_6(dt, 0.1);
        eprintln!("stop from 6 m/s at dt {dt}: {t:.3} s {d:.3} m (5 ms: {t0:.3} s {d0:.3} m)");
        assert!(
            (t / t0 - 1.0).abs() < 0.05 && (d / d0 - 1.0).abs() < 0.03,
            "stop {t:.3} s {d:.3} m at dt {dt} vs {t0:.3} s {d0:.3} m at 5 ms"
        );
    }
    for (steer, speed) in [(0.3, 1.0), (0.1, 5.0), (0.2, 3.0)] {
        let (r, _) = steady_turn(dt_max, steer, speed);
        let (r0, _) = steady_turn(0.005, steer, speed);
        eprintln!("turn steer {steer} speed {speed}: yaw rate {r:.4} vs {r0:.4} at 5 ms");
        assert!(
            (r / r0 - 1.0).abs() < 0.02,
            "yaw rate {r:.4} at dt {dt_max} vs {r0:.4} at 5 ms (steer {steer}, {speed} m/s)"
        );
    }
}

/// Subdivide a closed polyline so no edge is longer than `step` (like a map's walls).
fn subdivide(poly: &[[f64; 2]], step: f64) -> Vec<[f64; 2]> {
    let mut out = Vec::new();
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let k = ((b[0] - a[0]).hypot(b[1] - a[1]) / step).ceil().max(1.0) as usize;
        for j in 0..k {
            let t = j as f64 / k as f64;
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
        }
    }
    out
}

/// Worst |yaw rate|, |sideways speed| and backward speed (the rebound) from first wall
/// contact through 0.3 s after, driving head-on at 7 m/s into the wall x = half at
/// lateral position `y` with time step `dt`, starting `lead` metres short of the wall
/// (varies the impact's timing within a step).
fn head_on(walls: &[Vec<[f64; 2]>], half: f64, y: f64, lead: f64, dt: f64) -> [f64; 3] {
    let mut p = SimParams::default();
    p.physics.dt = dt;
    let (mut w, m) = hall_with(&p, walls.to_vec());
    let front =
        p.vehicle.chassis_length / 2.0 + (p.vehicle.com_to_front - p.vehicle.com_to_rear) / 2.0;
    w.reset_vehicle(0, [half - front - lead, y, 0.0], &m);
    w.set_forward_speed(0, 7.0, &m);
    let (mut contact_at, mut worst) = (None, [0.0f64; 3]);
    for i in 0..((0.3 + lead / 7.0 + 0.1) / dt) as usize {
        w.step(&[(0.0, 7.0)], 1, &m);
        let (s, ev) = state(&w);
        if contact_at.is_none() && ev & EVENT_WALL != 0 {
            contact_at = Some(i);
        }
        if let Some(c) = contact_at {
            if (i - c) as f64 * dt <= 0.3 {
                worst = [
                    worst[0].max(s[5].abs()),
                    worst[1].max(s[4].abs()),
                    worst[2].max(-s[3]),
                ];
            }
        }
    }
    assert!(contact_at.is_some(), "no wall contact at y = {y}");
    worst
}

/// Head-on hits at 7 m/s into the walls x = `half` of a square room (2 triangles per
/// side, and subdivided every 31 and 7 cm), at `positions` lateral positions spread over
/// y in [-8.5, 8.5] and `timings` impact timings within a step, at dt 2.5 ms, the default
/// and the largest internal time step. Returns the failures (|yaw rate| >= 1 rad/s or
/// sideways speed >= 0.3 m/s from contact through 0.3 s after) and the worst (yaw rate,
/// sideways speed, rebound).
fn head_on_grid(positions: usize, timings: usize) -> (Vec<String>, [f64; 3]) {
    let half = 10.0;
    let coarse = vec![square_room(half)];
    let fine = vec![subdivide(&square_room(half), 0.07)];
    let mid = vec![subdivide(&square_room(half), 0.31)];
    let mut fails = Vec::new();
    let mut worst = [0.0f64; 3];
    for dt in [0.0025, SimParams::default().physics.dt, MAX_INTERNAL_DT] {
        for (name, walls) in [("coarse", &coarse), ("fine", &fine), ("mid", &mid)] {
            for k in 0..positions {
                let y = -8.5 + 17.0 * k as f64 / (positions - 1) as f64;
                for q in 0..timings {
                    let lead = 0.3 + 7.0 * dt * q as f64 / timings as f64;
                    let hit = head_on(walls, half, y, lead, dt);
                    worst = [0, 1, 2].map(|j| worst[j].max(hit[j]));
                    let [yaw, side, _] = hit;
                    if yaw >= 1.0 || side >= 0.3 {
                        fails.push(format!(
                            "dt {dt} {name} y={y:.3} lead={lead:.4}: yaw {yaw:.2} side {side:.2}"
                        ));
                    }
                }
            }
        }
    }
    eprintln!(
        "head-on at 7 m/s, {} hits: worst yaw rate {:.3} rad/s, sideways speed {:.3} m/s, \
         rebound {:.3} m/s",
        3 * 3 * positions * timings,
        worst[0],
        worst[1],
        worst[2]
    );
    (fails, worst)
}

/// Fails on a spin (see [`head_on_grid`]) or on a rebound of 0.2 m/s or more: with a
/// restitution of 0 the car must not bounce back off the wall (under 3 % of the impact
/// speed; pitching and the tyres still pushing leave a few cm/s).
fn assert_head_on_grid(positions: usize, timings: usize) {
    let (fails, worst) = head_on_grid(positions, timings);
    assert!(
        fails.is_empty(),
        "{} spins:\n{}",
        fails.len(),
        fails.join("\n")
    );
    assert!(worst[2] < 0.2, "rebounds at {:.3} m/s", worst[2]);
}

/// A head-on hit at 7 m/s keeps the car straight at every impact position along the
/// wall (across the triangles' internal diagonals; walls of 2 triangles per side and
/// subdivided every 31 and 7 cm) and every timing within a step, at dt 2.5 ms, the
/// default and the largest internal time step: 35 positions 0.5 m apart x 4 timings.
///
/// Issue 13, defect 3: 118 of the 280 cases at dt = 5 ms spun at up to 11 rad/s. Rapier
/// reduced the chassis face's contact patch on two or more wall triangles to its deepest
/// speculative corner (it keeps only points within the world's prediction distance,
/// 5 mm, while soft CCD predicts 5 cm ahead), so the whole impact impulse went through
/// one corner; and sequential Gauss-Seidel gave the first-solved corner of the remaining
/// patches most of it. The prediction distance now covers the soft CCD and contact pairs
/// are solved as 2x2 blocks (`World::new`, rapier's `block-solver` feature). With one
/// stabilization pass the car still rebounded at up to 0.36 m/s (worst yaw rate
/// 0.73 rad/s); two passes (`STABILIZATION_ITERATIONS`) leave 0.10 m/s (0.49 rad/s).
#[test]
fn head_on_wall_hit_does_not_spin() {
    assert_head_on_grid(35, 4);
}

/// The same at a 44x denser grid (170 positions about 10 cm apart x 8 timings: 12,240
/// hits, about 10 s with optimised dependencies): a stress test, left out of a plain
/// `cargo test` and run by `make test` (and CI) through `--include-ignored`. With one
/// stabilization pass 4 hits failed (yaw rate up to 1.21 rad/s after a 0.5 m/s rebound
/// and a second, slightly askew hit); with two the worst is 0.81 rad/s.
#[test]
#[ignore = "stress test: 12,240 wall hits"]
fn head_on_wall_hit_dense_grid() {
    assert_head_on_grid(170, 8);
}

/// Forward speed after `seconds` of a straight run at command `cmd` from rest.
fn straight_run(p: &SimParams, cmd: f64, seconds: f64) -> Vec<f64> {
    let (mut w, m) = hall(p, 200.0);
    w.reset_vehicle(0, [-190.0, 0.0, 0.0], &m);
    let n = steps(p, 0.05);
    (0..(seconds / 0.05) as usize)
        .map(|_| {
            w.step(&[(0.0, cmd)], n, &m);
            state(&w).0[3]
        })
        .collect()
}

/// Top speed comes from the motor (back-EMF at the duty limit), drag and rolling
/// resistance, not from the command clamp: with the clamp out of the way the car levels
/// off below the motor's no-load speed (11.1 V * 0.95 * 3500 rpm/V over the gearing:
/// 16.0 m/s), and the default clamp still lets it reach the recorded 6.66 m/s.
#[test]
fn top_speed_comes_from_the_drivetrain() {
    let mut p = SimParams::default();
    p.vehicle.max_speed = 25.0;
    let v = straight_run(&p, 25.0, 14.0);
    let (top, before) = (v[v.len() - 1], v[v.len() - 21]);
    let v = &p.vehicle;
    let no_load = v.max_duty * v.battery_voltage * v.motor_kv / v.gear_ratio
        * 2.0
        * std::f64::consts::PI
        * v.wheel_radius
        / 60.0;
    eprintln!(
        "top speed {top:.3} m/s (1 s earlier {before:.3}), duty-limited no-load {no_load:.3}"
    );
    assert!(
        top < no_load && top > 0.8 * no_load,
        "top speed {top} vs no-load {no_load}"
    );
    assert!(
        (top - before).abs() < 0.05,
        "still accelerating: {before} -> {top}"
    );
    let v = straight_run(&SimParams::default(), 7.0, 4.0);
    assert!(
        v.iter().any(|&s| s >= 6.66),
        "never reaches 6.66 m/s: {v:?}"
    );
}

/// The PI loop settles on the commanded wheel speed (a P loop on chassis speed sat 1.6 %
/// low in a 5 m/s turn; what remains is the drive slip, well under 1 %) and a stop from
/// 6 m/s is friction-limited: never shorter than the ideal mu g stop, within 15 % of its
/// distance (equal torque to every wheel through open differentials locks the unloaded
/// rear wheels first) and 25 % of its time (the linear tail of the PI loop near 0 m/s).
#[test]
fn speed_loop_holds_speed_and_brakes_near_mu_g() {
    let (r, _) = steady_turn(0.005, 0.1, 5.0);
    let p = SimParams::default();
    let (mut w, m) = hall(&p, 80.0);
    w.reset_vehicle(0, [0.0, 0.0, 0.0], &m);
    for _ in 0..160 {
        w.step(&[(0.1, 5.0)], 10, &m);
    }
    let s = state(&w).0;
    let speed = s[3].hypot(s[4]);
    eprintln!("5 m/s turn: speed {speed:.4}, yaw rate {r:.3}");
    assert!(
        (speed / 5.0 - 1.0).abs() < 0.01,
        "turning at {speed} m/s for 5 m/s"
    );

    let (t, d) = stop_from_6(p.physics.dt, 0.01);
    let mu_g = p.vehicle.tyre_friction * p.physics.gravity;
    let (t0, d0) = (6.0 / mu_g, 36.0 / (2.0 * mu_g));
    eprintln!("brake 6 -> 0: {t:.3} s {d:.3} m, ideal {t0:.3} s {d0:.3} m");
    assert!(
        t >= 0.98 * t0 && t < 1.35 * t0,
        "stop time {t} vs ideal {t0}"
    );
    assert!(
        d >= 0.98 * d0 && d < 1.15 * d0,
        "stop distance {d} vs ideal {d0}"
    );
}

/// First-order steering lag: after one time constant the wheel has covered 1 - 1/e of
/// a small step (below the rate limit), and none of it with the lag set to zero.
#[test]
fn steering_follows_a_first_order_lag() {
    let mut p = SimParams::default();
    p.vehicle.steer_time_constant = 0.1;
    let (mut w, m) = hall(&p, 20.0);
    w.reset_vehicle(0, [0.0, 0.0, 0.0], &m);
    w.step(&[(0.1, 0.0)], steps(&p, 0.1), &m);
    let frac = state(&w).0[6] / 0.1;
    assert!(
        (frac - (1.0 - (-1.0f64).exp())).abs() < 0.01,
        "after tau: {frac}"
    );
    p.vehicle.steer_time_constant = 0.0;
    let (mut w, m) = hall(&p, 20.0);
    w.reset_vehicle(0, [0.0, 0.0, 0.0], &m);
    w.step(&[(0.1, 0.0)], steps(&p, 0.05), &m);
    assert!(
        (state(&w).0[6] - 0.1).abs() < 1e-9,
        "no lag: {}",
        state(&w).0[6]
    );
}

/// Per-vehicle parameters: half the friction lengthens the friction-limited stop, and a
/// car heavy enough that the motor, not the tyres, limits it accelerates more slowly.
#[test]
fn per_vehicle_params_change_the_dynamics() {
    use super::vehicle::CarParams;
    let p = SimParams::default();
    // A car at rest at (-60, 0) with its per-vehicle parameters changed by `edit`.
    let car = |edit: &dyn Fn(&mut CarParams)| {
        let (mut w, m) = hall(&p, 80.0);
        let mut cp = CarParams::nominal(&p.vehicle);
        edit(&mut cp);
        w.set_car_params(0, cp, &m);
        w.reset_vehicle(0, [-60.0, 0.0, 0.0], &m);
        (w, m)
    };
    let stop = |friction: f64| {
        let (mut w, m) = car(&|cp| cp.friction = friction);
        w.set_forward_speed(0, 5.0, &m);
        let x0 = state(&w).0[0];
        for _ in 0..80 {
            w.step(&[(0.0, 0.0)], 10, &m);
        }
        state(&w).0[0] - x0
    };
    let (d1, d2) = (stop(0.83), stop(0.415));
    eprintln!("stop from 5 m/s: mu 0.83 {d1:.3} m, mu 0.415 {d2:.3} m");
    assert!(d2 > 1.5 * d1, "{d1} vs {d2}");
    let speed_after = |mass: f64| {
        let (mut w, m) = car(&|cp| cp.mass = mass);
        w.step(&[(0.0, 7.0)], 100, &m);
        state(&w).0[3]
    };
    let (light, heavy) = (speed_after(4.885), speed_after(10.0));
    eprintln!("after 0.5 s: 4.885 kg {light:.3} m/s, 10 kg {heavy:.3} m/s");
    assert!(heavy < 0.9 * light, "{light} vs {heavy}");
    assert!(CarParams {
        mass: -1.0,
        ..CarParams::nominal(&p.vehicle)
    }
    .validate()
    .is_err());
}

/// A wall event means touching. The prediction distance covers a step at top speed
/// (several cm), so rapier holds speculative contacts with a wall the car merely passes;
/// counting those made cars that drove clean laps report collisions.
#[test]
fn passing_close_to_a_wall_is_not_a_contact() {
    let mut p = SimParams::default();
    p.physics.shortcut_free_steps = false; // every step through rapier's contacts
    let half = 20.0;
    let (mut w, m) = hall(&p, half);
    let side = m.half_extents[1] + m.box_centre[1].abs();
    for (gap, expect) in [(0.03, false), (-0.01, true)] {
        w.reset_vehicle(0, [-15.0, half - side - gap, 0.0], &m);
        let mut wall = false;
        for _ in 0..steps(&p, 1.5) {
            w.step(&[(0.0, 5.0)], 1, &m);
            wall |= state(&w).1 & EVENT_WALL != 0;
        }
        assert_eq!(wall, expect, "gap {gap} m: wall event {wall}");
    }
}
