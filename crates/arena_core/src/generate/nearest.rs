//! Nearest feasible specs after a generation failure (issue 28): a bounded, deterministic
//! search that changes one field at a time and runs Algorithm 1 on each changed spec,
//! keeping per field the first (nearest) spec that builds and the seed that built it.
//!
//! Four directions, each a fixed list of probes, nearest first:
//!
//! * `lap_length_m`: the lap shortened (then lengthened) in steps of [`LAP_STEP`] of L,
//!   alternately, so a lap too long for its hall finds the longest lap that builds and a
//!   lap too short for its turns the shortest;
//! * `hall`: both hall sides scaled up together in steps of [`HALL_STEP`] (same aspect,
//!   rounded up to 0.5 m): the smallest hall that holds this lap;
//! * `corridor_width_m`: the corridor narrowed in 0.1 m steps: the widest that fits;
//! * `features`: one feature dropped, then two, then three (every combination of kinds,
//!   the order kept for the features that stay): the largest feature count that fits.
//!
//! Probes run round-robin over the directions, so each gets its nearest probes first
//! whatever the budget. A probe tries [`PROBE_SEEDS`] seeds, each with a cap of
//! [`PROBE_CANDIDATES`] candidates. Candidate `k` of a seed never depends on the cap or
//! on earlier candidates, so a probe accepted at candidate `k` is accepted at `k` again
//! by a full run with the same seed (800 candidates, any budget that lets it reach `k`).
//! These are constructions found, not proofs: a nearer spec may build with another seed.

use super::budget::Budget;
use super::construct::{generate, Outcome};
use super::screen::screen;
use super::spec::{ConstructorConfig, Spec};
use crate::track::features::FeatureKind;
use serde::Serialize;

/// Relative lap step of the lap probes.
pub const LAP_STEP: f64 = 0.06;
/// Lap probes on each side of L.
pub const LAP_PROBES: usize = 8;
/// Relative hall step of the hall probes, and how many.
pub const HALL_STEP: f64 = 0.1;
pub const HALL_PROBES: usize = 8;
/// Width step (m) of the corridor probes, and how many.
pub const WIDTH_STEP_M: f64 = 0.1;
pub const WIDTH_PROBES: usize = 8;
/// Most features dropped by the feature probes.
pub const MAX_DROPPED: u32 = 3;
/// Seeds per probe (the caller's seed, then the next ones).
pub const PROBE_SEEDS: u64 = 3;
/// Candidate cap per seed of one probe.
pub const PROBE_CANDIDATES: u32 = 200;

/// One spec that built: which direction, the changed spec, and the seed and candidate
/// index that built it.
#[derive(Debug, Clone, Serialize)]
pub struct Suggestion {
    /// `lap_length_m`, `hall`, `corridor_width_m` or `features`.
    pub field: &'static str,
    /// The changed spec (every other field as requested).
    pub spec: Spec,
    pub seed: u64,
    /// Index of the accepted candidate (a full run with `seed` accepts it again).
    pub candidate_index: u32,
}

/// What the search found and how far it got.
#[derive(Debug, Clone, Serialize)]
pub struct NearestReport {
    pub suggestions: Vec<Suggestion>,
    /// Probes run (changed specs tried) and whether the budget cut the search short.
    pub probes: u32,
    pub exhausted: bool,
}

fn round_to(x: f64, step: f64) -> f64 {
    (x / step).round() * step
}

/// Lap probes: L (1 − i s), L (1 + i s) alternately, rounded to 1 m (0.5 m under 20 m).
fn lap_probes(spec: &Spec) -> Vec<Spec> {
    let l = spec.lap_length_m;
    let step = if l < 20.0 { 0.5 } else { 1.0 };
    let mut out: Vec<Spec> = Vec::new();
    for i in 1..=LAP_PROBES {
        for sign in [-1.0, 1.0] {
            let v = round_to(l * (1.0 + sign * LAP_STEP * i as f64), step);
            if !(1.0..=2000.0).contains(&v) || (v - l).abs() < 1e-9 {
                continue;
            }
            if out.iter().any(|s| s.lap_length_m == v) {
                continue;
            }
            out.push(Spec {
                lap_length_m: v,
                ..spec.clone()
            });
        }
    }
    out
}

