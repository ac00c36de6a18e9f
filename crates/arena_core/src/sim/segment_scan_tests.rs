//! Tests of the segment scan: bit-for-bit equality with the per-beam grid walk.

use super::*;
use crate::sim::shapes::stadium_track;
use std::f64::consts::{PI, TAU};

/// Scan once with `n` beams over `fov` from `(ox, oy)` heading `yaw` and check
/// every beam against the per-beam grid walk, bit for bit; returns the number of hits.
fn check_against_walk(grid: &SegmentGrid, ox: f64, oy: f64, yaw: f64, fov: f64, n: usize) -> usize {
    let inc = fov / (n - 1) as f64;
    let theta0 = yaw - fov / 2.0;
    let dirs: Vec<[f64; 2]> = (0..n)
        .map(|k| {
            let a = theta0 + k as f64 * inc;
            [a.cos(), a.sin()]
        })
        .collect();
    let mut ranges = vec![f64::INFINITY; n];
    segment_scan(grid, ox, oy, theta0, inc, &dirs, 30.0, &mut ranges);
    let mut hits = 0;
    for k in 0..n {
        let walk = grid.cast(ox, oy, dirs[k][0], dirs[k][1], 30.0);
        let swept = if ranges[k] <= 30.0 {
            ranges[k]
        } else {
            f64::INFINITY
        };
        assert_eq!(
            walk.to_bits(),
            swept.to_bits(),
            "({ox}, {oy}) beam {k}: {walk} vs {swept}"
        );
        hits += walk.is_finite() as usize;
    }
    hits
}

#[test]
fn segment_scan_equals_the_grid_walk_bit_for_bit() {
    let (mut walls, _) = stadium_track(18.0, 9.0, 2.0);
    walls.push(vec![[1.0, -9.5], [1.3, -9.2], [1.0, -8.9]]); // a small obstacle
    let grid = SegmentGrid::new(&walls);
    for (ox, oy, yaw, fov, n) in [
        (0.0, -9.0, 0.3, 4.712389, 1081),
        (-12.0, 3.0, 2.0, TAU, 720),
        (5.0, 9.2, -1.0, 1.0, 3),
    ] {
        check_against_walk(&grid, ox, oy, yaw, fov, n);
    }
}

#[test]
fn culled_segment_scan_equals_the_grid_walk_on_a_large_map() {
    // A 200 m x 90 m stadium (blocks far beyond range and behind walls get culled)
    // with a field of small obstacles, scanned from poses around the lap.
    let (mut walls, centre) = stadium_track(120.0, 40.0, 3.0);
    for i in 0..40 {
        let (x, y) = (-60.0 + 3.0 * i as f64, -40.0 + 0.4 * (i % 3) as f64);
        walls.push(vec![[x, y], [x + 0.3, y + 0.2], [x, y + 0.4]]);
    }
    let grid = SegmentGrid::new(&walls);
    let mut hits = 0;
    for (i, c) in centre.iter().enumerate().step_by(centre.len() / 23) {
        hits += check_against_walk(
            &grid,
            c[0] + 0.3,
            c[1] - 0.2,
            i as f64 * 0.7,
            4.712389,
            1081,
        );
    }
    assert!(hits > 10_000, "{hits}");
}

#[test]
fn fast_atan2_is_within_2e5() {
    for i in 0..10_000 {
        let a = i as f64 / 10_000.0 * TAU - PI;
        for r in [1e-3, 1.0, 30.0] {
            let (y, x) = (r * a.sin(), r * a.cos());
            let d = (fast_atan2(y, x) - y.atan2(x)).abs();
            assert!(d < 2e-5 || (d - TAU).abs() < 2e-5, "{a}: {d}");
        }
    }
}

/// A circuit like a map's (Spielberg: two closed walls of ~1100 points, 0.06-8 m edges,
/// the inner one clockwise): a wobbly closed centreline about 120 m x 80 m, walls offset
/// by a varying half width and snapped to a 0.05 m raster (staircase edges, merged where
/// collinear), a few small obstacles and one open two-point wall. Returns (walls,
/// centreline).
pub(super) fn raster_circuit() -> (Vec<Vec<[f64; 2]>>, Vec<[f64; 2]>) {
    let m = 2400;
    let centre: Vec<[f64; 2]> = (0..m)
        .map(|i| {
            let a = i as f64 / m as f64 * TAU;
            let r = 1.0 + 0.18 * (2.0 * a).sin() + 0.07 * (5.0 * a + 1.0).cos();
            [60.0 * r * a.cos(), 40.0 * r * a.sin()]
        })
        .collect();
    let wall = |side: f64| -> Vec<[f64; 2]> {
        let mut pts: Vec<[f64; 2]> = Vec::new();
        for i in 0..m {
            let (p, q) = (centre[i], centre[(i + 1) % m]);
            let (tx, ty) = (q[0] - p[0], q[1] - p[1]);
            let l = tx.hypot(ty);
            let half = circuit_half_width(i, m);
            let (x, y) = (p[0] - side * half * ty / l, p[1] + side * half * tx / l);
            let snapped = [(x / 0.05).round() * 0.05, (y / 0.05).round() * 0.05];
            if pts.last() != Some(&snapped) {
                pts.push(snapped);
            }
        }
        // Drop points in the middle of straight runs, as a map's contour tracer does.
        let mut out: Vec<[f64; 2]> = Vec::new();
        for (k, &p) in pts.iter().enumerate() {
            let (a, b) = (
                pts[(k + pts.len() - 1) % pts.len()],
                pts[(k + 1) % pts.len()],
            );
            let cross = (p[0] - a[0]) * (b[1] - p[1]) - (p[1] - a[1]) * (b[0] - p[0]);
            if cross.abs() > 1e-9 {
                out.push(p);
            }
        }
        out
    };
    let mut inner = wall(-1.0);
    inner.reverse();
    let mut walls = vec![wall(1.0), inner];
    for k in 0..6 {
        let c = centre[k * m / 6 + 37];
        let (x, y) = ((c[0] / 0.05).round() * 0.05, (c[1] / 0.05).round() * 0.05);
        walls.push(vec![
            [x, y],
            [x + 0.2, y],
            [x + 0.2, y + 0.15],
            [x, y + 0.15],
        ]);
    }
    let c = centre[m / 3];
    walls.push(vec![[c[0] - 0.4, c[1] + 0.3], [c[0] + 0.3, c[1] + 0.5]]);
    (walls, centre)
}

