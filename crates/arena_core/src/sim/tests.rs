//! Whole-simulator tests: rest, wall impact (no tunnelling), driving a lap, lidar in the
//! world, determinism across N and threads, bad actions.

use std::sync::Arc;

use super::shapes::{square_room, stadium_track};
use super::*;

fn stadium_sim(envs: usize, vehicles: usize, params: SimParams, seed: u64) -> Simulator {
    let (walls, centre) = stadium_track(6.0, 3.0, 2.0);
    let track =
        Arc::new(Track::new(&walls, &centre, crate::track::params::DEFAULT_WALL_HEIGHT_M).unwrap());
    Simulator::new(vec![track], envs, vehicles, params, seed).unwrap()
}

struct Out {
    state: Vec<f64>,
    events: Vec<u8>,
    scans: Vec<f32>,
}

impl Out {
    fn new(sim: &Simulator) -> Self {
        let n = sim.num_envs() * sim.vehicles_per_env();
        Out {
            state: vec![0.0; n * STATE_SIZE],
            events: vec![0; n],
            scans: vec![0.0; n * sim.num_beams()],
        }
    }
    fn row(&self, i: usize) -> &[f64] {
        &self.state[i * STATE_SIZE..(i + 1) * STATE_SIZE]
    }
}

/// Reset every vehicle on the stadium's bottom straight (the closing 6 m of the
/// centreline, driven towards +x), 1.2 m apart.
fn reset_on_centreline(sim: &mut Simulator) {
    let (e, v) = (sim.num_envs(), sim.vehicles_per_env());
    let c = &sim.tracks()[0].centreline;
    let mut poses = Vec::new();
    for _ in 0..e {
        for k in 0..v {
            poses.extend(c.pose_at(c.length() - 5.5 + 1.2 * k as f64));
        }
    }
    sim.reset(&vec![true; e], &poses).unwrap();
}

#[test]
fn car_at_rest_stays_at_rest() {
    let mut sim = stadium_sim(1, 1, SimParams::default(), 0);
    reset_on_centreline(&mut sim);
    let mut out = Out::new(&sim);
    sim.observe(None, &mut out.state, &mut out.events).unwrap();
    let start = out.row(0).to_vec();
    for _ in 0..40 {
        sim.step(&[0.0, 0.0], 10, None, &mut out.state, &mut out.events)
            .unwrap();
    }
    let end = out.row(0);
    // 2 s at rest: the car settles on its springs and does not creep.
    assert!(
        (end[0] - start[0]).abs() < 1e-4 && (end[1] - start[1]).abs() < 1e-4,
        "{start:?} -> {end:?}"
    );
    assert!((end[2] - start[2]).abs() < 1e-4);
    assert!(end[3].abs() < 1e-3 && end[4].abs() < 1e-3 && end[5].abs() < 1e-3);
    assert_eq!(out.events[0], 0);
}

/// Drive straight at the wall of a square room at full speed command; the chassis
/// front must never pass the wall (tolerance: 5 mm of contact penetration; soft CCD
/// makes it 0 at dt = 5 and 10 ms).
fn wall_impact(dt: f64, max_speed: f64) {
    let mut params = SimParams::default();
    params.physics.dt = dt;
    params.vehicle.max_speed = max_speed;
    let h = 10.0;
    let room = square_room(h);
    let centre = square_room(5.0);
    let track = Arc::new(
        Track::new(
            &[room],
            &centre,
            crate::track::params::DEFAULT_WALL_HEIGHT_M,
        )
        .unwrap(),
    );
    let mut sim = Simulator::new(vec![track], 1, 1, params.clone(), 0).unwrap();
    sim.reset(&[true], &[-9.0, 0.0, 0.0]).unwrap();
    let mut out = Out::new(&sim);
    let front = params.vehicle.chassis_length / 2.0
        + (params.vehicle.com_to_front - params.vehicle.com_to_rear) / 2.0;
    let (mut top, mut hit, mut max_x) = (0.0f64, false, f64::NEG_INFINITY);
    for _ in 0..(6.0 / dt) as usize {
        sim.step(&[0.0, 1e9], 1, None, &mut out.state, &mut out.events)
            .unwrap();
        let r = out.row(0);
        top = top.max(r[3]);
        hit |= out.events[0] & EVENT_WALL != 0;
        max_x = max_x.max(r[0] + front);
        assert!(r.iter().all(|x| x.is_finite()));
    }
    eprintln!("wall impact dt={dt}: top speed {top:.3} m/s, front max x {max_x:.4} (wall at {h})");
    assert!(hit, "no wall contact reported");
    assert!(
        top > 0.9 * max_speed,
        "top speed {top} never near {max_speed}"
    );
    assert!(
        max_x < h + 0.005,
        "chassis front reached x = {max_x} beyond the wall at {h}"
    );
    assert!(
        out.row(0)[0] + front > h - 0.1,
        "car stopped short of the wall: {:?}",
        out.row(0)
    );
}

