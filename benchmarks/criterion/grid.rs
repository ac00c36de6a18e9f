//! Criterion benches for the grid kernels and the geometry build on a synthetic ring
//! corridor at three raster sizes (0.13, 1 and 10 MP).

use arena_core::geometry::contour::marching_squares;
use arena_core::grid::edt::edt;
use arena_core::grid::flood::{flood_fill, Connectivity};
use arena_core::grid::regions::region_tree;
use arena_core::grid::{OccupancyGrid, FREE, OCCUPIED};
use arena_core::track::build::build_geometry;
use arena_core::track::params::BuildParams;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

/// A ring corridor of radius ~0.35 n with width ~0.1 n on an n × n grid.
fn ring(n: usize) -> Vec<bool> {
    let c = n as f64 / 2.0;
    (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64 - c, (i / n) as f64 - c);
            let r = (x * x + y * y).sqrt();
            (r - 0.35 * n as f64).abs() < 0.05 * n as f64
        })
        .collect()
}

fn bench_grid(c: &mut Criterion) {
    for n in [360usize, 1000, 3200] {
        let free = ring(n);
        let wall: Vec<bool> = free.iter().map(|f| !f).collect();
        let seed = free.iter().position(|&f| f).unwrap();
        c.bench_function(&format!("edt {n}x{n}"), |b| {
            b.iter(|| edt(black_box(&wall), n, n))
        });
        c.bench_function(&format!("flood_fill {n}x{n}"), |b| {
            b.iter(|| flood_fill(black_box(&free), n, n, &[seed], Connectivity::Four))
        });
        let data: Vec<u8> = free
            .iter()
            .map(|&f| if f { FREE } else { OCCUPIED })
            .collect();
        c.bench_function(&format!("region_tree {n}x{n}"), |b| {
            b.iter(|| region_tree(black_box(&data), n, n, |v| v == FREE))
        });
        let field: Vec<f32> = edt(&wall, n, n);
        c.bench_function(&format!("marching_squares {n}x{n}"), |b| {
            b.iter(|| marching_squares(black_box(&field), n, n, 2.5))
        });
        let g = OccupancyGrid {
            width: n,
            height: n,
            resolution: 0.05,
            origin: [0.0; 3],
            data,
        };
        c.bench_function(&format!("build_geometry {n}x{n}"), |b| {
            b.iter(|| build_geometry(black_box(&g), &BuildParams::default(), None).unwrap())
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench_grid
}
criterion_main!(benches);
