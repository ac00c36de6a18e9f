use super::*;
use crate::geometry::test_circle;
use proptest::prelude::*;
use std::f64::consts::PI;

/// The O(n²) definition the grid must agree with.
fn brute_force_crossings(p: &[[f64; 2]]) -> Vec<Crossing> {
    let n = p.len();
    let mut out = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            if adjacent(i, j, n) {
                continue;
            }
            if let Some(point) = segment_crossing(p, i, j) {
                out.push(Crossing { i, j, point });
            }
        }
    }
    out
}

/// A figure eight (lemniscate of Gerono, scaled): one crossing at the origin.
fn figure_eight(n: usize, a: f64) -> Vec<[f64; 2]> {
    (0..n)
        .map(|k| {
            let t = 2.0 * PI * (k as f64 + 0.5) / n as f64;
            [a * t.sin(), a * t.sin() * t.cos()]
        })
        .collect()
}

#[test]
fn square_length_arclength_and_orientation() {
    let sq = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    assert_eq!(polyline_length(&sq, true), 4.0);
    assert_eq!(polyline_length(&sq, false), 3.0);
    assert_eq!(cumulative_length(&sq, true), vec![0.0, 1.0, 2.0, 3.0, 4.0]);
    assert_eq!(cumulative_length(&sq, false), vec![0.0, 1.0, 2.0, 3.0]);
    assert!(cumulative_length(&[], true).is_empty());
    assert_eq!(cumulative_length(&[[1.0, 2.0]], true), vec![0.0, 0.0]);
    assert_eq!(signed_area(&sq), 1.0);
    let cw: Vec<_> = sq.iter().rev().copied().collect();
    assert_eq!(signed_area(&cw), -1.0);
}

#[test]
fn resampling_carries_values_linearly_in_arc_length() {
    // 4 m square, value = 0 at (0,0), 1 at (1,0), 2 at (1,1), 3 at (0,1).
    let sq = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let (pts, v) = resample_closed_values(&sq, &[0.0, 1.0, 2.0, 3.0], 0.5);
    assert_eq!(pts.len(), 8);
    assert_eq!(pts, resample_closed(&sq, 0.5));
    assert_eq!(pts[1], [0.5, 0.0]);
    assert_eq!(pts[3], [1.0, 0.5]);
    // Back towards point 0 on the closing edge: 3 → 0.
    assert_eq!(v, vec![0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 1.5]);
    // An unwrapped value (here the arc length itself) runs on to its closing value.
    let (_, s) = resample_closed_values(&sq, &[0.0, 1.0, 2.0, 3.0, 4.0], 0.5);
    assert_eq!(s, vec![0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5]);
    // Degenerate spacing or loops come back unchanged.
    assert_eq!(resample_closed(&sq, 0.0), sq);
    assert_eq!(resample_closed(&[[1.0, 1.0]; 5], 0.1), vec![[1.0, 1.0]; 5]);
    // Never fewer than a triangle.
    assert_eq!(resample_closed(&sq, 100.0).len(), MIN_RESAMPLED);
}

#[test]
fn curvature_is_signed_inverse_radius_on_circles() {
    let c = test_circle(720, 2.5); // counter-clockwise: left turns, κ > 0
    for span in [0.05, 0.5, 2.0] {
        let k = curvature_closed(&c, span);
        assert!(k.iter().all(|&k| (k - 0.4).abs() < 1e-9), "{span}: {k:?}");
        assert!((min_radius_closed(&c, span) - 2.5).abs() < 1e-9);
    }
    let cw: Vec<_> = c.iter().rev().copied().collect();
    assert!(curvature_closed(&cw, 0.5)
        .iter()
        .all(|&k| (k + 0.4).abs() < 1e-9));
    // A long straight has no bend except at its ends; a degenerate loop none at all.
    assert_eq!(min_radius_closed(&[[0.0, 0.0]; 4], 0.5), f64::INFINITY);
}

