//! Curvature-based analysis of a closed centreline: turns, named features (hairpin,
//! chicane, sweeper), straights, minimum radius and self-clearance.
//!
//! The same code measures the constructor's analytic curve (a cheap pre-check) and the
//! centreline recovered from the raster (the validator), so both agree on what a feature
//! is. Every threshold is a multiple of the *corner radius* `r_c = max(p/2, r_min)`, the
//! radius at which the lattice constructor rounds ordinary 90° corners (see
//! `generate::lattice`); the bands are:
//!
//! * a *turn* is a maximal run where `|κ| ≥ 1/(8 r_c)` that reaches `|κ| ≥ 1/(3 r_c)`;
//!   same-sense turns separated by less than `0.8 r_c` of straight are merged (one lattice
//!   edge leaves ≤ 0.8 r_c between fillets, two edges ≥ 2 r_c; smoothing blurs ~0.6 r_c);
//! * *hairpin*: a merged turn of `|θ| ≥ 135°`;
//! * *chicane*: two consecutive opposite-sense turns of `45° ≤ |θ| < 135°` separated by
//!   less than `0.8 r_c`;
//! * *sweeper*: any other turn of `45° ≤ |θ| < 135°` whose peak radius is `≥ 1.5 r_c`;
//! * a *straight* is a maximal run where `|κ| < 1/(8 r_c)`.

use crate::error::{ArenaError, Result};
use crate::geometry::dist;
use crate::geometry::polyline::resample_closed;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A named feature kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FeatureKind {
    Hairpin,
    Chicane,
    Sweeper,
}

impl FeatureKind {
    pub fn name(self) -> &'static str {
        match self {
            FeatureKind::Hairpin => "hairpin",
            FeatureKind::Chicane => "chicane",
            FeatureKind::Sweeper => "sweeper",
        }
    }
}

/// One merged turn: arc-length interval, signed angle (rad, + = left) and peak radius.
#[derive(Debug, Clone, Serialize)]
pub struct Turn {
    pub start_m: f64,
    pub end_m: f64,
    pub angle_rad: f64,
    pub peak_radius_m: f64,
}

/// A detected feature and where it starts along the lap (m from the first point).
#[derive(Debug, Clone, Serialize)]
pub struct Feature {
    pub kind: FeatureKind,
    pub at_m: f64,
    pub x: f64,
    pub y: f64,
}

/// Everything measured on one closed curve (in its point order = driving direction).
#[derive(Debug, Clone, Serialize)]
pub struct CurveAnalysis {
    pub length_m: f64,
    pub min_radius_m: f64,
    pub turns: Vec<Turn>,
    pub features: Vec<Feature>,
    pub longest_straight_m: f64,
    pub total_turn_rad: f64,
}

impl CurveAnalysis {
    pub fn count(&self, kind: FeatureKind) -> usize {
        self.features.iter().filter(|f| f.kind == kind).count()
    }
    pub fn order(&self) -> Vec<FeatureKind> {
        self.features.iter().map(|f| f.kind).collect()
    }
}

/// Periodic moving average with half-window `h` samples.
fn smooth_periodic<T: Copy + Default + std::ops::Add<Output = T> + std::ops::Sub<Output = T>>(
    x: &[T],
    h: usize,
    scale: impl Fn(T) -> T,
) -> Vec<T> {
    let n = x.len();
    if h == 0 || n == 0 {
        return x.to_vec();
    }
    let idx = |i: isize| x[i.rem_euclid(n as isize) as usize];
    let mut acc = T::default();
    for k in -(h as isize)..=(h as isize) {
        acc = acc + idx(k);
    }
    let mut out = Vec::with_capacity(n);
    for i in 0..n as isize {
        out.push(scale(acc));
        acc = acc + idx(i + h as isize + 1) - idx(i - h as isize);
    }
    out
}

#[derive(Clone, Copy, Default)]
struct P2([f64; 2]);
impl std::ops::Add for P2 {
    type Output = P2;
    fn add(self, o: P2) -> P2 {
        P2([self.0[0] + o.0[0], self.0[1] + o.0[1]])
    }
}
impl std::ops::Sub for P2 {
    type Output = P2;
    fn sub(self, o: P2) -> P2 {
        P2([self.0[0] - o.0[0], self.0[1] - o.0[1]])
    }
}

/// Smoothing half-window as a share of the corner radius.
pub const SMOOTHING: f64 = 0.3;

/// Sample spacing (m) used for the analysis.
pub const ANALYSIS_DS: f64 = 0.05;

