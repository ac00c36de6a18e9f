//! Criterion benches for the simulator: one world step, one 1081-beam scan, a batched
//! step. Geometry: the analytic stadium track (18 m straights, 9 m radius, 2 m corridor).

use std::hint::black_box;
use std::sync::Arc;

use arena_core::sim::shapes::stadium_track;
use arena_core::sim::{SimParams, Simulator, Track, STATE_SIZE};
use arena_core::track::params::DEFAULT_WALL_HEIGHT_M;
use criterion::{criterion_group, criterion_main, Criterion};
use rapier3d::parry::query::{Ray, RayCast};
use rapier3d::prelude::Vector;

fn simulator(envs: usize, per_env: usize) -> Simulator {
    let params = SimParams::default();
    let (walls, centre) = stadium_track(18.0, 9.0, 2.0);
    let track = Arc::new(Track::new(&walls, &centre, DEFAULT_WALL_HEIGHT_M).unwrap());
    let mut sim = Simulator::new(vec![track.clone()], envs, per_env, params, 0).unwrap();
    let len = track.centreline.length();
    let mut poses = Vec::new();
    for _ in 0..envs {
        for v in 0..per_env {
            poses.extend(track.centreline.pose_at(len - 16.0 + 1.2 * v as f64));
        }
    }
    sim.reset(&vec![true; envs], &poses).unwrap();
    sim
}

fn bench_sim(c: &mut Criterion) {
    // One physics step of one world with one car, driving slowly along the straight
    // (re-reset every 2000 steps so it never reaches the bend).
    let mut sim = simulator(1, 1);
    let (mut state, mut events) = (vec![0.0; STATE_SIZE], vec![0u8; 1]);
    let mut n = 0;
    c.bench_function("world step (1 car, dt 5 ms)", |b| {
        b.iter(|| {
            n += 1;
            if n % 2000 == 0 {
                sim = simulator(1, 1);
            }
            sim.step(black_box(&[0.0, 1.0]), 1, None, &mut state, &mut events)
                .unwrap()
        })
    });

    let mut scans = vec![0.0f32; sim.num_beams()];
    c.bench_function("lidar scan (1081 beams)", |b| {
        b.iter(|| {
            sim.observe(Some(&mut scans), &mut state, &mut events)
                .unwrap()
        })
    });

    // The alternatives, from the same pose: the per-beam grid walk, and ray casts on the
    // rapier/parry trimesh (the 3D collision walls) as a reference.
    let track = sim.tracks()[0].clone();
    let (ox, oy, yaw) = (
        state[0] + 0.12 * state[2].cos(),
        state[1] + 0.12 * state[2].sin(),
        state[2],
    );
    let dirs: Vec<(f64, f64)> = (0..1081)
        .map(|k| {
            let a =
                yaw - 0.75 * std::f64::consts::PI + k as f64 * 1.5 * std::f64::consts::PI / 1080.0;
            (a.cos(), a.sin())
        })
        .collect();
    c.bench_function("lidar scan (1081 beams, per-beam grid walk)", |b| {
        b.iter(|| {
            dirs.iter()
                .map(|&(dx, dy)| track.grid.cast(ox, oy, dx, dy, 30.0))
                .fold(0.0, f64::max)
        })
    });
    let mesh = track.wall_shape.as_trimesh().unwrap();
    c.bench_function("lidar scan (1081 beams, parry trimesh ray casts)", |b| {
        b.iter(|| {
            dirs.iter()
                .map(|&(dx, dy)| {
                    let ray = Ray::new(
                        Vector::new(ox as f32, oy as f32, 0.12),
                        Vector::new(dx as f32, dy as f32, 0.0),
                    );
                    mesh.cast_local_ray(&ray, 30.0, true).unwrap_or(30.0)
                })
                .fold(0.0, f32::max)
        })
    });

    for (envs, per_env) in [(256, 1), (32, 8)] {
        let mut sim = simulator(envs, per_env);
        let n = envs * per_env;
        let actions: Vec<f64> = (0..n).flat_map(|_| [0.0, 1.0]).collect();
        let (mut state, mut events) = (vec![0.0; n * STATE_SIZE], vec![0u8; n]);
        let mut k = 0;
        c.bench_function(
            &format!("batched step ({envs} envs x {per_env} cars, 10 substeps)"),
            |b| {
                b.iter(|| {
                    k += 1;
                    if k % 200 == 0 {
                        sim = simulator(envs, per_env);
                    }
                    sim.step(&actions, 10, None, &mut state, &mut events)
                        .unwrap()
                })
            },
        );
    }
}

criterion_group!(benches, bench_sim);
criterion_main!(benches);