/// Hall probes: both sides × (1 + i s), rounded up to 0.5 m.
fn hall_probes(spec: &Spec) -> Vec<Spec> {
    let mut out: Vec<Spec> = Vec::new();
    for i in 1..=HALL_PROBES {
        let f = 1.0 + HALL_STEP * i as f64;
        let (x, y) = (
            (spec.hall_x_m * f * 2.0).ceil() / 2.0,
            (spec.hall_y_m * f * 2.0).ceil() / 2.0,
        );
        if x > 1000.0 || y > 1000.0 || out.iter().any(|s| s.hall_x_m == x && s.hall_y_m == y) {
            continue;
        }
        out.push(Spec {
            hall_x_m: x,
            hall_y_m: y,
            ..spec.clone()
        });
    }
    out
}

/// Width probes: w − i·0.1 m on the 0.05 m grid, down to the schema's 0.2 m.
fn width_probes(spec: &Spec) -> Vec<Spec> {
    let w = spec.corridor_width_m;
    (1..=WIDTH_PROBES)
        .map(|i| round_to(w - WIDTH_STEP_M * i as f64, 0.05))
        .filter(|&v| v >= 0.2 - 1e-9 && v < w - 1e-9)
        .map(|v| Spec {
            corridor_width_m: v,
            ..spec.clone()
        })
        .collect()
}

/// Feature probes: every (dh, dc, ds) dropping 1, then 2, … up to [`MAX_DROPPED`]
/// features; the requested order keeps the features that stay (the last ones of a kind
/// are dropped).
fn feature_probes(spec: &Spec) -> Vec<Spec> {
    let (h, c, s) = (spec.hairpins, spec.chicanes, spec.sweepers);
    let mut out = Vec::new();
    for d in 1..=MAX_DROPPED {
        for dh in 0..=d.min(h) {
            for dc in 0..=(d - dh).min(c) {
                let ds = d - dh - dc;
                if ds > s {
                    continue;
                }
                let mut order = spec.feature_order.clone();
                for (kind, n) in [
                    (FeatureKind::Hairpin, dh),
                    (FeatureKind::Chicane, dc),
                    (FeatureKind::Sweeper, ds),
                ] {
                    for _ in 0..n {
                        if let Some(i) = order.iter().rposition(|&k| k == kind) {
                            order.remove(i);
                        }
                    }
                }
                out.push(Spec {
                    hairpins: h - dh,
                    chicanes: c - dc,
                    sweepers: s - ds,
                    feature_order: order,
                    ..spec.clone()
                });
            }
        }
    }
    out
}

/// The first seed (of [`PROBE_SEEDS`] from `seed`) whose capped run accepts `spec`.
fn builds(spec: &Spec, cfg: &ConstructorConfig, seed: u64, budget: &Budget) -> Option<(u64, u32)> {
    if !screen(spec, cfg).passed {
        return None;
    }
    let probe_cfg = ConstructorConfig {
        max_candidates: cfg.max_candidates.min(PROBE_CANDIDATES),
        ..*cfg
    };
    for i in 0..PROBE_SEEDS {
        let s = seed.wrapping_add(i);
        match generate(spec, &probe_cfg, s, budget) {
            Ok(Outcome::Accepted {
                candidate_index, ..
            }) => return Some((s, candidate_index)),
            _ if budget.stopped().is_some() => return None,
            _ => {}
        }
    }
    None
}