#[test]
fn car_driven_at_a_wall_stops_at_it() {
    wall_impact(0.005, 7.0);
    wall_impact(0.01, 7.0);
}

#[test]
fn car_accelerates_turns_and_counts_progress() {
    let mut sim = stadium_sim(1, 1, SimParams::default(), 0);
    reset_on_centreline(&mut sim);
    let mut out = Out::new(&sim);
    for _ in 0..20 {
        sim.step(&[0.0, 3.0], 10, None, &mut out.state, &mut out.events)
            .unwrap();
    }
    let r = out.row(0);
    assert!((r[3] - 3.0).abs() < 0.2, "speed {r:?}");
    assert!(r[9] > 1.5, "progress {r:?}");
    // Full left lock at 2 m/s: steady circle with yaw rate close to v tan(delta) / L.
    let mut params = SimParams::default();
    params.physics.dt = 0.005;
    let mut sim = Simulator::new(
        vec![Arc::new(
            Track::new(&[square_room(20.0)], &square_room(5.0), 0.5).unwrap(),
        )],
        1,
        1,
        params,
        0,
    )
    .unwrap();
    sim.reset(&[true], &[0.0, 0.0, 0.0]).unwrap();
    for _ in 0..60 {
        sim.step(&[0.3, 2.0], 10, None, &mut out.state, &mut out.events)
            .unwrap();
    }
    let r = out.row(0);
    let kinematic = r[3] * 0.3f64.tan() / 0.3275;
    assert!(
        r[5] > 0.7 * kinematic && r[5] < 1.1 * kinematic,
        "yaw rate {} vs kinematic {kinematic}",
        r[5]
    );
}

#[test]
fn lidar_in_world_sees_walls_and_other_cars() {
    let mut params = SimParams::default();
    params.lidar.mount_x = 0.0;
    let track = Arc::new(Track::new(&[square_room(5.0)], &square_room(2.0), 0.5).unwrap());
    let mut sim = Simulator::new(vec![track], 1, 2, params, 0).unwrap();
    // Car 0 at the origin facing +x; car 1 three metres ahead, sideways.
    sim.reset(
        &[true],
        &[0.0, 0.0, 0.0, 3.0, 0.0, std::f64::consts::FRAC_PI_2],
    )
    .unwrap();
    let mut out = Out::new(&sim);
    sim.observe(Some(&mut out.scans), &mut out.state, &mut out.events)
        .unwrap();
    let b = sim.num_beams();
    let mid = b / 2;
    // Straight ahead: the other car's side (its box is 0.29 wide; centre offset along its
    // own x, i.e. along world y) at 3 - 0.145 m.
    assert!(
        (out.scans[mid] as f64 - (3.0 - 0.145)).abs() < 1e-3,
        "{}",
        out.scans[mid]
    );
    // Straight left (beam at +90 deg = index mid + 360): wall at y = 5.
    assert!(
        (out.scans[mid + 360] as f64 - 5.0).abs() < 1e-3,
        "{}",
        out.scans[mid + 360]
    );
    // Car 1 looking along +y sees the wall at 5 m (minus the mount offset 0).
    assert!((out.scans[b + mid] as f64 - 5.0).abs() < 1e-3);
}

fn run_batch(envs: usize, threads: usize) -> (Vec<f64>, Vec<f32>) {
    let mut params = SimParams::default();
    params.lidar.noise_std = 0.02;
    params.lidar.num_beams = 181;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut sim = stadium_sim(envs, 2, params, 42);
        reset_on_centreline(&mut sim);
        let mut out = Out::new(&sim);
        for t in 0..30 {
            let actions: Vec<f64> = (0..envs * 2)
                .flat_map(|i| {
                    let e = i / 2;
                    [
                        0.3 * ((t + e) as f64 * 0.3).sin(),
                        2.0 + (i % 2) as f64 + 0.1 * e as f64,
                    ]
                })
                .collect();
            sim.step(
                &actions,
                4,
                Some(&mut out.scans),
                &mut out.state,
                &mut out.events,
            )
            .unwrap();
        }
        (out.state, out.scans)
    })
}