#[test]
fn min_radius_finds_the_tight_end_of_a_stadium() {
    // Straights joined by a 1 m and a 3 m semicircle, sampled every ~5 cm.
    let mut p = Vec::new();
    for i in 0..63 {
        let a = -PI / 2.0 + PI * i as f64 / 63.0;
        p.push([1.0 * a.cos() + 10.0, 2.0 + 1.0 * a.sin()]);
    }
    for i in 0..189 {
        let a = PI / 2.0 + PI * i as f64 / 189.0;
        p.push([3.0 * a.cos(), 0.0 + 3.0 * a.sin()]);
    }
    let p = resample_closed(&p, 0.05);
    let r = min_radius_closed(&p, 0.5);
    assert!((r - 1.0).abs() < 0.02, "{r}");
}

#[test]
fn figure_eight_crosses_once_at_the_origin() {
    let p = figure_eight(1000, 5.0);
    let x = self_intersections_closed(&p).unwrap();
    assert_eq!(x.len(), 1, "{x:?}");
    assert!(x[0].point[0].abs() < 1e-3 && x[0].point[1].abs() < 1e-3);
    assert_eq!((x[0].i, x[0].j), (499, 999));
    assert!(self_intersections_closed(&test_circle(1000, 5.0))
        .unwrap()
        .is_empty());
    // Too few points or no length: nothing to cross.
    assert!(self_intersections_closed(&[[0.0, 0.0]; 10])
        .unwrap()
        .is_empty());
}

#[test]
fn a_crossing_through_a_vertex_counts_once() {
    // A bow tie whose crossing is exactly at vertex 2 / the middle of segment 4.
    let p = vec![
        [0.0, 0.0],
        [1.0, 1.0],
        [2.0, 0.0],
        [3.0, -1.0],
        [3.0, 1.0],
        [2.0, 2.0],
        [1.0, -1.0],
    ];
    let x = self_intersections_closed(&p).unwrap();
    assert_eq!(x, brute_force_crossings(&p));
    assert!(!x.is_empty());
}

#[test]
fn long_closing_segment_is_found() {
    // A random baseline's loop closed by one long chord across the whole curve.
    let mut p: Vec<[f64; 2]> = (0..2000)
        .map(|i| {
            let t = i as f64 / 2000.0 * 3.0 * PI;
            [t.cos() * (5.0 + t), t.sin() * (5.0 + t)]
        })
        .collect();
    p.push([-50.0, 0.0]);
    assert_eq!(
        self_intersections_closed(&p).unwrap(),
        brute_force_crossings(&p)
    );
    assert!(!self_intersections_closed(&p).unwrap().is_empty());
}

#[test]
fn a_loop_folded_onto_itself_is_refused_not_ground_through() {
    // 4000 passes back and forth over the same 1 m: every segment shares every cell.
    let p: Vec<[f64; 2]> = (0..16_000)
        .map(|i| {
            [
                if (i / 4) % 2 == 0 {
                    (i % 4) as f64 / 4.0
                } else {
                    1.0 - (i % 4) as f64 / 4.0
                },
                0.0,
            ]
        })
        .collect();
    let e = self_intersections_closed(&p).unwrap_err().to_string();
    assert!(e.contains("folded onto itself"), "{e}");
}

#[test]
fn doors_refuse_bad_polylines() {
    let ok = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
    assert_eq!(check_points(&ok, 3, true, "xy").unwrap(), 3);
    let mut repeated = ok.clone();
    repeated.push(ok[0]);
    assert_eq!(check_points(&repeated, 3, true, "xy").unwrap(), 3);
    assert_eq!(check_points(&repeated, 2, false, "xy").unwrap(), 4);
    let e = check_points(&ok[..2], 3, true, "xy")
        .unwrap_err()
        .to_string();
    assert!(e.contains("at least 3 points, got 2"), "{e}");
    let e = check_points(&[[0.0, 0.0], [f64::NAN, 1.0], [2.0, 2.0]], 3, true, "xy")
        .unwrap_err()
        .to_string();
    assert!(e.contains("point 1 must be finite"), "{e}");
    assert!(check_spacing(0.1, 10.0).is_ok());
    for s in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-12] {
        assert!(check_spacing(s, 1000.0).is_err(), "{s}");
    }
    assert!(check_span(0.5).is_ok());
    for s in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(check_span(s).is_err(), "{s}");
    }
}