/// Search the nearest specs that build (see the module doc). `budget` bounds the whole
/// search; the probes and their order never depend on time, only how far it gets.
pub fn nearest_specs(
    spec: &Spec,
    cfg: &ConstructorConfig,
    seed: u64,
    budget: &Budget,
) -> NearestReport {
    let directions: [(&'static str, Vec<Spec>); 4] = [
        ("lap_length_m", lap_probes(spec)),
        ("hall", hall_probes(spec)),
        ("corridor_width_m", width_probes(spec)),
        ("features", feature_probes(spec)),
    ];
    let mut found: [Option<Suggestion>; 4] = [None, None, None, None];
    let mut probes = 0;
    let rounds = directions.iter().map(|d| d.1.len()).max().unwrap_or(0);
    'outer: for r in 0..rounds {
        for (i, (field, list)) in directions.iter().enumerate() {
            if found[i].is_some() {
                continue;
            }
            let Some(p) = list.get(r) else { continue };
            if budget.stopped().is_some() {
                break 'outer;
            }
            probes += 1;
            if let Some((s, k)) = builds(p, cfg, seed, budget) {
                found[i] = Some(Suggestion {
                    field,
                    spec: p.clone(),
                    seed: s,
                    candidate_index: k,
                });
            }
        }
    }
    NearestReport {
        suggestions: found.into_iter().flatten().collect(),
        probes,
        exhausted: budget.stopped().is_some(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(l: f64, w: f64, bx: f64, by: f64, h: u32, c: u32, s: u32) -> Spec {
        Spec {
            name: "n".into(),
            lap_length_m: l,
            corridor_width_m: w,
            hall_x_m: bx,
            hall_y_m: by,
            direction: "counterclockwise".into(),
            hairpins: h,
            chicanes: c,
            sweepers: s,
            feature_order: vec![],
            min_radius_m: 0.0,
            longest_straight_m: 0.0,
            max_straight_m: None,
        }
    }

    #[test]
    fn probes_change_one_field_nearest_first() {
        let s = spec(60.0, 1.0, 12.0, 9.0, 1, 1, 0);
        let laps: Vec<f64> = lap_probes(&s).iter().map(|p| p.lap_length_m).collect();
        assert_eq!(laps[..4], [56.0, 64.0, 53.0, 68.0]);
        let halls: Vec<(f64, f64)> = hall_probes(&s)
            .iter()
            .map(|p| (p.hall_x_m, p.hall_y_m))
            .collect();
        assert_eq!(halls[..2], [(13.5, 10.0), (14.5, 11.0)]);
        let widths: Vec<f64> = width_probes(&s)
            .iter()
            .map(|p| p.corridor_width_m)
            .collect();
        assert!((widths[0] - 0.9).abs() < 1e-9 && widths.iter().all(|&w| w >= 0.2 - 1e-9));
        let feats: Vec<(u32, u32, u32)> = feature_probes(&s)
            .iter()
            .map(|p| (p.hairpins, p.chicanes, p.sweepers))
            .collect();
        assert_eq!(feats, [(1, 0, 0), (0, 1, 0), (0, 0, 0)]);
    }

    #[test]
    fn dropped_features_leave_the_order_of_the_rest() {
        use FeatureKind::*;
        let mut s = spec(60.0, 1.0, 20.0, 15.0, 2, 1, 0);
        s.feature_order = vec![Hairpin, Chicane, Hairpin];
        let p = &feature_probes(&s)[0];
        assert_eq!((p.hairpins, p.chicanes), (1, 1));
        assert_eq!(p.feature_order, vec![Hairpin, Chicane]);
    }

    #[test]
    fn a_failed_long_lap_gets_suggestions_that_build_again() {
        // 60 m at w = 0.8 m in 12 × 9 m (fill 0.87): a sweep miss.
        let s = spec(60.0, 0.8, 12.0, 9.0, 0, 0, 0);
        let cfg = ConstructorConfig::default();
        let r = nearest_specs(&s, &cfg, 0, &Budget::new(Some(60.0), None));
        assert!(!r.suggestions.is_empty(), "{r:?}");
        for g in &r.suggestions {
            match generate(&g.spec, &cfg, g.seed, &Budget::default()).unwrap() {
                Outcome::Accepted {
                    candidate_index, ..
                } => assert_eq!(candidate_index, g.candidate_index),
                other => panic!("{}: {other:?}", g.field),
            }
        }
        let lap = r.suggestions.iter().find(|g| g.field == "lap_length_m");
        assert!(lap.is_some_and(|g| g.spec.lap_length_m < 60.0));
    }
}
