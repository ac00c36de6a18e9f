//! The admissibility screen (Eqs. 1–2): a constant-time necessary condition.
//!
//! Feature minimum arc lengths ℓ_i^min follow the detector's geometric bands (see
//! `track::features`): a hairpin turns ≥ 180° in the lattice (two 90° corners), a
//! chicane is two opposite ≥ 45° turns, a sweeper a ≥ 60° turn at ≥ 1.5 r_min; every
//! feature also needs a straight lead λ on both sides so the detector can tell it from
//! its neighbours. λ = 0.424 m is calibrated on the paper's worked example (five
//! hairpins in a 45 m lap clear the 0.70·0.72·L budget by 0.77 m at the default width):
//!
//! * hairpin: `ℓ = π r_min + 2λ`  (4.382 m at w = 1.5 m)
//! * chicane: `ℓ = (π/2) r_min + 2λ`
//! * sweeper: `ℓ = (π/3)·1.5 r_min + 2λ = (π/2) r_min + 2λ`

use super::spec::{derive, ConstructorConfig, Spec};
use serde::Serialize;
use std::f64::consts::PI;

/// Straight lead each named feature needs on either side (m).
pub const FEATURE_LEAD_M: f64 = 0.424;
/// Share of the lap reserved for straights, and share of the rest features may use.
pub const STRAIGHT_SHARE: f64 = 0.28;
pub const FEATURE_SHARE: f64 = 0.70;

/// ℓ_i^min per feature kind (m): (hairpin, chicane, sweeper).
pub fn feature_min_lengths(r_min: f64) -> (f64, f64, f64) {
    let lead = 2.0 * FEATURE_LEAD_M;
    (
        PI * r_min + lead,
        PI / 2.0 * r_min + lead,
        PI / 2.0 * r_min + lead,
    )
}

/// Outcome of the screen with every quantity it computed.
#[derive(Debug, Clone, Serialize)]
pub struct ScreenResult {
    pub passed: bool,
    /// Human-readable violated bound(s), empty when passed.
    pub violations: Vec<String>,
    pub r_min_m: f64,
    pub pitch_m: f64,
    pub l_max_m: f64,
    pub l_min_m: f64,
    pub feature_length_m: f64,
    pub feature_budget_m: f64,
}

pub fn screen(spec: &Spec, cfg: &ConstructorConfig) -> ScreenResult {
    let d = derive(spec, cfg);
    let l = spec.lap_length_m;
    let l_min = 2.0 * PI * d.r_min;
    let (h, c, s) = feature_min_lengths(d.r_min);
    let feat = spec.hairpins as f64 * h + spec.chicanes as f64 * c + spec.sweepers as f64 * s;
    let budget = FEATURE_SHARE * (1.0 - STRAIGHT_SHARE) * l;
    let mut v = Vec::new();
    if l < l_min {
        v.push(format!(
            "L = {l:.1} m < 2π r_min = {l_min:.1} m (r_min = {:.2} m)",
            d.r_min
        ));
    }
    if l > d.l_max {
        v.push(format!(
            "L = {l:.1} m > L_max = {:.1} m for a {}×{} m hall (p = {:.2} m, m_h = {} m)",
            d.l_max,
            fmt_num(spec.hall_x_m),
            fmt_num(spec.hall_y_m),
            d.pitch,
            cfg.hall_margin_m
        ));
    }
    if let Some(cap) = spec.max_straight_m {
        // The validator wants the longest straight ≥ 0.95 × the floor and ≤ the cap.
        let floor = 0.95 * spec.longest_straight_m;
        if floor > cap {
            v.push(format!(
                "longest straight ≥ 0.95 × {:.2} m = {floor:.2} m (the floor less the validator's \
                 5 %) > max_straight_m = {cap:.2} m",
                spec.longest_straight_m
            ));
        }
    }
    if feat > budget {
        v.push(format!(
            "named features need Σℓ_min = {feat:.2} m > 0.70·(1 − 0.28)·L = {budget:.2} m \
             ({} hairpins × {h:.2} m, {} chicanes × {c:.2} m, {} sweepers × {s:.2} m)",
            spec.hairpins, spec.chicanes, spec.sweepers
        ));
    }
    ScreenResult {
        passed: v.is_empty(),
        violations: v,
        r_min_m: d.r_min,
        pitch_m: d.pitch,
        l_max_m: d.l_max,
        l_min_m: l_min,
        feature_length_m: feat,
        feature_budget_m: budget,
    }
}

fn fmt_num(x: f64) -> String {
    if x.fract() == 0.0 {
        format!("{x:.0}")
    } else {
        format!("{x}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn spec(l: f64, bx: f64, by: f64) -> Spec {
        Spec::plain(l, 1.5, bx, by)
    }

    #[test]
    fn paper_200m_in_20x15_is_rejected_with_lmax() {
        let r = screen(&spec(200.0, 20.0, 15.0), &ConstructorConfig::default());
        assert!(!r.passed);
        assert!((r.pitch_m - 2.15).abs() < 1e-12);
        assert!((r.l_max_m - 123.72).abs() < 0.01, "{}", r.l_max_m);
        assert_eq!(
            r.violations[0],
            "L = 200.0 m > L_max = 123.7 m for a 20×15 m hall (p = 2.15 m, m_h = 0.5 m)"
        );
    }

    #[test]
    fn paper_five_hairpins_in_45m_clear_budget_by_077() {
        let mut s = spec(45.0, 20.0, 15.0);
        s.hairpins = 5;
        let r = screen(&s, &ConstructorConfig::default());
        assert!(r.passed, "{:?}", r.violations);
        assert!(((r.feature_budget_m - r.feature_length_m) - 0.77).abs() < 0.005);
        s.hairpins = 6;
        assert!(!screen(&s, &ConstructorConfig::default()).passed);
    }

    #[test]
    fn a_straight_cap_below_the_floor_is_rejected() {
        let mut s = spec(60.0, 20.0, 15.0);
        s.longest_straight_m = 8.0;
        s.max_straight_m = Some(7.6);
        assert!(screen(&s, &ConstructorConfig::default()).passed);
        s.max_straight_m = Some(7.5);
        let r = screen(&s, &ConstructorConfig::default());
        assert!(!r.passed && r.violations[0].contains("max_straight_m = 7.50 m"));
    }

    #[test]
    fn too_short_lap_is_rejected() {
        let r = screen(&spec(5.0, 20.0, 15.0), &ConstructorConfig::default());
        assert!(!r.passed && r.violations[0].contains("2π r_min"));
    }
}
