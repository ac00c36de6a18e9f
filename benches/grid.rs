//! Criterion benches for the grid kernels on a synthetic ring corridor.

use arena_core::grid::edt::edt;
use arena_core::grid::flood::{flood_fill, Connectivity};
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
        c.bench_function(&format!("edt {n}x{n}"), |b| b.iter(|| edt(black_box(&wall), n, n)));
        c.bench_function(&format!("flood_fill {n}x{n}"), |b| {
            b.iter(|| flood_fill(black_box(&free), n, n, &[seed], Connectivity::Four))
        });
    }
}

criterion_group!(benches, bench_grid);
criterion_main!(benches);
