//! Masked resets and observes, per-env reset and noise streams (bit-exact whatever the
//! batch, the threads or the other envs' resets), and inputs refused at the door: no
//! public simulator function panics on non-finite or out-of-range input.

use std::sync::Arc;

use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::lidar::{Footprint, ScanNoise, Scanner};
use super::progress::Progress;
use super::segment_scan::segment_scan;
use super::segments::SegmentGrid;
use super::shapes::stadium_track;
use super::*;

const BEAMS: usize = 121;

fn spec(num_tracks: usize) -> StartSpec {
    StartSpec {
        random_s: true,
        s0: vec![0.0; num_tracks],
        track_weights: vec![],
        grid_spacing: 1.0,
        grid_offset: 0.2,
        lateral_noise: 0.3,
        heading_noise: 0.1,
        side_clearance: 0.25,
        speed_noise: 1.0,
        noise_std: [0.01, 0.05],
        dropout: 0.1,
    }
}

fn sim(envs: usize, seed: u64) -> Simulator {
    let mut params = SimParams::default();
    params.lidar.num_beams = BEAMS;
    params.lidar.noise_std = 0.02;
    let (walls, centre) = stadium_track(6.0, 3.0, 2.0);
    let track =
        Arc::new(Track::new(&walls, &centre, crate::track::params::DEFAULT_WALL_HEIGHT_M).unwrap());
    let (walls2, centre2) = stadium_track(10.0, 4.0, 2.5);
    let track2 = Arc::new(
        Track::new(
            &walls2,
            &centre2,
            crate::track::params::DEFAULT_WALL_HEIGHT_M,
        )
        .unwrap(),
    );
    let mut s = Simulator::new(vec![track, track2], envs, 1, params, seed).unwrap();
    s.set_start_spec(spec(2)).unwrap();
    s
}

struct Buffers {
    tracks: Vec<i64>,
    poses: Vec<f64>,
    speeds: Vec<f64>,
    state: Vec<f64>,
    events: Vec<u8>,
    scans: Vec<f32>,
}

impl Buffers {
    fn new(e: usize) -> Self {
        Buffers {
            tracks: vec![0; e],
            poses: vec![0.0; e * 3],
            speeds: vec![0.0; e],
            state: vec![0.0; e * STATE_SIZE],
            events: vec![0; e],
            scans: vec![0.0; e * BEAMS],
        }
    }

    fn reset(&mut self, sim: &mut Simulator, mask: &[bool]) {
        let out = ResetOut {
            tracks: &mut self.tracks,
            poses: &mut self.poses,
            speeds: &mut self.speeds,
        };
        sim.reset_drawn(mask, ResetGiven::default(), out).unwrap();
        sim.observe_masked(
            Some(mask),
            Some(&mut self.scans),
            &mut self.state,
            &mut self.events,
        )
        .unwrap();
    }
}

/// Env 0's scans, states and start poses over 40 steps with lidar noise and dropout, in
/// a batch of `envs` where every other env resets on its own schedule (env e at steps
/// that are multiples of e + 2); env 0 resets at steps 13 and 29.
fn env0_history(envs: usize, threads: usize) -> Vec<u64> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut s = sim(envs, 7);
        let mut b = Buffers::new(envs);
        b.reset(&mut s, &vec![true; envs]);
        let mut bits = Vec::new();
        for t in 1..=40usize {
            let actions: Vec<f64> = (0..envs)
                .flat_map(|e| [0.2 * (t as f64 * 0.1 + e as f64).sin(), 1.5])
                .collect();
            s.step(&actions, 2, Some(&mut b.scans), &mut b.state, &mut b.events)
                .unwrap();
            let mask: Vec<bool> = (0..envs)
                .map(|e| {
                    if e == 0 {
                        t == 13 || t == 29
                    } else {
                        t % (e + 2) == 0
                    }
                })
                .collect();
            if mask.iter().any(|&m| m) {
                b.reset(&mut s, &mask);
            }
            bits.extend(b.scans[..BEAMS].iter().map(|x| x.to_bits() as u64));
            bits.extend(b.state[..STATE_SIZE].iter().map(|x| x.to_bits()));
            bits.extend(b.poses[..3].iter().map(|x| x.to_bits()));
            bits.push(b.tracks[0] as u64);
        }
        bits
    })
}

#[test]
fn env_streams_are_bit_exact_across_batches_threads_and_partial_resets() {
    let alone = env0_history(1, 1);
    assert_eq!(alone, env0_history(4, 2));
    assert_eq!(alone, env0_history(4, 1));
    assert_eq!(alone, env0_history(7, 2));
}

