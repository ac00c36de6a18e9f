//! Segment scan, the lidar scan by angular order ("z-buffer" over beams): instead of walking each beam through the
//! segment grid, walk each wall segment the scanner may see once and update only the beams
//! whose directions it spans. A segment's beam range comes from a fast arctangent (error
//! < 2e-5 rad, one per shared wall vertex) widened by 1e-4 rad (by a beam more when the
//! sensor is very near the segment, see `Walk::segment`), so it is conservative; every
//! (segment, beam) pair in range is then intersected exactly with the same arithmetic as
//! the grid walk's `ray_segment`, so both methods return the same minimum, bit for bit.
//!
//! Culling (so a scan scales with what the scanner can see, not with the map): segments
//! are also bucketed in coarse square blocks ([`BlockIndex`]). A scan visits the non-empty
//! blocks within range, nearest first, and skips a block when every beam it spans already
//! has a hit nearer than the block (hidden behind nearer walls) or when it lies outside
//! the field of view. A segment in several blocks is processed once (a bitset).
//!
//! Cost: O(blocks within range + visible segments + their beam crossings) per scan.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use super::segments::{ray_segment, SegmentGrid};

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

/// Widening (rad) of a segment's angular interval when the sensor is not very near it.
const TIGHT_MARGIN: f64 = 1e-4;

/// The beams of one scan: world angle of beam 0 (wrapped to [0, 2 pi)), increment,
/// angular span and the widening of every angular interval.
struct Beams {
    theta0: f64,
    inc: f64,
    inv: f64,
    span: f64,
    margin: f64,
    /// Index of the last beam, n - 1.
    last: f64,
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
        // (±1e-6 beams: span * inv may round just below n - 1.) Clamped to [0, n]
        // first, so the conversions are plain truncations (no libm floor/ceil calls);
        // compares rather than f64::max/min, whose NaN handling costs instructions here
        // (a NaN only comes with NaN angles, whose beams hit nothing).
        // k0 = floor(x - 3e-6) + 1 for x = l * inv: at most ceil(x - 1e-6), one
        // truncation instead of a ceiling.
        let last = self.last;
        let f0 = l * self.inv + (1.0 - 3e-6);
        let f0 = if f0 > 0.0 { f0 } else { 0.0 };
        let k0 = (if f0 < last + 1.0 { f0 } else { last + 1.0 }) as i64 as usize;
        let h = if self.span < h { self.span } else { h };
        // (>= 1e-6: h >= 0 and inv >= 0.)
        let f1 = h * self.inv + 1e-6;
        let k1 = (if f1 < last { f1 } else { last }) as i64 as usize;
        (k0 <= k1).then_some((k0, k1))
    }

    /// Angle from beam 0 (counter-clockwise, in [0, 2 pi)) of the world angle `a` in
    /// [-pi, pi].
    #[inline(always)]
    fn angle_from_beam0(&self, a: f64) -> f64 {
        // a - theta0 is in [-3 pi, pi]: at most two turns to add.
        let x = a - self.theta0;
        let x = if x < 0.0 { x + TAU } else { x };
        if x < 0.0 {
            x + TAU
        } else {
            x
        }
    }
}

