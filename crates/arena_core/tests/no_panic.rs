//! Property tests of the core's public doors: for random finite and non-finite inputs
//! (NaN, ±inf, ±0, 1e±300, subnormals, huge counts), every function returns a value or an
//! error and never panics. Seeded (ChaCha8), so a failure names a reproducible case.

use std::panic::{catch_unwind, AssertUnwindSafe};

use arena_core::grid::{mapfile, pgm, png_io, rasterise, OccupancyGrid, FREE, OCCUPIED};
use arena_core::limits;
use arena_core::track::{build, features, metrics, params::BuildParams};
use rand_chacha::rand_core::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const CASES: usize = 200;

/// A value from the hostile palette or a plain random one.
fn num(rng: &mut ChaCha8Rng) -> f64 {
    const PALETTE: [f64; 14] = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        0.0,
        -0.0,
        1e300,
        -1e300,
        1e-300,
        f64::MIN_POSITIVE / 4.0,
        1e6,
        1000.0,
        -5.0,
        1e-7,
        f64::MAX,
    ];
    match rng.next_u32() % 3 {
        0 => PALETTE[rng.next_u32() as usize % PALETTE.len()],
        1 => (rng.next_u32() as f64 / u32::MAX as f64 - 0.5) * 40.0,
        _ => (rng.next_u32() as f64 / u32::MAX as f64) * 0.2,
    }
}

/// Run `f` and fail with `what` if it panics.
fn no_panic<T>(what: impl std::fmt::Debug, f: impl FnOnce() -> T) {
    if catch_unwind(AssertUnwindSafe(f)).is_err() {
        panic!("panicked on {what:?}");
    }
}

fn ring_grid(resolution: f64, origin: [f64; 3]) -> OccupancyGrid {
    let n = 40usize;
    let mut g = OccupancyGrid::filled(n, n, resolution, origin, OCCUPIED);
    for r in 0..n {
        for c in 0..n {
            let d = ((r as f64 - 19.5).powi(2) + (c as f64 - 19.5).powi(2)).sqrt();
            if (8.0..16.0).contains(&d) {
                g.data[r * n + c] = FREE;
            }
        }
    }
    g
}

#[test]
fn grid_doors_never_panic() {
    let mut rng = ChaCha8Rng::seed_from_u64(10);
    for _ in 0..CASES {
        let (res, origin) = (num(&mut rng), [num(&mut rng), num(&mut rng), num(&mut rng)]);
        let g = ring_grid(res, origin);
        no_panic(("measure", res, origin), || metrics::measure_raster(&g));
        let start = Some([num(&mut rng), num(&mut rng)]);
        no_panic(("build", res, origin, start), || {
            build::build_geometry(&g, &BuildParams::default(), start)
        });
        let (w, h) = (
            rng.next_u64() as usize,
            rng.next_u64() as usize >> (rng.next_u32() % 64),
        );
        no_panic(("cells", w, h), || limits::check_cells(w, h, "x"));
        no_panic(("header", w, h, res), || {
            limits::check_grid_header(w, h, res, origin)
        });
    }
}

#[test]
fn build_params_never_panic() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let fields = [
        "wall_height_m",
        "wall_offset_m",
        "tube_diameter_m",
        "ring_spacing_m",
        "ring_width_m",
        "ring_scale",
        "simplify_tolerance_m",
        "centreline_spacing_m",
        "floor_margin_m",
    ];
    let g = ring_grid(0.05, [0.0; 3]);
    for _ in 0..CASES / 4 {
        let k = fields[rng.next_u32() as usize % fields.len()];
        let v = num(&mut rng);
        // serde_json refuses non-finite numbers: those take the text route ("NaN").
        let json = format!(
            "{{\"{k}\": {}}}",
            if v.is_finite() {
                format!("{v:e}")
            } else {
                "1e999".into()
            }
        );
        no_panic(&json, || {
            if let Ok(p) = BuildParams::from_json(&json) {
                let _ = build::build_geometry(&g, &p, None);
            }
        });
    }
}

#[test]
fn curves_and_rasteriser_never_panic() {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    for _ in 0..CASES {
        let n = (rng.next_u32() % 12) as usize;
        let pts: Vec<[f64; 2]> = (0..n)
            .map(|_| {
                if rng.next_u32() % 4 == 0 {
                    [1.0, 1.0] // repeated points
                } else {
                    [num(&mut rng) * 10.0, num(&mut rng) * 10.0]
                }
            })
            .collect();
        let (r, ex) = (num(&mut rng), num(&mut rng));
        no_panic(("curve", &pts, r, ex), || {
            if features::check_curve_args(&pts, r, ex).is_ok() {
                features::analyse_closed_curve(&pts, r);
                features::self_clearance(&pts, ex, 0.1);
            }
        });
        let widths: Vec<f64> = (0..n).map(|_| num(&mut rng)).collect();
        let (res, t, m) = (num(&mut rng), num(&mut rng), num(&mut rng));
        no_panic(("rasterise", &pts, &widths, res, t, m), || {
            rasterise::rasterise_centreline(&pts, &widths, res, t, m)
        });
    }
}