/// Signed curvature (1/m) at each sample of a uniformly resampled closed curve, after
/// smoothing with moving averages of half-width `half_window` (m), applied twice to the
/// points and once to the curvature. A window of ~0.3 r suppresses raster staircase
/// noise while shrinking the radius of a smoothed arc by only ~1 % (r·sinc(h/r)).
pub fn curvature_profile(pts: &[[f64; 2]], ds: f64, half_window: f64) -> Vec<f64> {
    let n = pts.len();
    let h = ((half_window / ds).round() as usize).max(1);
    let inv = 1.0 / (2 * h + 1) as f64;
    let mut q: Vec<P2> = pts.iter().map(|&p| P2(p)).collect();
    for _ in 0..2 {
        q = smooth_periodic(&q, h, |a| P2([a.0[0] * inv, a.0[1] * inv]));
    }
    let heading: Vec<f64> = (0..n)
        .map(|i| {
            let (a, b) = (q[(i + n - 1) % n].0, q[(i + 1) % n].0);
            (b[1] - a[1]).atan2(b[0] - a[0])
        })
        .collect();
    let kappa: Vec<f64> = (0..n)
        .map(|i| {
            let mut d = heading[(i + 1) % n] - heading[(i + n - 1) % n];
            d = (d + PI).rem_euclid(2.0 * PI) - PI;
            d / (2.0 * ds)
        })
        .collect();
    smooth_periodic(&kappa, h, |a| a * inv)
}

/// Longest closed curve [`analyse_closed_curve`] and [`self_clearance`] accept (m): the
/// clearance is quadratic in the number of 0.1 m samples.
pub const MAX_CURVE_LENGTH_M: f64 = 5_000.0;

/// The door of the curve analysis: ≥ 3 finite points spanning a positive length of at
/// most [`MAX_CURVE_LENGTH_M`], `corner_radius` finite and > 0, `exclude_m` finite ≥ 0.
pub fn check_curve_args(points: &[[f64; 2]], corner_radius: f64, exclude_m: f64) -> Result<()> {
    if points.len() < 3 {
        return Err(ArenaError::invalid(format!(
            "analyse_curve needs at least 3 points, got {}",
            points.len()
        )));
    }
    if let Some(p) = points
        .iter()
        .find(|p| !(p[0].is_finite() && p[1].is_finite()))
    {
        return Err(ArenaError::invalid(format!(
            "analyse_curve points must be finite, got {p:?}"
        )));
    }
    let length = crate::geometry::polyline_length(points, true);
    if !(length > 0.0 && length <= MAX_CURVE_LENGTH_M) {
        return Err(ArenaError::invalid(format!(
            "analyse_curve needs a curve of length in (0, {MAX_CURVE_LENGTH_M}] m, got {length} m"
        )));
    }
    crate::limits::check_range("corner_radius", corner_radius, 1e-3, 1e4, " m")?;
    crate::limits::check_range("exclude_m", exclude_m, 0.0, 1e6, " m")?;
    Ok(())
}

/// A turn in samples counted from the scan's start: (first, last, angle, peak |κ|).
type SampleTurn = (usize, usize, f64, f64);

/// Analyse a closed curve whose point order is the driving direction.
pub fn analyse_closed_curve(points: &[[f64; 2]], corner_radius: f64) -> CurveAnalysis {
    let length = crate::geometry::polyline_length(points, true);
    let pts = resample_closed(points, ANALYSIS_DS);
    let n = pts.len();
    let ds = length / n as f64;
    let kappa = curvature_profile(&pts, ds, SMOOTHING * corner_radius);
    let rc = corner_radius;
    let max_k = kappa.iter().fold(0.0f64, |m, k| m.max(k.abs()));
    let total_turn: f64 = kappa.iter().sum::<f64>() * ds;

    // Start the scan on the sample that is most straight so no turn wraps around 0.
    let start = (0..n)
        .min_by(|&a, &b| {
            kappa[a]
                .abs()
                .partial_cmp(&kappa[b].abs())
                .unwrap_or(std::cmp::Ordering::Equal)
        })
        .unwrap_or(0);
    let at = |k: usize| kappa[(start + k) % n];
    let (raw, longest_straight) = scan_turns(at, n, ds, rc);
    let gap_max = 0.8 * rc;
    let turns = merge_turns(raw, ds, gap_max);
    // The scan started mid-straight, so the first and last turn are never split halves.
    let to_m = |k: usize| ((start + k) % n) as f64 * ds;
    let features = classify_turns(&turns, n, ds, rc, gap_max)
        .into_iter()
        .map(|(kind, k)| {
            let p = pts[(start + k) % n];
            Feature {
                kind,
                at_m: to_m(k),
                x: p[0],
                y: p[1],
            }
        })
        .collect();
    let turns = turns
        .iter()
        .map(|t| Turn {
            start_m: to_m(t.0),
            end_m: to_m(t.1),
            angle_rad: t.2,
            peak_radius_m: 1.0 / t.3,
        })
        .collect();
    CurveAnalysis {
        length_m: length,
        min_radius_m: if max_k > 0.0 {
            1.0 / max_k
        } else {
            f64::INFINITY
        },
        turns,
        features,
        longest_straight_m: longest_straight,
        total_turn_rad: total_turn,
    }
}