#[test]
fn bit_identical_across_thread_counts_and_num_envs() {
    let (s1, l1) = run_batch(3, 1);
    let (s2, l2) = run_batch(3, 2);
    assert!(s1.iter().zip(&s2).all(|(a, b)| a.to_bits() == b.to_bits()));
    assert!(l1.iter().zip(&l2).all(|(a, b)| a.to_bits() == b.to_bits()));
    // Env 2 behaves identically whether the batch holds 3 or 5 envs.
    let (s5, l5) = run_batch(5, 2);
    let (rs, rl) = (2 * STATE_SIZE, 2 * 181);
    assert!(s1[2 * rs..3 * rs]
        .iter()
        .zip(&s5[2 * rs..3 * rs])
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    assert!(l1[2 * rl..3 * rl]
        .iter()
        .zip(&l5[2 * rl..3 * rl])
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    // Noise differs between vehicles (independent streams).
    assert_ne!(l1[..181], l1[181..362]);
}

#[test]
fn sanitised_actions_drive_as_the_raw_ones() {
    // One rule: what `sanitise_actions` stores is what `step` applies (NaN -> 0, ±inf -> the
    // bound), so stepping either gives the same car, bit for bit.
    let raw = [
        f64::NAN,
        f64::INFINITY,
        f64::INFINITY,
        2.0,
        f64::NEG_INFINITY,
        f64::NAN,
        0.1,
        f64::NEG_INFINITY,
    ];
    let mut clean = raw;
    let probe = stadium_sim(2, 2, SimParams::default(), 0);
    probe.sanitise_actions(&mut clean).unwrap();
    assert_eq!(clean, [0.0, 7.0, 0.524, 2.0, -0.524, 0.0, 0.1, -3.0]);
    assert!(probe.sanitise_actions(&mut [0.0; 6]).is_err());
    let run = |actions: &[f64]| {
        let mut sim = stadium_sim(2, 2, SimParams::default(), 0);
        reset_on_centreline(&mut sim);
        let mut out = Out::new(&sim);
        for _ in 0..20 {
            sim.step(actions, 5, None, &mut out.state, &mut out.events)
                .unwrap();
        }
        out.state
    };
    let (a, b) = (run(&raw), run(&clean));
    assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
}

#[test]
fn bad_actions_never_make_a_nan_state() {
    let mut sim = stadium_sim(2, 2, SimParams::default(), 0);
    reset_on_centreline(&mut sim);
    let mut out = Out::new(&sim);
    let bad = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1e300,
        -1e300,
        0.0,
        f64::MIN_POSITIVE,
        5.0,
    ];
    for t in 0..40 {
        let actions: Vec<f64> = (0..8).map(|i| bad[(i * 3 + t) % bad.len()]).collect();
        sim.step(
            &actions,
            5,
            Some(&mut out.scans),
            &mut out.state,
            &mut out.events,
        )
        .unwrap();
        assert!(out.state.iter().all(|x| x.is_finite()));
        assert!(out.scans.iter().all(|x| x.is_finite()));
        for v in 0..4 {
            assert!(out.row(v)[6].abs() <= 0.524 + 1e-12);
        }
    }
    assert!(out.events.iter().all(|e| e & EVENT_FAULT == 0));
    // Wrong lengths and ids are errors, not panics.
    assert!(sim
        .step(&[0.0; 3], 1, None, &mut out.state, &mut out.events)
        .is_err());
    assert!(sim
        .step(&[0.0; 8], 0, None, &mut out.state, &mut out.events)
        .is_err());
    assert!(sim.set_tracks(&[0, 1]).is_err());
    assert!(sim.reset(&[true, false], &[f64::NAN; 12]).is_err());
}

/// The free-step shortcut integrates exactly like rapier: two cars weaving in an empty
/// room end up bit-identical to the full pipeline (the wall test runs with it on).
#[test]
fn free_step_shortcut_matches_the_full_pipeline() {
    let run = |shortcut: bool| {
        let mut params = SimParams::default();
        params.physics.shortcut_free_steps = shortcut;
        let track = Arc::new(Track::new(&[square_room(30.0)], &square_room(5.0), 0.5).unwrap());
        let mut sim = Simulator::new(vec![track], 1, 2, params, 0).unwrap();
        sim.reset(&[true], &[0.0, 0.0, 0.0, 0.0, 5.0, 0.0]).unwrap();
        let mut out = Out::new(&sim);
        for t in 0..40 {
            let steer = 0.3 * (t as f64 * 0.2).sin();
            sim.step(
                &[steer, 3.0, -steer, 2.0],
                20,
                None,
                &mut out.state,
                &mut out.events,
            )
            .unwrap();
        }
        (out.state, sim.step_counts())
    };
    let ((fast, c_fast), (full, c_full)) = (run(true), run(false));
    assert_eq!(c_full, [800, 0]);
    // Most steps of free driving take the shortcut (not those where hard pitch or roll
    // brings a chassis corner within the contact margin of the ground: the launches at
    // the traction limit and the weave's speed changes here).
    assert!(
        c_fast[1] > 650 && c_fast[0] + c_fast[1] == 800,
        "{c_fast:?}"
    );
    // It replays rapier's contact-free integration exactly: bit-identical states.
    assert!(fast
        .iter()
        .zip(&full)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    for v in 0..2 {
        let (a, b) = (&fast[v * STATE_SIZE..], &full[v * STATE_SIZE..]);
        let d = (a[0] - b[0]).hypot(a[1] - b[1]);
        assert!(
            d < 0.02,
            "vehicle {v}: {:?} vs {:?} ({d} m apart)",
            &a[..6],
            &b[..6]
        );
        assert!((a[3] - b[3]).abs() < 0.02 && (a[2] - b[2]).abs() < 0.01);
    }
}

/// Two cars driven head-on into each other report a vehicle contact (not a wall one),
/// stop instead of passing through each other, and never produce a fault.
#[test]
fn head_on_cars_report_vehicle_contact() {
    let track = Arc::new(Track::new(&[square_room(20.0)], &square_room(5.0), 0.5).unwrap());
    let mut sim = Simulator::new(vec![track], 1, 2, SimParams::default(), 0).unwrap();
    sim.reset(&[true], &[-3.0, 0.0, 0.0, 3.0, 0.0, std::f64::consts::PI])
        .unwrap();
    let mut out = Out::new(&sim);
    let mut seen = 0u8;
    for _ in 0..60 {
        sim.step(
            &[0.0, 4.0, 0.0, 4.0],
            10,
            None,
            &mut out.state,
            &mut out.events,
        )
        .unwrap();
        seen |= out.events[0] | out.events[1];
        // Chassis boxes are 0.55 m long: centres never closer than that minus contact slack.
        assert!(
            out.row(0)[0] < out.row(1)[0],
            "cars passed through each other"
        );
    }
    assert!(seen & EVENT_VEHICLE != 0, "no vehicle contact reported");
    assert_eq!(seen & (EVENT_WALL | EVENT_FAULT), 0);
    assert!(
        out.row(1)[0] - out.row(0)[0] > 0.5,
        "{:?} {:?}",
        out.row(0),
        out.row(1)
    );
}

#[test]
fn rolling_start_keeps_its_speed_and_bad_speeds_are_refused() {
    let mut sim = stadium_sim(2, 1, SimParams::default(), 0);
    reset_on_centreline(&mut sim);
    sim.set_speeds(&[true, false], &[3.0, 3.0]).unwrap();
    let mut out = Out::new(&sim);
    sim.observe(None, &mut out.state, &mut out.events).unwrap();
    assert!((out.row(0)[3] - 3.0).abs() < 1e-3, "vx {}", out.row(0)[3]);
    assert!(out.row(1)[3].abs() < 1e-6); // masked out: still at rest
    for _ in 0..4 {
        sim.step(
            &[0.0, 3.0, 0.0, 0.0],
            10,
            None,
            &mut out.state,
            &mut out.events,
        )
        .unwrap();
    }
    assert!((out.row(0)[3] - 3.0).abs() < 0.1, "vx {}", out.row(0)[3]);
    assert!(out.row(0)[9] > 0.5); // travelled about 0.6 m in 0.2 s
    for bad in [f64::NAN, 1e3, -1e3] {
        assert!(sim.set_speeds(&[true, true], &[bad, 0.0]).is_err());
    }
    assert!(sim.set_speeds(&[true], &[1.0]).is_err());
}