fn wobbly_loop(n: usize, wobble: f64, lobes: f64) -> Vec<[f64; 2]> {
    (0..n)
        .map(|i| {
            let a = 2.0 * PI * i as f64 / n as f64;
            let r = 5.0 + wobble * (lobes * a).sin();
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

proptest! {
    #[test]
    fn grid_crossings_equal_brute_force(
        pts in prop::collection::vec((-10.0f64..10.0, -10.0f64..10.0), 4..60),
    ) {
        let p: Vec<[f64; 2]> = pts.into_iter().map(|(x, y)| [x, y]).collect();
        prop_assert_eq!(self_intersections_closed(&p).unwrap(), brute_force_crossings(&p));
    }

    #[test]
    fn grid_crossings_equal_brute_force_on_wavy_loops(
        n in 20usize..400, wobble in 0.0f64..8.0, lobes in 2.0f64..9.0,
    ) {
        // Large wobbles fold the loop over itself: many crossings, all found.
        let p = wobbly_loop(n, wobble, lobes.round());
        prop_assert_eq!(self_intersections_closed(&p).unwrap(), brute_force_crossings(&p));
    }

    #[test]
    fn resampling_keeps_length_start_and_even_spacing(
        n in 5usize..300, wobble in 0.0f64..2.0, frac in 0.2f64..1.0,
    ) {
        let p = wobbly_loop(n, wobble, 5.0);
        // Spacing at most the shortest edge, so each chord cuts at most one vertex: a chord
        // of arc length s across a turn of θ is at least s cos(θ/2), which bounds the loss.
        let edge = |i: usize| {
            let (a, b) = (p[i], p[(i + 1) % p.len()]);
            ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()
        };
        let shortest = (0..p.len()).map(edge).fold(f64::INFINITY, f64::min);
        let spacing = frac * shortest;
        let max_turn = (0..p.len())
            .map(|i| {
                let (a, b, c) = (p[(i + p.len() - 1) % p.len()], p[i], p[(i + 1) % p.len()]);
                let (h0, h1) = ((b[1] - a[1]).atan2(b[0] - a[0]), (c[1] - b[1]).atan2(c[0] - b[0]));
                let d = (h1 - h0).rem_euclid(std::f64::consts::TAU);
                d.min(std::f64::consts::TAU - d)
            })
            .fold(0.0, f64::max);
        let r = resample_closed(&p, spacing);
        let (l0, l1) = (polyline_length(&p, true), polyline_length(&r, true));
        prop_assert_eq!(r[0], p[0]);
        let floor = l0 * (max_turn / 2.0).cos().min(0.999) - 1e-9;
        prop_assert!(l1 <= l0 + 1e-9 && l1 >= floor, "{} {} (floor {})", l0, l1, floor);
        let m = ((l0 / spacing).round() as usize).max(MIN_RESAMPLED);
        prop_assert_eq!(r.len(), m);
        // Every resampled point lies on the input loop.
        prop_assert!(crate::geometry::smooth::hausdorff_to_closed(&r, &p) < 1e-9);
    }

    #[test]
    fn curvature_flips_sign_with_direction_and_scales_inversely(
        n in 50usize..300, wobble in 0.0f64..1.0, scale in 0.2f64..5.0,
    ) {
        let p = wobbly_loop(n, wobble, 3.0);
        let k = curvature_closed(&p, 0.5);
        let big: Vec<[f64; 2]> = p.iter().map(|q| [q[0] * scale, q[1] * scale]).collect();
        let kb = curvature_closed(&big, 0.5 * scale);
        for (a, b) in k.iter().zip(&kb) {
            prop_assert!((a - b * scale).abs() < 1e-9 * (1.0 + a.abs()));
        }
        let rev: Vec<[f64; 2]> = p.iter().rev().copied().collect();
        let kr = curvature_closed(&rev, 0.5);
        for i in 0..n {
            prop_assert!((k[i] + kr[n - 1 - i]).abs() < 1e-9 * (1.0 + k[i].abs()));
        }
        prop_assert!(min_radius_closed(&p, 0.5) > 0.0);
    }
}