/// Lower `ranges[k]` to the nearest wall hit of beam k, for beams at world angles
/// `theta0 + k inc` with unit directions `dirs[k]`, from `(ox, oy)`, within `rmax`.
#[allow(clippy::too_many_arguments)]
pub fn segment_scan(
    grid: &SegmentGrid,
    ox: f64,
    oy: f64,
    theta0: f64,
    inc: f64,
    dirs: &[[f64; 2]],
    rmax: f64,
    ranges: &mut [f64],
) {
    let n = dirs.len().min(ranges.len());
    if n == 0 || !(ox.is_finite() && oy.is_finite() && rmax > 0.0) {
        return;
    }
    let beams = Beams {
        theta0: theta0.rem_euclid(TAU),
        inc,
        inv: if inc > 0.0 { 1.0 / inc } else { 0.0 },
        span: inc * (n - 1) as f64,
        margin: inc.max(1e-4) + 1e-4,
        last: (n - 1) as f64,
    };
    let max_len = grid.max_len();
    let blocks = grid.blocks();
    let mut near = Vec::with_capacity(128);
    blocks.near(ox, oy, rmax, &mut near);
    let mut seen = vec![0u64; grid.num_segments().div_ceil(64)];
    let mut walk = Walk {
        grid,
        ox,
        oy,
        r2: rmax * rmax,
        near2: 1e-12 * max_len * max_len,
        beams,
        dirs: &dirs[..n],
        ranges: &mut ranges[..n],
        after: usize::MAX,
        end_angle: 0.0,
    };
    // Nearest blocks first, so that beams are covered early: farther blocks then turn
    // out hidden, and occluded (segment, beam) pairs fail the cheap `dmin >= range` test.
    // The order cannot change the result: each range is a minimum.
    for &(d, b) in &near {
        let b = b as usize;
        if d > 0.0 && !block_visible(&blocks.corners(b), ox, oy, d, &walk.beams, walk.ranges) {
            continue;
        }
        for &i in blocks.segments(b) {
            let (w, bit) = (i as usize / 64, 1u64 << (i % 64));
            if seen[w] & bit == 0 {
                seen[w] |= bit;
                walk.segment(i as usize);
            }
        }
    }
}

/// The state of one segment scan: the scan, and the angle of the end point of the segment
/// swept last (segment `after - 1`), which is the start point of segment `after` when
/// that continues the same polyline: a wall's segments mostly come in index order, so
/// most end points need one arctangent instead of two.
struct Walk<'a> {
    grid: &'a SegmentGrid,
    ox: f64,
    oy: f64,
    r2: f64,
    /// Squared distance under which a segment gets the wide margin, see `segment`.
    near2: f64,
    beams: Beams,
    dirs: &'a [[f64; 2]],
    ranges: &'a mut [f64],
    after: usize,
    end_angle: f64,
}

impl Walk<'_> {
    /// Lower the ranges of the beams segment `i` spans to its exact hits.
    #[inline(always)]
    fn segment(&mut self, i: usize) {
        let s = &self.grid.segments()[i];
        let (ax, ay) = (s[0] - self.ox, s[1] - self.oy);
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
        if d2 > self.r2 {
            return;
        }
        // Angles of both end points from beam 0 (within 2e-5 rad, plus rounding; the
        // shared end point's angle was computed from the previous segment's end).
        let beams = &self.beams;
        let fa = if self.after == i && self.grid.continues_previous(i) {
            self.end_angle
        } else {
            beams.angle_from_beam0(fast_atan2(ay, ax))
        };
        let fb = beams.angle_from_beam0(fast_atan2(by, bx));
        (self.after, self.end_angle) = (i + 1, fb);
        // Angular interval swept counter-clockwise from p to q as seen from the sensor.
        let (fp, fq) = if ax * by - ay * bx >= 0.0 {
            (fa, fb)
        } else {
            (fb, fa)
        };
        let len = if fq < fp { fq - fp + TAU } else { fq - fp };
        // The margin covers the arctangent's error (< 2e-5 rad) and the rounding of the
        // hit test: a beam passes `ray_segment` only within ~3e-16 (|a| + |e|) / |b| rad
        // of the segment's exact wedge (a, b its end points from the sensor, e = b - a),
        // and the shared end point's angle was computed from the previous segment,
        // within ~1e-16 (|a'| + |e'|) / |a| rad. While the sensor is at least 1e-6 of the
        // longest segment away from this segment, both are below 1e-9 rad, and 1e-4 rad
        // covers them all; nearer, take the old, wider margin (a beam plus 1e-4).
        let m = if d2 >= self.near2 {
            TIGHT_MARGIN
        } else {
            beams.margin
        };
        let (lo, hi) = (fp - m, fp + len + m);
        // No hit on this segment is nearer than its closest point (slack for rounding).
        let dmin = d2.sqrt() * (1.0 - 1e-9);
        let hit = Hit::new(s, ax, ay);
        // `lo` >= -margin, so only an interval reaching past 2 pi wraps onto the first
        // beams (shift -2 pi), and only a full-turn fan starts before `lo` (+2 pi).
        if let Some((k0, k1)) = beams.span(lo, hi) {
            hit.lower(dmin, &self.dirs[k0..=k1], &mut self.ranges[k0..=k1]);
        }
        if hi >= TAU || lo + TAU <= beams.span {
            self.wrapped(&hit, dmin, lo, hi);
        }
    }

    /// The beams of a widened interval `lo..hi` one turn away (past 2 pi, or before 0
    /// for a full-turn fan).
    #[cold]
    fn wrapped(&mut self, hit: &Hit, dmin: f64, lo: f64, hi: f64) {
        for shift in [-TAU, TAU] {
            if let Some((k0, k1)) = self.beams.span(lo + shift, hi + shift) {
                hit.lower(dmin, &self.dirs[k0..=k1], &mut self.ranges[k0..=k1]);
            }
        }
    }
}

