//! Per-stage timings of `measure_raster` on ROS maps (best of 3 for the whole call):
//! `cargo run --release -p arena_core --example measure_timing -- MAP.yaml [...]`.
//! Set `RAYON_NUM_THREADS=1` for single-threaded figures.
use arena_core::grid::edt::{edt, edt_within};
use arena_core::grid::mapfile::load_map;
use arena_core::grid::regions::region_tree;
use arena_core::grid::FREE;
use arena_core::track::centreline::longest_zero_loop;
use arena_core::track::metrics::{known_extent, measure_raster};
use std::time::Instant;

fn secs(t: Instant) -> f64 {
    t.elapsed().as_secs_f64()
}

fn main() {
    for path in std::env::args().skip(1) {
        let (g, _) = load_map(&path).expect("map");
        let (w, h) = (g.width, g.height);
        let mut best = f64::INFINITY;
        for _ in 0..3 {
            let t = Instant::now();
            std::hint::black_box(measure_raster(&g).expect("measure"));
            best = best.min(secs(t));
        }
        let t = Instant::now();
        let tree = region_tree(&g.data, w, h, |v| v == FREE);
        let t_tree = secs(t);
        // A stand-in side mask: every non-free cell (same size class as the real ones).
        let side: Vec<bool> = g.data.iter().map(|&v| v != FREE).collect();
        let t = Instant::now();
        let d = edt(&side, w, h);
        let t_edt = secs(t);
        let t = Instant::now();
        std::hint::black_box(edt_within(&side, w, h, 250.0));
        let t_capped = secs(t);
        let f: Vec<f32> = d.iter().map(|&x| 0.5 - x).collect();
        let t = Instant::now();
        let l = longest_zero_loop(&f, w, h);
        let t_ms = secs(t);
        let t = Instant::now();
        std::hint::black_box(known_extent(&g));
        let t_ext = secs(t);
        println!(
            "{path}: {w}x{h} measure_raster {best:.3} s | region tree {t_tree:.3} ({} regions) edt {t_edt:.3} edt_within(250) {t_capped:.3} marching {t_ms:.3} ({} pts) extent {t_ext:.3}",
            tree.len(),
            l.map(|x| x.len()).unwrap_or(0)
        );
    }
}
