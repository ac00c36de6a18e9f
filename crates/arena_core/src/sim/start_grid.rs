//! The grid start of a track: where the first car of a staggered grid stands, and the
//! measures that choose it (wall clearance, free run ahead). The envs, the previews, the
//! ROS 2 bridge and the library all place cars with it (`roboracer_arena.start_grid` is
//! its Python view); [`super::starts`] then draws the resets from the chosen arc length.
//!
//! The grid start comes from the track's geometry, not from wherever an extracted
//! centreline happens to begin: candidates every `max(0.25 m, lap / 400)` along the
//! centreline; a candidate qualifies when each of the grid's slots behind it keeps at
//! least 75 % of the median candidate wall clearance; among those the longest free run
//! ahead (to the first wall along the heading, capped at 1e6 m) wins, ties going to the
//! larger clearance, then to the later candidate. With none qualifying, the largest
//! clearance wins (the first on ties). A source start line (a circuit's or recorded
//! map's centreline file) keeps the grid at s = 0 whenever its slots qualify. An open
//! map's grid starts at its start pose.
//!
//! The arithmetic follows the numpy code this replaced, operation for operation, so the
//! grid starts (and every result that depends on them) are bit-identical to it: a test
//! holds the two together on many tracks (`tests/test_start_grid_oracle.py`).

use std::sync::Mutex;

use super::shared_track::pose_on_ring;
use crate::error::{ArenaError, Result};
use crate::geometry::polyline::cumulative_length;

/// Fraction of the median candidate clearance every grid slot must keep.
const CLEARANCE_FRACTION: f64 = 0.75;
/// Candidates are at least this far apart (m), and at most 400 per lap.
const MIN_CANDIDATE_STEP: f64 = 0.25;
const CANDIDATES_PER_LAP: f64 = 400.0;
/// Free runs are capped here (m): an open horizon compares as this long.
const MAX_FREE_RUN: f64 = 1e6;
/// Most grid slots (the simulator's own bound on cars).
const MAX_SLOTS: usize = 1 << 20;

/// Python's (and numpy's) float modulo: the result takes the divisor's sign.
fn py_mod(a: f64, b: f64) -> f64 {
    let m = a % b;
    if m != 0.0 {
        if (b < 0.0) != (m < 0.0) {
            m + b
        } else {
            m
        }
    } else {
        0.0f64.copysign(b)
    }
}

/// numpy's `allclose` for two points (rtol 1e-5, atol 1e-8).
fn allclose(a: [f64; 2], b: [f64; 2]) -> bool {
    (0..2).all(|i| (a[i] - b[i]).abs() <= 1e-8 + 1e-5 * b[i].abs())
}

/// What the grid is laid along: a closed centreline, or an open map's start pose.
#[derive(Debug, Clone)]
enum Line {
    Ring { pts: Vec<[f64; 2]>, cum: Vec<f64> },
    Anchor([f64; 3]),
}

/// A track's start geometry: wall edges, its centreline (or an open map's start pose)
/// and whether s = 0 is the source's own start line. Grid starts are cached per
/// (slots, spacing).
#[derive(Debug)]
pub struct StartGrid {
    /// Wall edges as (start, delta); each wall closes back to its first vertex unless it
    /// has two points or already ends (allclose) where it began.
    edges: Vec<([f64; 2], [f64; 2])>,
    line: Line,
    source_start: bool,
    cache: Mutex<Vec<(usize, u64, f64)>>,
}

