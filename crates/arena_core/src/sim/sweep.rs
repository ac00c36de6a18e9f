//! Angular-sweep scan ("z-buffer" over beams): instead of walking each beam through the
//! segment grid, walk each wall segment once and update only the beams whose directions
//! it spans. A segment's beam range comes from a fast arctangent (error < 2e-5 rad)
//! widened by one beam on each side, so it is conservative; every (segment, beam) pair
//! in range is then intersected exactly with the same arithmetic as the grid walk's
//! `ray_segment`,
//! so both methods return the same minimum, bit for bit.
//!
//! Cost: O(segments + beam-segment crossings within range) per scan, independent of the
//! grid; best when segments are few relative to beams (see `Scanner::scan`).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use super::lidar::SegmentGrid;

/// atan2 with |error| < 2e-5 rad (Abramowitz & Stegun 4.4.49 on [0, 1], folded).
#[inline(always)]
pub fn fast_atan2(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    let (mn, mx) = if ax < ay { (ax, ay) } else { (ay, ax) };
    if mx == 0.0 {
        return 0.0;
    }
    let a = mn / mx;
    let s = a * a;
    let mut r =
        a * (0.999_866 + s * (-0.330_299_5 + s * (0.180_141 + s * (-0.085_133 + s * 0.020_835_1))));
    if ay > ax {
        r = FRAC_PI_2 - r;
    }
    if x < 0.0 {
        r = PI - r;
    }
    if y < 0.0 {
        -r
    } else {
        r
    }
}