/// The ray–segment test of `ray_segment` with the segment's side chosen once: every hit
/// has `t = tn / den >= 0`, so the sign of `den` must be the sign of `tn`. Flipping the
/// segment (and its start) when `tn < 0` makes both positive; all flips are exact
/// negations, so each hit's `t` has the same bits as `ray_segment`'s.
struct Hit {
    /// Start point from the sensor and direction, flipped so that `tn >= 0`.
    ax: f64,
    ay: f64,
    ex: f64,
    ey: f64,
    /// `|ax * ey - ay * ex|` (t * den).
    tn: f64,
    /// Whether `tn` is zero (or NaN): then the sign of `den` is free, see `lower`.
    either: bool,
}

impl Hit {
    #[inline(always)]
    fn new(s: &[f64; 4], ax: f64, ay: f64) -> Self {
        let tn = ax * s[3] - ay * s[2];
        let g = if tn < 0.0 { -1.0 } else { 1.0 };
        Hit {
            ax: ax * g,
            ay: ay * g,
            ex: s[2] * g,
            ey: s[3] * g,
            tn: tn * g,
            either: tn == 0.0 || tn.is_nan(),
        }
    }

    /// Lower `ranges` (beams with unit directions `dirs`) to their hits, none nearer
    /// than `dmin`.
    #[inline(always)]
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    fn lower(&self, dmin: f64, dirs: &[[f64; 2]], ranges: &mut [f64]) {
        if self.either {
            return self.lower_either(dirs, ranges);
        }
        for (r, d) in ranges.iter_mut().zip(dirs) {
            if dmin >= *r {
                continue; // occluded: a nearer wall already covers this beam
            }
            // `ray_segment` with den > 0 (den < 0 would make t < 0: no hit).
            let den = d[0] * self.ey - d[1] * self.ex;
            let un = self.ax * d[1] - self.ay * d[0];
            if (den > 1e-14) & (un >= 0.0) & (un <= den) {
                // No pre-test: a hit is almost always the nearest yet (measured). (t > 0,
                // so this is `r.min(t)`, NaN included, in one compare.)
                let t = self.tn / den;
                if !(t >= *r) {
                    *r = t;
                }
            }
        }
    }

    /// `ray_segment` itself, for a sensor on the segment's line (`tn` = 0, t = 0).
    #[cold]
    fn lower_either(&self, dirs: &[[f64; 2]], ranges: &mut [f64]) {
        let s = [self.ax, self.ay, self.ex, self.ey];
        for (r, d) in ranges.iter_mut().zip(dirs) {
            *r = r.min(ray_segment(0.0, 0.0, d[0], d[1], &s));
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
    let (l, h) = interval(beams, wrap_pi(ac + lo), wrap_pi(ac + hi));
    [-TAU, 0.0, TAU].iter().any(|sh| {
        beams
            .span(l + sh, h + sh)
            .is_some_and(|(k0, k1)| ranges[k0..=k1].iter().any(|&r| r > d))
    })
}

/// Widened angular interval (from beam 0) swept counter-clockwise from the world angle
/// `ap` to `aq` (each in [-pi, pi]).
#[inline(always)]
fn interval(beams: &Beams, ap: f64, aq: f64) -> (f64, f64) {
    let start = wrap_tau(ap - beams.theta0);
    let len = wrap_tau(aq - ap);
    (start - beams.margin, start + len + beams.margin)
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

#[cfg(test)]
#[path = "segment_scan_tests.rs"]
mod tests;