impl StartGrid {
    /// From wall polylines and either a closed centreline ring (`open_map` false: at
    /// least 3 points, in the racing direction, no repeated closing point) or an open
    /// map's start anchor (`open_map` true: two distinct points, the start and a point it
    /// heads to). `source_start`: s = 0 is the source's own start line.
    pub fn new(
        walls: &[Vec<[f64; 2]>],
        centreline: &[[f64; 2]],
        open_map: bool,
        source_start: bool,
    ) -> Result<Self> {
        let bad = |m: &str| Err(ArenaError::invalid(format!("start grid: {m}")));
        if walls.is_empty() || walls.iter().any(|w| w.len() < 2) {
            return bad("needs at least one wall, each of at least 2 points");
        }
        let finite = |p: &[[f64; 2]]| p.iter().flatten().all(|v| v.is_finite());
        if !walls.iter().all(|w| finite(w)) || !finite(centreline) {
            return bad("walls and centreline must be finite");
        }
        let line = if open_map {
            let [a, b] = match centreline {
                [a, b] if a != b => [*a, *b],
                _ => return bad("an open map's start anchor is 2 distinct points"),
            };
            Line::Anchor([a[0], a[1], (b[1] - a[1]).atan2(b[0] - a[0])])
        } else {
            if centreline.len() < 3 {
                return bad("a closed centreline needs at least 3 points");
            }
            let cum = cumulative_length(centreline, true);
            let length = cum[centreline.len()];
            if length <= 0.0 || !length.is_finite() {
                return bad("the centreline must have a finite length > 0");
            }
            Line::Ring {
                pts: centreline.to_vec(),
                cum,
            }
        };
        let mut edges = Vec::new();
        for w in walls {
            let closes = w.len() > 2 && !allclose(w[0], w[w.len() - 1]);
            let ring = w.iter().chain(closes.then_some(&w[0]));
            for (a, b) in ring.clone().zip(ring.skip(1)) {
                edges.push((*a, [b[0] - a[0], b[1] - a[1]]));
            }
        }
        Ok(StartGrid {
            edges,
            line,
            source_start,
            cache: Mutex::new(Vec::new()),
        })
    }

    /// An open map's start anchor (no closed centreline).
    pub fn is_open(&self) -> bool {
        matches!(self.line, Line::Anchor(_))
    }

    /// s = 0 is the source's own start line (kept whenever the grid is clear there).
    pub fn source_start(&self) -> bool {
        self.source_start
    }

    /// Lap length (m); 0 for an open map.
    pub fn length(&self) -> f64 {
        match &self.line {
            Line::Ring { cum, .. } => cum[cum.len() - 1],
            Line::Anchor(_) => 0.0,
        }
    }

    /// (x, y, heading) on the centreline at arc length `s` (wrapped at the lap); on an
    /// open map, `s` metres along the start heading (behind the start for `s < 0`).
    pub fn pose_at(&self, s: f64) -> [f64; 3] {
        match &self.line {
            Line::Anchor([x, y, yaw]) => [x + s * yaw.cos(), y + s * yaw.sin(), *yaw],
            Line::Ring { pts, cum } => pose_on_ring(pts, cum, py_mod(s, cum[cum.len() - 1])),
        }
    }

    /// Distance (m) from (x, y) along `heading` to the first wall (infinite if none).
    pub fn free_run_ahead(&self, x: f64, y: f64, heading: f64) -> f64 {
        let (c, s) = (heading.cos(), heading.sin());
        let mut best = f64::INFINITY;
        for &(a, e) in &self.edges {
            let den = c * e[1] - s * e[0];
            if den.abs() <= 1e-12 || den.is_nan() {
                continue;
            }
            let (ax, ay) = (a[0] - x, a[1] - y);
            let t = (ax * e[1] - ay * e[0]) / den;
            let u = (ax * s - ay * c) / den;
            if t > 0.0 && (0.0..=1.0).contains(&u) && t < best {
                best = t;
            }
        }
        best
    }

    /// Distance (m) from `p` to the nearest wall.
    pub fn clearance(&self, p: [f64; 2]) -> f64 {
        let mut best = f64::INFINITY;
        for &(a, d) in &self.edges {
            let l2 = (d[0] * d[0] + d[1] * d[1]).max(1e-18);
            let t = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2;
            // numpy's clip: max first, then min (a NaN stays NaN).
            let t = if t > 0.0 || t.is_nan() { t } else { 0.0 };
            let t = if t < 1.0 || t.is_nan() { t } else { 1.0 };
            let (dx, dy) = ((a[0] + t * d[0]) - p[0], (a[1] + t * d[1]) - p[1]);
            let d2 = dx * dx + dy * dy;
            if d2 < best || d2.is_nan() {
                best = d2;
            }
        }
        best.sqrt()
    }

    /// Arc length of the first slot of a grid of `slots` cars `spacing` m apart (see
    /// the module docs); 0 on an open map. Cached per (slots, spacing).
    pub fn grid_start_s(&self, slots: usize, spacing: f64) -> Result<f64> {
        check_grid(slots, spacing)?;
        if matches!(self.line, Line::Anchor(_)) {
            return Ok(0.0);
        }
        let key = (slots, spacing.to_bits());
        let mut cache = self.cache.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(&(_, _, s)) = cache.iter().find(|c| (c.0, c.1) == key) {
            return Ok(s);
        }
        let s = self.choose_start(slots, spacing);
        cache.push((key.0, key.1, s));
        Ok(s)
    }