#[test]
fn masked_observe_touches_only_masked_rows() {
    let mut s = sim(3, 1);
    let mut b = Buffers::new(3);
    b.reset(&mut s, &[true, true, true]);
    let (state, scans) = (vec![-7.0; 3 * STATE_SIZE], vec![-7.0f32; 3 * BEAMS]);
    (b.state, b.scans) = (state, scans);
    b.events = vec![99; 3];
    s.observe_masked(
        Some(&[false, true, false]),
        Some(&mut b.scans),
        &mut b.state,
        &mut b.events,
    )
    .unwrap();
    for e in [0, 2] {
        assert!(b.state[e * STATE_SIZE..(e + 1) * STATE_SIZE]
            .iter()
            .all(|&x| x == -7.0));
        assert!(b.scans[e * BEAMS..(e + 1) * BEAMS]
            .iter()
            .all(|&x| x == -7.0));
        assert_eq!(b.events[e], 99);
    }
    assert!(b.scans[BEAMS..2 * BEAMS].iter().all(|&x| x >= 0.0));
    assert_ne!(b.state[STATE_SIZE], -7.0);
}

#[test]
fn drawn_starts_lie_on_the_drawn_track_inside_the_walls() {
    let mut s = sim(64, 3);
    let mut b = Buffers::new(64);
    b.reset(&mut s, &[true; 64]);
    let mut used = [0; 2];
    for e in 0..64 {
        let t = b.tracks[e] as usize;
        used[t] += 1;
        assert_eq!(s.track_of(e), t);
        let track = &s.tracks()[t];
        let p = &b.poses[3 * e..3 * e + 3];
        // On the corridor (half width >= 1 m), at most 0.3 m off the centreline.
        let c = track.grid.clearance(p[0], p[1]);
        assert!((0.25 - 1e-9..=1.3).contains(&c), "env {e}: clearance {c}");
        assert!((0.0..=1.0).contains(&b.speeds[e]));
        // The state reports the reset pose.
        let row = &b.state[e * STATE_SIZE..];
        assert!((row[0] - p[0]).abs() < 1e-3 && (row[1] - p[1]).abs() < 1e-3);
    }
    assert!(used[0] > 10 && used[1] > 10, "{used:?}");
}

#[test]
fn clearance_matches_brute_force() {
    let (walls, _) = stadium_track(6.0, 3.0, 2.0);
    let grid = SegmentGrid::new(&walls);
    let brute = |x: f64, y: f64| {
        grid.segments()
            .iter()
            .map(|s| {
                let l2 = s[2] * s[2] + s[3] * s[3];
                let t = (((x - s[0]) * s[2] + (y - s[1]) * s[3]) / l2).clamp(0.0, 1.0);
                (x - s[0] - t * s[2]).hypot(y - s[1] - t * s[3])
            })
            .fold(f64::INFINITY, f64::min)
    };
    for (x, y) in [
        (0.0, 0.0),
        (0.0, -3.0),
        (5.0, 2.9),
        (-40.0, 17.0),
        (3.3, 0.1),
    ] {
        assert!(
            (grid.clearance(x, y) - brute(x, y)).abs() < 1e-12,
            "({x}, {y})"
        );
    }
}

#[test]
fn bad_inputs_are_refused_with_their_name_and_nothing_changes() {
    let mut s = sim(2, 0);
    let mut b = Buffers::new(2);
    b.reset(&mut s, &[true, true]);
    let before = b.state.clone();
    let msg = |r: crate::Result<()>| r.unwrap_err().to_string();
    for bad in [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1e300,
        -1e300,
        1e5,
    ] {
        let poses = [bad, 0.0, 0.0, 0.0, -3.0, 0.0];
        assert!(msg(s.reset(&[true, true], &poses)).contains("poses[0][0]"));
        let yaw = [0.0, -3.0, bad, 0.0, -3.0, 0.0];
        assert!(msg(s.reset(&[true, false], &yaw)).contains("poses[0][0]"));
        let given = ResetGiven {
            poses: Some(&poses),
            ..Default::default()
        };
        let out = ResetOut {
            tracks: &mut b.tracks,
            poses: &mut b.poses,
            speeds: &mut b.speeds,
        };
        assert!(msg(s.reset_drawn(&[true, true], given, out)).contains("poses"));
        assert!(msg(s.set_speeds(&[true, true], &[bad, 0.0])).contains("speeds[0][0]"));
        let mut bad_spec = spec(2);
        bad_spec.lateral_noise = bad;
        assert!(msg(s.set_start_spec(bad_spec)).contains("lateral_noise"));
        let mut bad_spec = spec(2);
        bad_spec.s0[1] = bad;
        if !bad.is_finite() {
            assert!(msg(s.set_start_spec(bad_spec)).contains("s0"));
        }
    }
    // Masked-out rows are not checked (they are ignored).
    s.reset(&[false, true], &[f64::NAN, 0.0, 0.0, 0.0, -3.0, 0.0])
        .unwrap();
    assert!(msg(s.set_tracks(&[0, 2])).contains("track_ids[1]"));
    assert!(msg(s.set_tracks(&[-1, 0])).contains("track_ids[0]"));
    let given = ResetGiven {
        tracks: Some(&[5, 0]),
        ..Default::default()
    };
    let out = ResetOut {
        tracks: &mut b.tracks,
        poses: &mut b.poses,
        speeds: &mut b.speeds,
    };
    assert!(msg(s.reset_drawn(&[true, true], given, out)).contains("track_ids[0]"));
    assert!(
        msg(s.observe_masked(Some(&[true]), None, &mut b.state, &mut b.events))
            .contains("env_mask")
    );
    let mut fresh = sim(2, 0);
    let out = ResetOut {
        tracks: &mut b.tracks,
        poses: &mut b.poses,
        speeds: &mut b.speeds,
    };
    let mut no_spec =
        Simulator::new(fresh.tracks().to_vec(), 2, 1, fresh.params().clone(), 0).unwrap();
    assert!(
        msg(no_spec.reset_drawn(&[true, true], ResetGiven::default(), out)).contains("start spec")
    );
    // Env 1 was reset above with a finite pose; env 0 is untouched by every refusal.
    fresh.observe(None, &mut b.state, &mut b.events).unwrap();
    s.observe(None, &mut b.state, &mut b.events).unwrap();
    assert_eq!(
        before[..STATE_SIZE]
            .iter()
            .map(|x| x.to_bits())
            .collect::<Vec<_>>(),
        b.state[..STATE_SIZE]
            .iter()
            .map(|x| x.to_bits())
            .collect::<Vec<_>>()
    );
}