/// Lower `ranges[k]` to the nearest wall hit of beam k, for beams at world angles
/// `theta0 + k inc` with unit directions `dirs[k]`, from `(ox, oy)`, within `rmax`.
#[allow(clippy::too_many_arguments)]
pub fn sweep(
    grid: &SegmentGrid,
    ox: f64,
    oy: f64,
    theta0: f64,
    inc: f64,
    dirs: &[[f64; 2]],
    rmax: f64,
    ranges: &mut [f64],
) {
    let n = dirs.len();
    if n == 0 {
        return;
    }
    let span = inc * (n - 1) as f64;
    let margin = inc.max(1e-4) + 1e-4;
    let inv = if inc > 0.0 { 1.0 / inc } else { 0.0 };
    let r2 = rmax * rmax;
    let theta0 = theta0.rem_euclid(TAU);
    // Pass 1: segments within range and the field of view, with their nearest distance
    // and angular interval.
    let segs = grid.segments();
    // One arctangent per polyline vertex (shared by its two segments), as seen from the
    // sensor; only used for the conservative beam ranges.
    let (verts, seg_verts) = grid.vertices();
    let angles: Vec<f64> = verts
        .iter()
        .map(|v| fast_atan2(v[1] - oy, v[0] - ox))
        .collect();
    let mut cands: Vec<Candidate> = Vec::with_capacity(segs.len());
    for (i, s) in segs.iter().enumerate() {
        let (ax, ay) = (s[0] - ox, s[1] - oy);
        let (bx, by) = (ax + s[2], ay + s[3]);
        // Skip segments entirely beyond range.
        let l2 = s[2] * s[2] + s[3] * s[3];
        let t = if l2 > 0.0 {
            (-(ax * s[2] + ay * s[3]) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (cx, cy) = (ax + t * s[2], ay + t * s[3]);
        let d2 = cx * cx + cy * cy;
        if d2 > r2 {
            continue;
        }
        // Angular interval swept counter-clockwise from p to q as seen from the origin.
        let [va, vb] = seg_verts[i];
        let (aa, ab) = (angles[va as usize], angles[vb as usize]);
        let (ap, aq) = if ax * by - ay * bx >= 0.0 {
            (aa, ab)
        } else {
            (ab, aa)
        };
        let start = wrap_tau(ap - theta0);
        let len = wrap_tau(aq - ap);
        let (lo, hi) = (start - margin, start + len + margin);
        if [-TAU, 0.0, TAU]
            .iter()
            .all(|sh| hi + sh < 0.0 || lo + sh > span)
        {
            continue; // outside the field of view
        }
        // No hit on this segment is nearer than its closest point (slack for rounding).
        cands.push(Candidate {
            dmin: d2.sqrt() * (1.0 - 1e-9),
            lo,
            hi,
            seg: i as u32,
        });
    }
    // Near segments first (counting sort on distance buckets), so that beams are covered
    // early and occluded (segment, beam) pairs fail the cheap `dmin >= range` test. The
    // order cannot change the result: each range is a minimum.
    const BUCKETS: usize = 32;
    let bucket = |d: f64| ((d / rmax * BUCKETS as f64) as usize).min(BUCKETS - 1);
    let mut first = [0usize; BUCKETS + 1];
    for c in &cands {
        first[bucket(c.dmin) + 1] += 1;
    }
    for b in 0..BUCKETS {
        first[b + 1] += first[b];
    }
    let mut order = vec![0u32; cands.len()];
    for (i, c) in cands.iter().enumerate() {
        let b = bucket(c.dmin);
        order[first[b]] = i as u32;
        first[b] += 1;
    }
    // Pass 2: exact intersections of each candidate with the beams it spans.
    for &i in &order {
        let c = &cands[i as usize];
        let s = &segs[c.seg as usize];
        let (ax, ay) = (s[0] - ox, s[1] - oy);
        for shift in [-TAU, 0.0, TAU] {
            let (l, h) = (c.lo + shift, c.hi + shift);
            if h < 0.0 || l > span {
                continue;
            }
            // (±1e-6 beams: span * inv may round just below n - 1.)
            // (Non-negative, so truncation is floor; no libm floor/ceil calls.)
            let k0 = if inc > 0.0 {
                ceil_nonneg(l.max(0.0) * inv - 1e-6)
            } else {
                0
            };
            let k1 = if inc > 0.0 {
                ((h.min(span) * inv + 1e-6) as usize).min(n - 1)
            } else {
                0
            };
            for k in k0..=k1 {
                if c.dmin >= ranges[k] {
                    continue; // occluded: a nearer wall already covers this beam
                }
                let d = dirs[k];
                // Same arithmetic as `ray_segment` (so the same bits), but the division
                // is only done for a hit that can lower the range (1e-12 slack keeps
                // the pre-test conservative under rounding).
                let den = d[0] * s[3] - d[1] * s[2];
                let sign = if den < 0.0 { -1.0 } else { 1.0 };
                let ad = den * sign;
                let tn = (ax * s[3] - ay * s[2]) * sign;
                let un = (ax * d[1] - ay * d[0]) * sign;
                let ok = (ad > 1e-14) & (tn >= 0.0) & (un >= 0.0) & (un <= ad);
                if ok && tn <= ranges[k] * ad * (1.0 + 1e-12) {
                    ranges[k] = ranges[k].min(tn / ad);
                }
            }
        }
    }
}

/// `x` wrapped into [0, 2 pi) for |x| < 4 pi (all this module passes), without fmod.
#[inline(always)]
fn wrap_tau(x: f64) -> f64 {
    let x = if x < 0.0 { x + TAU } else { x };
    let x = if x < 0.0 { x + TAU } else { x };
    let x = if x >= TAU { x - TAU } else { x };
    if x >= TAU {
        x - TAU
    } else {
        x
    }
}

/// Ceiling of a value >= -1 as usize (negative values give 0).
#[inline(always)]
fn ceil_nonneg(x: f64) -> usize {
    if x <= 0.0 {
        return 0;
    }
    let t = x as usize;
    t + ((t as f64) < x) as usize
}

/// A segment that may be seen: nearest distance, angular interval (rad from beam 0,
/// widened), index.
struct Candidate {
    dmin: f64,
    lo: f64,
    hi: f64,
    seg: u32,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::shapes::stadium_track;

    #[test]
    fn sweep_equals_the_grid_walk_bit_for_bit() {
        let (mut walls, _) = stadium_track(18.0, 9.0, 2.0);
        walls.push(vec![[1.0, -9.5], [1.3, -9.2], [1.0, -8.9]]); // a small obstacle
        let grid = SegmentGrid::new(&walls);
        for (ox, oy, yaw, fov, n) in [
            (0.0, -9.0, 0.3, 4.712389, 1081),
            (-12.0, 3.0, 2.0, TAU, 720),
            (5.0, 9.2, -1.0, 1.0, 3),
        ] {
            let inc = fov / (n - 1) as f64;
            let theta0 = yaw - fov / 2.0;
            let dirs: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let a = theta0 + k as f64 * inc;
                    [a.cos(), a.sin()]
                })
                .collect();
            let mut ranges = vec![f64::INFINITY; n];
            sweep(&grid, ox, oy, theta0, inc, &dirs, 30.0, &mut ranges);
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
                    "beam {k}: {walk} vs {swept}"
                );
            }
        }
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
}
