//! Simplification, smoothing and resampling of closed polylines (no repeated end point).

use super::dist;
// Resampling lives with the other polyline measures; kept reachable here for callers.
pub use super::polyline::resample_closed;

/// Distance from `p` to the segment `a`–`b`.
fn seg_dist(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    if l2 == 0.0 {
        return dist(p, a);
    }
    let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0);
    dist(p, [a[0] + t * dx, a[1] + t * dy])
}

/// Douglas–Peucker on a closed polyline: every removed point lies within `tol` of the
/// simplified loop. Anchored at point 0 and the point farthest from it; iterative.
pub fn simplify_closed(p: &[[f64; 2]], tol: f64) -> Vec<[f64; 2]> {
    let n = p.len();
    if n <= 4 || tol <= 0.0 {
        return p.to_vec();
    }
    let far = (1..n)
        .max_by(|&a, &b| dist(p[0], p[a]).total_cmp(&dist(p[0], p[b])))
        .unwrap();
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[far] = true;
    // Index n stands for point 0 again (closing the loop).
    let at = |i: usize| p[i % n];
    let mut stack = vec![(0usize, far), (far, n)];
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let (mut worst, mut wi) = (-1.0, a);
        for i in a + 1..b {
            let d = seg_dist(at(i), at(a), at(b));
            if d > worst {
                worst = d;
                wi = i;
            }
        }
        if worst > tol {
            keep[wi % n] = true;
            stack.push((a, wi));
            stack.push((wi, b));
        }
    }
    let out: Vec<[f64; 2]> = (0..n).filter(|&i| keep[i]).map(|i| p[i]).collect();
    if out.len() < 3 {
        p.to_vec()
    } else {
        out
    }
}

/// Taubin smoothing (λ = 0.5, μ = −0.53) of a closed polyline: removes the staircase of
/// a raster contour without the shrinkage of plain Laplacian smoothing.
pub fn smooth_closed(p: &[[f64; 2]], iterations: usize) -> Vec<[f64; 2]> {
    let n = p.len();
    if n < 3 {
        return p.to_vec();
    }
    let mut cur = p.to_vec();
    let mut tmp = cur.clone();
    for _ in 0..iterations {
        for factor in [0.5, -0.53] {
            for i in 0..n {
                let (a, b, c) = (cur[(i + n - 1) % n], cur[i], cur[(i + 1) % n]);
                tmp[i] = [
                    b[0] + factor * ((a[0] + c[0]) / 2.0 - b[0]),
                    b[1] + factor * ((a[1] + c[1]) / 2.0 - b[1]),
                ];
            }
            std::mem::swap(&mut cur, &mut tmp);
        }
    }
    cur
}

/// Largest distance from any point of `fine` to the closed polyline `coarse` (for
/// checking simplification). Quadratic; meant for tests and small inputs.
pub fn hausdorff_to_closed(fine: &[[f64; 2]], coarse: &[[f64; 2]]) -> f64 {
    let m = coarse.len();
    fine.iter()
        .map(|&q| {
            (0..m)
                .map(|i| seg_dist(q, coarse[i], coarse[(i + 1) % m]))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{polyline_length, signed_area};
    use proptest::prelude::*;
    use std::f64::consts::PI;

    fn circle(n: usize, r: f64) -> Vec<[f64; 2]> {
        crate::geometry::test_circle(n, r)
    }

    #[test]
    fn square_with_collinear_points_simplifies_to_corners() {
        let mut sq = Vec::new();
        for i in 0..10 {
            sq.push([i as f64, 0.0]);
        }
        for i in 0..10 {
            sq.push([10.0, i as f64]);
        }
        for i in 0..10 {
            sq.push([10.0 - i as f64, 10.0]);
        }
        for i in 0..10 {
            sq.push([0.0, 10.0 - i as f64]);
        }
        let s = simplify_closed(&sq, 0.01);
        assert_eq!(s.len(), 4);
        assert_eq!(signed_area(&s), 100.0);
    }

    #[test]
    fn smoothing_keeps_a_circle_round_and_resampling_is_even() {
        let c = circle(400, 10.0);
        let s = smooth_closed(&c, 10);
        assert!((polyline_length(&s, true) - polyline_length(&c, true)).abs() < 0.01);
        let r = resample_closed(&c, 0.5);
        assert_eq!(r.len(), (2.0 * PI * 10.0 / 0.5).round() as usize);
        let gaps: Vec<f64> = (0..r.len())
            .map(|i| dist(r[i], r[(i + 1) % r.len()]))
            .collect();
        let (lo, hi) = gaps
            .iter()
            .fold((f64::MAX, 0.0f64), |(a, b), &g| (a.min(g), b.max(g)));
        assert!(hi - lo < 1e-3, "{lo} {hi}");
    }

    proptest! {
        #[test]
        fn simplification_stays_within_tolerance(n in 5usize..200, tol in 0.01f64..0.5, wobble in 0.0f64..0.3) {
            let p: Vec<[f64; 2]> = (0..n).map(|i| {
                let a = 2.0 * PI * i as f64 / n as f64;
                let r = 5.0 + wobble * (7.0 * a).sin();
                [r * a.cos(), r * a.sin()]
            }).collect();
            let s = simplify_closed(&p, tol);
            prop_assert!(s.len() >= 3 && s.len() <= n);
            prop_assert!(hausdorff_to_closed(&p, &s) <= tol + 1e-9);
        }
    }
}