/// Hostile numbers for the no-panic tests.
const HOSTILE: [f64; 8] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e300,
    -1e300,
    1e-300,
    0.0,
    -0.0,
];

#[test]
fn no_public_sim_function_panics_on_non_finite_input() {
    let (walls, centre) = stadium_track(6.0, 3.0, 2.0);
    let grid = SegmentGrid::new(&walls);
    let track = Track::new(&walls, &centre, 0.3).unwrap();
    let scanner = Scanner::new(&LidarParams {
        num_beams: 61,
        ..Default::default()
    });
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    let mut out = vec![0.0f32; 61];
    let mut s = sim(2, 0);
    let mut b = Buffers::new(2);
    b.reset(&mut s, &[true, true]);
    for &h in &HOSTILE {
        for pose in [[h, 0.0, 0.0], [0.0, h, 0.0], [0.0, -3.0, h], [h, h, h]] {
            let noise = ScanNoise {
                extra_std: h.abs().min(1.0),
                dropout: 0.1,
            };
            scanner.scan(pose, &grid, &[], noise, &mut rng, &mut out);
            assert!(out.iter().all(|x| x.is_finite()));
            let car = Footprint {
                x: h,
                y: 0.0,
                cos: h,
                sin: 0.0,
                half_length: 0.2,
                half_width: 0.1,
            };
            scanner.scan([0.0, -3.0, 0.0], &grid, &[car], noise, &mut rng, &mut out);
            let _ = s.reset(&[true, true], &[pose, [0.0, -3.0, 0.0]].concat());
        }
        let mut ranges = vec![f64::INFINITY; 8];
        let dirs = vec![[1.0, 0.0]; 8];
        segment_scan(&grid, h, 0.0, h, 0.1, &dirs, 30.0, &mut ranges);
        segment_scan(&grid, 0.0, -3.0, 0.0, h, &dirs, h, &mut ranges);
        let _ = grid.cast(h, 0.0, 1.0, 0.0, 30.0);
        let _ = grid.cast(0.0, -3.0, h, h, h);
        let _ = grid.clearance(h, h);
        let _ = grid.clear_of(h, 0.0, h);
        let _ = track.centreline.pose_at(h);
        let _ = track.centreline.project_global([h, h]);
        let mut p = Progress::reset(&track.centreline, [h, 0.0]);
        p.update(&track.centreline, [h, h], h, h);
        let _ = Track::new(&[vec![[h, 0.0], [1.0, 0.0], [1.0, 1.0]]], &centre, 0.3);
        let _ = Track::new(&walls, &[[h, 0.0], [1.0, 0.0], [1.0, 1.0]], h);
        let _ = s.set_speeds(&[true, true], &[h, h]);
        let actions = [h, h, 0.0, h];
        s.step(&actions, 1, Some(&mut b.scans), &mut b.state, &mut b.events)
            .unwrap();
        assert!(b.state.iter().all(|x| x.is_finite()));
        let mut bad = spec(2);
        bad.noise_std = [h, h];
        bad.dropout = h;
        bad.track_weights = vec![h, 1.0];
        let _ = s.set_start_spec(bad);
    }
    let _ = s.set_tracks(&[i64::MIN, i64::MAX]);
}
