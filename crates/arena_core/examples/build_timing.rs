//! Per-stage timings of the geometry build on ROS maps (best of 3 runs):
//! `cargo run --release -p arena_core --example build_timing -- MAP.yaml [MAP.yaml ...]`.
//! Set `RAYON_NUM_THREADS=1` for single-threaded figures.

use arena_core::grid::mapfile::load_map;
use arena_core::track::build::build_geometry;
use arena_core::track::params::BuildParams;

/// CPU seconds (user + system) used by this process so far (Linux /proc; 0 elsewhere).
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit(')')
        .next()
        .unwrap_or("")
        .split_whitespace()
        .collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (ticks(11) + ticks(12)) / 100.0
}

fn main() {
    for path in std::env::args().skip(1) {
        let (g, _) = match load_map(&path) {
            Ok(m) => m,
            Err(e) => {
                println!("{path}: {e}");
                continue;
            }
        };
        let mut best: Option<Vec<(&'static str, f64)>> = None;
        let mut summary = String::new();
        let cpu0 = cpu_seconds();
        for _ in 0..3 {
            match build_geometry(&g, &BuildParams::default(), None) {
                Ok(geo) => {
                    if best
                        .as_ref()
                        .is_none_or(|b| geo.timings.last().unwrap().1 < b.last().unwrap().1)
                    {
                        summary = format!(
                            "iou {:.4} vertices {} triangles {}",
                            geo.iou,
                            geo.wall_mesh.vertices.len()
                                + geo.duct_mesh.vertices.len()
                                + geo.ring_mesh.vertices.len()
                                + geo.floor.vertices.len(),
                            geo.wall_mesh.triangles.len()
                                + geo.duct_mesh.triangles.len()
                                + geo.ring_mesh.triangles.len()
                                + geo.floor.triangles.len()
                        );
                        best = Some(geo.timings);
                    }
                }
                Err(e) => {
                    summary = e.to_string();
                    break;
                }
            }
        }
        let stages: Vec<String> = best
            .unwrap_or_default()
            .iter()
            .map(|(k, v)| format!("{k}={:.1}ms", v * 1e3))
            .collect();
        let cpu = (cpu_seconds() - cpu0) / 3.0;
        println!(
            "{path} {:.2} MP cpu/run={:.0}ms {} {}",
            g.megapixels(),
            cpu * 1e3,
            stages.join(" "),
            summary
        );
    }
}