    fn choose_start(&self, slots: usize, spacing: f64) -> f64 {
        let length = self.length();
        let step = MIN_CANDIDATE_STEP.max(length / CANDIDATES_PER_LAP);
        // numpy's arange(0, length, step): ceil(length / step) values i * step.
        let n = (length / step).ceil() as usize;
        let cand: Vec<f64> = (0..n).map(|i| i as f64 * step).collect();
        let poses: Vec<[f64; 3]> = cand.iter().map(|&s| self.pose_at(s)).collect();
        let clear: Vec<f64> = poses.iter().map(|p| self.clearance([p[0], p[1]])).collect();
        let need = CLEARANCE_FRACTION * median(&clear);
        let slot_clear: Vec<f64> = (0..n)
            .map(|i| {
                (0..slots)
                    .map(|k| {
                        let back = py_mod(cand[i] - k as f64 * spacing, length) / step;
                        clear[(back.round_ties_even() as usize) % n]
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        let ok: Vec<bool> = slot_clear.iter().map(|&c| c >= need).collect();
        let best = if self.source_start && ok[0] {
            0
        } else if ok.iter().any(|&q| q) {
            let run = |i: usize| {
                let [x, y, h] = poses[i];
                self.free_run_ahead(x, y, h).min(MAX_FREE_RUN)
            };
            // The longest run, then the larger clearance, then the later candidate.
            let mut best = (f64::NEG_INFINITY, f64::NEG_INFINITY, 0);
            for i in (0..n).filter(|&i| ok[i]) {
                let key = (run(i), slot_clear[i], i);
                if (key.0, key.1) >= (best.0, best.1) {
                    best = key;
                }
            }
            best.2
        } else {
            // The largest clearance, the first on ties.
            (0..n).fold(0, |b, i| if slot_clear[i] > slot_clear[b] { i } else { b })
        };
        cand[best]
    }

    /// Poses of a staggered grid of `slots` cars: the first at arc length `s0` (default
    /// [`Self::grid_start_s`]), each further one `spacing` behind the one before and,
    /// with more than one car, `offset` left and right of the centreline in turn.
    pub fn grid_poses(
        &self,
        slots: usize,
        spacing: f64,
        offset: f64,
        s0: Option<f64>,
    ) -> Result<Vec<[f64; 3]>> {
        check_grid(slots, spacing)?;
        let s0 = match s0 {
            Some(s) if !s.is_finite() => {
                return Err(ArenaError::invalid("start grid: s0 must be finite"))
            }
            Some(s) => s,
            None => self.grid_start_s(slots, spacing)?,
        };
        if !(offset.is_finite() && (0.0..=1e4).contains(&offset)) {
            return Err(ArenaError::invalid(format!(
                "start grid: offset must be in [0, 1e4] m, got {offset}"
            )));
        }
        let length = self.length();
        Ok((0..slots)
            .map(|k| {
                let s = s0 - k as f64 * spacing;
                let [x, y, yaw] = self.pose_at(if length > 0.0 { py_mod(s, length) } else { s });
                let lat = match (slots, k % 2) {
                    (1, _) => 0.0,
                    (_, 0) => offset,
                    _ => -offset,
                };
                [x - lat * yaw.sin(), y + lat * yaw.cos(), yaw]
            })
            .collect())
    }
}

/// A grid of 1 to [`MAX_SLOTS`] cars, spaced by a finite distance in [0, 1e4] m.
fn check_grid(slots: usize, spacing: f64) -> Result<()> {
    if (1..=MAX_SLOTS).contains(&slots) && spacing.is_finite() && (0.0..=1e4).contains(&spacing) {
        Ok(())
    } else {
        Err(ArenaError::invalid(format!(
            "start grid: needs slots in [1, {MAX_SLOTS}] and spacing in [0, 1e4] m, got {slots} and {spacing}"
        )))
    }
}

/// numpy's median: the middle value, or the mean of the two middle values.
fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    if n % 2 == 1 {
        s[n / 2]
    } else {
        (s[n / 2 - 1] + s[n / 2]) / 2.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle(r: f64, n: usize) -> Vec<[f64; 2]> {
        crate::geometry::test_circle(n, r)
    }

    /// A stadium: two 10 m straights joined by half circles; walls 1 m either side.
    fn stadium(r: f64) -> Vec<[f64; 2]> {
        let mut p = Vec::new();
        for i in 0..20 {
            p.push([-5.0 + i as f64 * 0.5, -r]);
        }
        for i in 0..20 {
            let a = -std::f64::consts::FRAC_PI_2 + i as f64 / 20.0 * std::f64::consts::PI;
            p.push([5.0 + r * a.cos(), r * a.sin()]);
        }
        for i in 0..20 {
            p.push([5.0 - i as f64 * 0.5, r]);
        }
        for i in 0..20 {
            let a = std::f64::consts::FRAC_PI_2 + i as f64 / 20.0 * std::f64::consts::PI;
            p.push([-5.0 + r * a.cos(), r * a.sin()]);
        }
        p
    }

    #[test]
    fn free_run_and_clearance_on_a_ring() {
        let g = StartGrid::new(
            &[circle(3.0, 256), circle(1.0, 256)],
            &circle(2.0, 64),
            false,
            false,
        )
        .unwrap();
        assert!((g.clearance([2.0, 0.0]) - 1.0).abs() < 1e-3);
        // From (2, 0) heading +y, the chord to the outer wall: sqrt(9 - 4).
        let run = g.free_run_ahead(2.0, 0.0, std::f64::consts::FRAC_PI_2);
        assert!((run - 5f64.sqrt()).abs() < 1e-3, "{run}");
        assert_eq!(g.free_run_ahead(10.0, 0.0, 0.0), f64::INFINITY);
    }

    #[test]
    fn the_grid_starts_on_a_straight_facing_it() {
        let g = StartGrid::new(&[stadium(3.0), stadium(1.0)], &stadium(2.0), false, false).unwrap();
        let s = g.grid_start_s(3, 1.0).unwrap();
        let [x, y, h] = g.pose_at(s);
        assert!(g.free_run_ahead(x, y, h) > 5.0);
        for k in 0..3 {
            let p = g.pose_at(s - k as f64);
            assert!(g.clearance([p[0], p[1]]) > 0.5);
        }
        assert_eq!(g.grid_start_s(3, 1.0).unwrap(), s, "cached");
        let poses = g.grid_poses(2, 1.0, 0.2, Some(s)).unwrap();
        assert_eq!(poses.len(), 2);
        assert!(g.grid_start_s(0, 1.0).is_err() && g.grid_start_s(1, f64::NAN).is_err());
    }

    #[test]
    fn a_clear_source_start_line_keeps_the_grid() {
        let g = StartGrid::new(&[stadium(3.0), stadium(1.0)], &stadium(2.0), false, true).unwrap();
        assert_eq!(g.grid_start_s(2, 1.0).unwrap(), 0.0);
    }

    #[test]
    fn an_open_map_grid_lines_up_behind_its_start() {
        let g = StartGrid::new(&[circle(5.0, 64)], &[[1.0, 1.0], [1.0, 2.0]], true, false).unwrap();
        assert_eq!(g.length(), 0.0);
        assert_eq!(g.grid_start_s(2, 1.0).unwrap(), 0.0);
        let p = g.grid_poses(2, 1.0, 0.2, None).unwrap();
        assert!((p[1][1] - 0.0).abs() < 1e-12 && (p[1][0] - 1.2).abs() < 1e-12);
        assert!(
            StartGrid::new(&[circle(5.0, 64)], &[[1.0, 1.0], [1.0, 1.0]], true, false).is_err()
        );
    }

    #[test]
    fn bad_geometry_is_refused() {
        assert!(StartGrid::new(&[], &circle(2.0, 8), false, false).is_err());
        assert!(StartGrid::new(&[circle(3.0, 8)], &circle(2.0, 8)[..2], false, false).is_err());
        let mut w = circle(3.0, 8);
        w[2][0] = f64::NAN;
        assert!(StartGrid::new(&[w], &circle(2.0, 8), false, false).is_err());
        assert!(StartGrid::new(&[circle(3.0, 8)], &[[0.0, 0.0]; 3], false, false).is_err());
    }

    #[test]
    fn median_and_modulo_follow_numpy() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
        assert_eq!(py_mod(-1.0, 5.0), 4.0);
        assert_eq!(py_mod(5.0, 5.0), 0.0);
        assert!(py_mod(-0.0, 5.0).is_sign_positive());
    }
}
