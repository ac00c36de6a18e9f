//! Angular-sweep scan ("z-buffer" over beams): instead of walking each beam through the
//! segment grid, walk each wall segment the scanner may see once and update only the beams
//! whose directions it spans. A segment's beam range comes from a fast arctangent (error
//! < 2e-5 rad) widened by one beam on each side, so it is conservative; every (segment,
//! beam) pair in range is then intersected exactly with the same arithmetic as the grid
//! walk's `ray_segment`, so both methods return the same minimum, bit for bit.
//!
//! Culling (so a scan scales with what the scanner can see, not with the map): segments
//! are also bucketed in coarse square blocks ([`BlockIndex`]). A scan visits the non-empty
//! blocks within range, nearest first, and skips a block when every beam it spans already
//! has a hit nearer than the block (hidden behind nearer walls) or when it lies outside
//! the field of view. A segment in several blocks is processed once (a bitset).
//!
//! Cost: O(blocks within range + visible segments + their beam crossings) per scan.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use super::segments::SegmentGrid;

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

/// The beams of one scan: world angle of beam 0 (wrapped to [0, 2 pi)), increment,
/// angular span and the widening of every angular interval.
struct Beams {
    theta0: f64,
    inc: f64,
    inv: f64,
    span: f64,
    margin: f64,
    n: usize,
}

impl Beams {
    /// Beams k0..=k1 whose angles (from beam 0) fall in [l, h], or None.
    #[inline(always)]
    fn span(&self, l: f64, h: f64) -> Option<(usize, usize)> {
        if h < 0.0 || l > self.span {
            return None;
        }
        if self.inc <= 0.0 {
            return Some((0, 0));
        }
        // (±1e-6 beams: span * inv may round just below n - 1.)
        // (Non-negative, so truncation is floor; no libm floor/ceil calls.)
        let k0 = ceil_nonneg(l.max(0.0) * self.inv - 1e-6);
        let k1 = ((h.min(self.span) * self.inv + 1e-6) as usize).min(self.n - 1);
        (k0 <= k1).then_some((k0, k1))
    }

    /// Widened angular interval (from beam 0) swept counter-clockwise from the world
    /// angle `ap` to `aq` (each in [-pi, pi]).
    #[inline(always)]
    fn interval(&self, ap: f64, aq: f64) -> (f64, f64) {
        let start = wrap_tau(ap - self.theta0);
        let len = wrap_tau(aq - ap);
        (start - self.margin, start + len + self.margin)
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
    if n == 0 || !(ox.is_finite() && oy.is_finite() && rmax > 0.0) {
        return;
    }
    let beams = Beams {
        theta0: theta0.rem_euclid(TAU),
        inc,
        inv: if inc > 0.0 { 1.0 / inc } else { 0.0 },
        span: inc * (n - 1) as f64,
        margin: inc.max(1e-4) + 1e-4,
        n,
    };
    let segs = grid.segments();
    let blocks = grid.blocks();
    let mut near = Vec::with_capacity(128);
    blocks.near(ox, oy, rmax, &mut near);
    let mut seen = vec![0u64; segs.len().div_ceil(64)];
    let r2 = rmax * rmax;
    // Nearest blocks first, so that beams are covered early: farther blocks then turn
    // out hidden, and occluded (segment, beam) pairs fail the cheap `dmin >= range` test.
    // The order cannot change the result: each range is a minimum.
    for &(d, b) in &near {
        let b = b as usize;
        if d > 0.0 && !block_visible(&blocks.corners(b), ox, oy, d, &beams, ranges) {
            continue;
        }
        for &i in blocks.segments(b) {
            let (w, bit) = (i as usize / 64, 1u64 << (i % 64));
            if seen[w] & bit == 0 {
                seen[w] |= bit;
                sweep_segment(&segs[i as usize], ox, oy, r2, &beams, dirs, ranges);
            }
        }
    }
}

/// Whether a block (corners `c`, at distance `d` > 0 from the sensor, which is outside
/// it) can still lower some beam: a beam it spans has no hit nearer than `d` yet.
fn block_visible(
    c: &[[f64; 2]; 4],
    ox: f64,
    oy: f64,
    d: f64,
    beams: &Beams,
    ranges: &[f64],
) -> bool {
    let (cx, cy) = (
        0.5 * (c[0][0] + c[3][0]) - ox,
        0.5 * (c[0][1] + c[3][1]) - oy,
    );
    let ac = fast_atan2(cy, cx);
    // Outside the box the corners span less than pi, so offsets from the centre's angle
    // wrapped to (-pi, pi] order them.
    let (mut lo, mut hi) = (0.0f64, 0.0f64);
    for p in c {
        let a = wrap_pi(fast_atan2(p[1] - oy, p[0] - ox) - ac);
        lo = lo.min(a);
        hi = hi.max(a);
    }
    let (l, h) = beams.interval(wrap_pi(ac + lo), wrap_pi(ac + hi));
    [-TAU, 0.0, TAU].iter().any(|sh| {
        beams
            .span(l + sh, h + sh)
            .is_some_and(|(k0, k1)| ranges[k0..=k1].iter().any(|&r| r > d))
    })
}

/// Lower the ranges of the beams segment `s` spans to its exact hits.
#[inline]
fn sweep_segment(
    s: &[f64; 4],
    ox: f64,
    oy: f64,
    r2: f64,
    beams: &Beams,
    dirs: &[[f64; 2]],
    ranges: &mut [f64],
) {
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
        return;
    }
    // Angular interval swept counter-clockwise from p to q as seen from the sensor.
    let (aa, ab) = (fast_atan2(ay, ax), fast_atan2(by, bx));
    let (ap, aq) = if ax * by - ay * bx >= 0.0 {
        (aa, ab)
    } else {
        (ab, aa)
    };
    let (lo, hi) = beams.interval(ap, aq);
    // No hit on this segment is nearer than its closest point (slack for rounding).
    let dmin = d2.sqrt() * (1.0 - 1e-9);
    for shift in [-TAU, 0.0, TAU] {
        let Some((k0, k1)) = beams.span(lo + shift, hi + shift) else {
            continue;
        };
        for k in k0..=k1 {
            if dmin >= ranges[k] {
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

/// `x` wrapped into (-pi, pi] for |x| < 3 pi.
#[inline(always)]
fn wrap_pi(x: f64) -> f64 {
    if x > PI {
        x - TAU
    } else if x <= -PI {
        x + TAU
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::shapes::stadium_track;

    /// Sweep one scan of `n` beams over `fov` from `(ox, oy)` heading `yaw` and check
    /// every beam against the per-beam grid walk, bit for bit; returns the number of hits.
    fn check_against_walk(
        grid: &SegmentGrid,
        ox: f64,
        oy: f64,
        yaw: f64,
        fov: f64,
        n: usize,
    ) -> usize {
        let inc = fov / (n - 1) as f64;
        let theta0 = yaw - fov / 2.0;
        let dirs: Vec<[f64; 2]> = (0..n)
            .map(|k| {
                let a = theta0 + k as f64 * inc;
                [a.cos(), a.sin()]
            })
            .collect();
        let mut ranges = vec![f64::INFINITY; n];
        sweep(grid, ox, oy, theta0, inc, &dirs, 30.0, &mut ranges);
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
    fn sweep_equals_the_grid_walk_bit_for_bit() {
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
    fn culled_sweep_equals_the_grid_walk_on_a_large_map() {
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
}