/// Half width of [`raster_circuit`] at centreline point `i` of `m` (0.8 to 1.9 m).
fn circuit_half_width(i: usize, m: usize) -> f64 {
    let a = i as f64 / m as f64 * TAU;
    1.1 + 0.5 * (3.0 * a).sin().abs() + 0.3 * (11.0 * a).cos()
}

#[test]
fn raster_circuit_is_map_like() {
    let (walls, _) = raster_circuit();
    let grid = SegmentGrid::new(&walls);
    let lens: Vec<f64> = grid.segments().iter().map(|s| s[2].hypot(s[3])).collect();
    let mean = lens.iter().sum::<f64>() / lens.len() as f64;
    assert!(
        (1500..6000).contains(&grid.num_segments()),
        "{}",
        grid.num_segments()
    );
    assert!((0.1..0.6).contains(&mean), "{mean}");
    assert!(lens.iter().any(|&l| l < 0.06) && lens.iter().any(|&l| l > 0.5));
}

#[test]
fn segment_scan_equals_the_grid_walk_on_a_raster_circuit() {
    // Poses all around the lap: on the centreline, near either wall (the sensor within
    // a few cm of it) and next to the obstacles, headings along, across and against the
    // lap; the fans of the env (270 degrees, 1080 and 1081 beams) and a full turn.
    let (walls, centre) = raster_circuit();
    let grid = SegmentGrid::new(&walls);
    let mut rng = 0x2545_f491_4f6c_dd1du64;
    let mut unit = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut hits = 0;
    for (i, k) in (0..centre.len()).step_by(9).enumerate() {
        let (p, q) = (centre[k], centre[(k + 1) % centre.len()]);
        let heading = (q[1] - p[1]).atan2(q[0] - p[0]);
        let (nx, ny) = (-heading.sin(), heading.cos());
        // (Snapping moves a wall by up to 0.035 m: 0.95 of the half width is 0.04 to
        // 0.13 m from it, 0.99 within a few cm or just beyond.)
        let frac = [0.0, 0.5, -0.5, 0.95, -0.95, 0.99, -0.99][i % 7];
        let off = (frac + 0.01 * (unit() - 0.5)) * circuit_half_width(k, centre.len());
        let yaw = heading + [0.0, 0.3, -0.3, 1.6, PI, -2.0][i % 6] + 0.05 * unit();
        let (ox, oy) = (p[0] + off * nx, p[1] + off * ny);
        let (fov, n) = [(4.712389, 1081), (4.712389, 1080), (TAU, 720)][i % 3];
        hits += check_against_walk(&grid, ox, oy, yaw, fov, n);
    }
    assert!(hits > 200_000, "{hits}");
}

#[test]
fn split_scan_equals_the_single_scan_on_a_raster_circuit() {
    use crate::sim::lidar::{ScanNoise, Scanner, SPLIT_MIN_BEAMS};
    use crate::sim::LidarParams;
    use rand_chacha::rand_core::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    let (walls, centre) = raster_circuit();
    let grid = SegmentGrid::new(&walls);
    for num_beams in [SPLIT_MIN_BEAMS, SPLIT_MIN_BEAMS + 1] {
        let one = Scanner::new(&LidarParams {
            num_beams,
            ..Default::default()
        });
        let mut two = one.clone();
        two.split = true;
        for k in (0..centre.len()).step_by(97) {
            let pose = [centre[k][0], centre[k][1], k as f64 * 0.37];
            let (mut a, mut b) = (vec![0.0f32; num_beams], vec![0.0f32; num_beams]);
            let mut rng = ChaCha8Rng::seed_from_u64(3);
            one.scan(pose, &grid, &[], ScanNoise::default(), &mut rng, &mut a);
            let mut rng = ChaCha8Rng::seed_from_u64(3);
            two.scan(pose, &grid, &[], ScanNoise::default(), &mut rng, &mut b);
            let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&a), bits(&b), "pose {pose:?}");
        }
    }
}

#[test]
fn segment_scan_equals_the_grid_walk_next_to_wall_vertices() {
    // The sensor 1 mm, 10 µm and 1 µm from wall vertices of the raster circuit (within
    // 1e-6 of the longest segment the scan widens its angular intervals), looking
    // along, across and into the wall.
    let (walls, _) = raster_circuit();
    let grid = SegmentGrid::new(&walls);
    let mut hits = 0;
    for (i, v) in walls[0].iter().chain(&walls[1]).step_by(53).enumerate() {
        let a = i as f64 * 2.4;
        let r = [1e-3, 1e-5, 1e-6][i % 3];
        let (ox, oy) = (v[0] + r * a.cos(), v[1] + r * a.sin());
        hits += check_against_walk(&grid, ox, oy, a + 0.5 * i as f64, 4.712389, 1081);
    }
    assert!(hits > 20_000, "{hits}");
}