/// Raw turns of the curvature `at(k)` over `n` samples `ds` apart, by hysteresis (a turn
/// runs while |κ| ≥ 1/(8 r_c) with one sign and counts when it peaks at ≥ 1/(3 r_c)),
/// and the longest straight (m) between them.
fn scan_turns(at: impl Fn(usize) -> f64, n: usize, ds: f64, rc: f64) -> (Vec<SampleTurn>, f64) {
    let (k_on, k_off) = (1.0 / (3.0 * rc), 1.0 / (8.0 * rc));
    let mut raw: Vec<SampleTurn> = Vec::new();
    let mut longest_straight = 0.0f64;
    let mut k = 0;
    while k < n {
        let sign = at(k).signum();
        if at(k).abs() < k_off {
            let s0 = k;
            while k < n && at(k).abs() < k_off {
                k += 1;
            }
            longest_straight = longest_straight.max((k - s0) as f64 * ds);
            continue;
        }
        let s0 = k;
        let (mut ang, mut peak) = (0.0, 0.0f64);
        while k < n && at(k).abs() >= k_off && at(k).signum() == sign {
            ang += at(k) * ds;
            peak = peak.max(at(k).abs());
            k += 1;
        }
        if peak >= k_on {
            raw.push((s0, k - 1, ang, peak));
        }
    }
    (raw, longest_straight)
}

/// Merge same-sense turns across gaps shorter than `gap_max` (m).
fn merge_turns(raw: Vec<SampleTurn>, ds: f64, gap_max: f64) -> Vec<SampleTurn> {
    let mut turns: Vec<SampleTurn> = Vec::new();
    for t in raw {
        if let Some(last) = turns.last_mut() {
            let gap = (t.0 - last.1) as f64 * ds;
            if last.2.signum() == t.2.signum() && gap < gap_max {
                *last = (last.0, t.1, last.2 + t.2, last.3.max(t.3));
                continue;
            }
        }
        turns.push(t);
    }
    turns
}

/// The features among merged turns, each with its first sample: a hairpin turns ≥ 135°;
/// a 45–135° turn followed within `gap_max` by one of the other sense is a chicane (both
/// used), else a sweeper if its peak radius is ≥ 1.5 r_c.
fn classify_turns(
    turns: &[SampleTurn],
    n: usize,
    ds: f64,
    rc: f64,
    gap_max: f64,
) -> Vec<(FeatureKind, usize)> {
    let deg = |a: f64| a.abs().to_degrees();
    let mut features = Vec::new();
    let mut used = vec![false; turns.len()];
    for i in 0..turns.len() {
        if used[i] {
            continue;
        }
        let t = turns[i];
        let a = deg(t.2);
        let kind = if a >= 135.0 {
            Some(FeatureKind::Hairpin)
        } else if a >= 45.0 {
            let j = (i + 1) % turns.len();
            let chicane = turns.len() > 1 && j != i && !used[j] && {
                let u = turns[j];
                let gap = ((u.0 + n - t.1) % n) as f64 * ds;
                u.2.signum() != t.2.signum()
                    && deg(u.2) >= 45.0
                    && deg(u.2) < 135.0
                    && gap < gap_max
            };
            if chicane {
                used[j] = true;
                Some(FeatureKind::Chicane)
            } else if 1.0 / t.3 >= 1.5 * rc {
                Some(FeatureKind::Sweeper)
            } else {
                None
            }
        } else {
            None
        };
        used[i] = true;
        if let Some(kind) = kind {
            features.push((kind, t.0));
        }
    }
    features
}

/// Sampling step (m) of the self-clearance in [`analyse_curve`].
pub const CLEARANCE_STEP_M: f64 = 0.1;