#[test]
fn image_decoders_never_panic() {
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    for _ in 0..CASES {
        let dims = [
            rng.next_u64(),
            rng.next_u32() as u64,
            (rng.next_u32() % 5000) as u64,
        ];
        let (w, h) = (
            dims[rng.next_u32() as usize % 3],
            dims[rng.next_u32() as usize % 3],
        );
        let maxval = [1u64, 255, 256, 65535, 65536, u64::MAX][rng.next_u32() as usize % 6];
        let magic = ["P2", "P5", "P6", "PX"][rng.next_u32() as usize % 4];
        let mut bytes = format!("{magic}\n{w} {h}\n{maxval}\n").into_bytes();
        bytes.extend((0..rng.next_u32() % 64).map(|_| rng.next_u32() as u8));
        no_panic(("pgm", w, h, maxval, magic), || pgm::decode(&bytes));
        let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
        png.extend((0..rng.next_u32() % 96).map(|_| rng.next_u32() as u8));
        no_panic("png bytes", || png_io::decode(&png));
    }
}

#[test]
fn map_yaml_fields_never_panic() {
    let mut rng = ChaCha8Rng::seed_from_u64(14);
    let dir = std::env::temp_dir().join(format!("arena_no_panic_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("m.pgm"), pgm::encode(&[FREE; 400], 20, 20)).unwrap();
    let texts = [
        "1e300", ".nan", "-.inf", "1e-300", "0", "-1", "true", "[1, 2]", "{a: 1}", "''",
    ];
    for i in 0..CASES / 2 {
        let mut pick = || texts[rng.next_u32() as usize % texts.len()];
        let yaml = format!(
            "image: m.pgm\nresolution: {}\norigin: [{}, {}, {}]\nnegate: {}\nfree_thresh: {}\n",
            pick(),
            pick(),
            pick(),
            pick(),
            pick(),
            pick()
        );
        let path = dir.join(format!("m{i}.yaml"));
        std::fs::write(&path, &yaml).unwrap();
        no_panic(&yaml, || mapfile::load_map(&path));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn geometry_building_blocks_never_panic() {
    use arena_core::geometry::{contour, smooth, tube};
    use arena_core::grid::edt;
    let mut rng = ChaCha8Rng::seed_from_u64(15);
    for _ in 0..CASES {
        let n = (rng.next_u32() % 8) as usize;
        let pts: Vec<[f64; 2]> = (0..n).map(|_| [num(&mut rng), num(&mut rng)]).collect();
        let (a, b) = (num(&mut rng), (rng.next_u32() % 70) as usize);
        no_panic(("simplify", &pts, a), || smooth::simplify_closed(&pts, a));
        no_panic(("smooth", &pts, b), || smooth::smooth_closed(&pts, b));
        // Spacing and radius come validated from BuildParams; only plausible ones here.
        let s = a.abs().clamp(1e-3, 10.0);
        if arena_core::geometry::polyline_length(&pts, true) / s < 1e6 {
            no_panic(("resample", &pts, s), || smooth::resample_closed(&pts, s));
            no_panic(("tube", &pts, s), || {
                tube::closed_tube_mesh(&pts, s, 0.0, 3 + b % 10)
            });
        }
        no_panic(("polyline", &pts, a), || {
            use arena_core::geometry::polyline as pl;
            (
                pl::cumulative_length(&pts, true),
                pl::curvature_closed(&pts, a),
                pl::min_radius_closed(&pts, a),
                pl::self_intersections_closed(&pts),
            )
        });
        let (w, h) = ((rng.next_u32() % 9) as usize, (rng.next_u32() % 9) as usize);
        let f: Vec<f32> = (0..w * h).map(|_| num(&mut rng) as f32).collect();
        no_panic(("marching", w, h), || {
            contour::marching_squares(&f, w, h, a as f32)
        });
        let mask: Vec<bool> = (0..w * h).map(|_| rng.next_u32() % 3 == 0).collect();
        no_panic(("edt", w, h, a), || edt::edt_within(&mask, w, h, a));
    }
}