/// [`CurveAnalysis`] with the curve's [`self_clearance`] outside `exclude_m`.
#[derive(Debug, Clone, Serialize)]
pub struct CurveReport {
    #[serde(flatten)]
    pub analysis: CurveAnalysis,
    /// Self-clearance (m); `None` when no two points are more than `exclude_m` apart
    /// along the curve (no non-local pass).
    pub self_clearance_m: Option<f64>,
}

/// The curve analysis of a closed curve from outside (the door [`check_curve_args`]
/// first): features, turns and radius, plus its self-clearance outside `exclude_m`.
pub fn analyse_curve(
    points: &[[f64; 2]],
    corner_radius: f64,
    exclude_m: f64,
) -> Result<CurveReport> {
    check_curve_args(points, corner_radius, exclude_m)?;
    let clearance = self_clearance(points, exclude_m, CLEARANCE_STEP_M);
    Ok(CurveReport {
        analysis: analyse_closed_curve(points, corner_radius),
        self_clearance_m: clearance.is_finite().then_some(clearance),
    })
}

/// Smallest distance between two points of a closed curve that are more than `exclude_m`
/// apart along it (m): the centreline-to-centreline clearance of non-local sections.
pub fn self_clearance(points: &[[f64; 2]], exclude_m: f64, ds: f64) -> f64 {
    let pts = resample_closed(points, ds);
    let n = pts.len();
    let len = crate::geometry::polyline_length(&pts, true);
    let step = len / n as f64;
    let skip = (exclude_m / step).ceil() as usize;
    let mut best = f64::INFINITY;
    if 2 * skip >= n {
        return best;
    }
    for i in 0..n {
        for j in (i + skip)..(i + n - skip).min(n) {
            let d = dist(pts[i], pts[j]);
            if d < best {
                best = d;
            }
        }
    }
    best
}

/// Whether `measured` is a cyclic rotation of `wanted` (feature order on a closed lap).
pub fn is_cyclic_order(measured: &[FeatureKind], wanted: &[FeatureKind]) -> bool {
    if measured.len() != wanted.len() {
        return false;
    }
    if wanted.is_empty() {
        return true;
    }
    (0..measured.len())
        .any(|r| (0..wanted.len()).all(|i| measured[(i + r) % measured.len()] == wanted[i]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stadium(r: f64, straight: f64) -> Vec<[f64; 2]> {
        let mut p = Vec::new();
        let m = 200;
        for i in 0..=m {
            let a = -PI / 2.0 + PI * i as f64 / m as f64;
            p.push([straight + r * a.cos(), r + r * a.sin()]);
        }
        for i in 0..=m {
            let a = PI / 2.0 + PI * i as f64 / m as f64;
            p.push([r * a.cos(), r + r * a.sin()]);
        }
        p
    }

    #[test]
    fn stadium_has_two_hairpins_and_long_straights() {
        let a = analyse_closed_curve(&stadium(1.2, 10.0), 1.1);
        assert_eq!(a.count(FeatureKind::Hairpin), 2, "{:?}", a.turns);
        assert_eq!(a.features.len(), 2);
        assert!((a.min_radius_m - 1.2).abs() < 0.1, "{}", a.min_radius_m);
        assert!(
            a.longest_straight_m > 9.0 && a.longest_straight_m <= 10.0,
            "{}",
            a.longest_straight_m
        );
        assert!((a.total_turn_rad - 2.0 * PI).abs() < 1e-6);
        // Legs are 2.4 m apart; the hairpin itself is excluded by the window.
        let c = self_clearance(&stadium(1.2, 10.0), PI * 1.2, 0.05);
        assert!((c - 2.4).abs() < 0.02, "{c}");
    }

    #[test]
    fn cyclic_order_matches_rotations_only() {
        use FeatureKind::*;
        assert!(is_cyclic_order(
            &[Chicane, Hairpin, Hairpin],
            &[Hairpin, Chicane, Hairpin]
        ));
        assert!(!is_cyclic_order(
            &[Chicane, Hairpin, Sweeper],
            &[Chicane, Sweeper, Hairpin]
        ));
        assert!(is_cyclic_order(&[], &[]));
    }

    #[test]
    fn resample_keeps_length() {
        let s = stadium(1.0, 5.0);
        let r = resample_closed(&s, 0.05);
        let (l0, l1) = (
            crate::geometry::polyline_length(&s, true),
            crate::geometry::polyline_length(&r, true),
        );
        assert!((l0 - l1).abs() / l0 < 1e-3);
    }
}
