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
//! Each direction first tries one *anchor*: the value that puts the lap at
//! [`ANCHOR_FILL`] of L_max (lap shortened, hall enlarged, corridor narrowed), where the
//! sweep builds almost everything, so a long lap in a small hall gets a suggestion even
//! when its nearer probes are slow to fail. Then the probes run, nearest first, and the
//! nearest that builds replaces the anchor. Both phases run round-robin over the
//! directions, so each gets its anchor and then its nearest probes whatever the deadline.
//! A probe tries [`PROBE_SEEDS`] seeds, each with a cap of [`PROBE_CANDIDATES`]
//! candidates. Candidate `k` of a seed never depends on the cap or on earlier candidates,
//! so a probe accepted at candidate `k` is accepted at `k` again by a full run with the
//! same seed (800 candidates, any deadline that lets it reach `k`).
//! These are constructions found, not proofs: a nearer spec may build with another seed.

use super::construct::{generate, Outcome};
use super::deadline::Deadline;
use super::screen::screen;
use super::spec::{derive, ConstructorConfig, Spec};
use crate::track::features::FeatureKind;
use serde::Serialize;

/// Fill L / L_max the anchors aim at.
pub const ANCHOR_FILL: f64 = 0.5;
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
    /// Probes run (changed specs tried) and whether the deadline cut the search short.
    pub probes: u32,
    pub exhausted: bool,
}

impl NearestReport {
    /// The report when the deadline passed inside the first probe and the caller stopped
    /// waiting: nothing found, the deadline passed.
    pub fn abandoned() -> NearestReport {
        NearestReport {
            suggestions: Vec::new(),
            probes: 0,
            exhausted: true,
        }
    }
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

/// The anchors (see the module doc), or `None` where the lap already fills at most
/// [`ANCHOR_FILL`] of L_max in that direction (the nearest probes then do).
fn anchors(spec: &Spec, cfg: &ConstructorConfig) -> [Option<Spec>; 4] {
    let l_max = derive(spec, cfg).l_max;
    let l = spec.lap_length_m;
    if !(l_max > 0.0 && l > ANCHOR_FILL * l_max) {
        return [None, None, None, None];
    }
    let step = if l < 20.0 { 0.5 } else { 1.0 };
    let lap = ((ANCHOR_FILL * l_max / step).floor() * step).max(1.0);
    let lap = (lap < l).then(|| Spec {
        lap_length_m: lap,
        ..spec.clone()
    });
    // L_max = (X − 2 m)(Y − 2 m) / p: the scale f with (fX − 2 m)(fY − 2 m) = L p / fill.
    let m = cfg.hall_margin_m;
    let p = derive(spec, cfg).pitch;
    let (x, y) = (spec.hall_x_m, spec.hall_y_m);
    let area = l * p / ANCHOR_FILL;
    // (f x − 2m)(f y − 2m) = area: x y f² − 2m (x + y) f + 4m² − area = 0.
    let (a, b, c) = (x * y, -2.0 * m * (x + y), 4.0 * m * m - area);
    let f = (-b + (b * b - 4.0 * a * c).max(0.0).sqrt()) / (2.0 * a);
    let hall = (f.is_finite() && f * x.max(y) <= 1000.0).then(|| Spec {
        hall_x_m: (x * f * 2.0).ceil() / 2.0,
        hall_y_m: (y * f * 2.0).ceil() / 2.0,
        ..spec.clone()
    });
    // p = w + 2 t_w + d_c: the width whose pitch gives L_max = L / fill.
    let usable = (x - 2.0 * m).max(0.0) * (y - 2.0 * m).max(0.0);
    let w = ((usable * ANCHOR_FILL / l - 2.0 * cfg.wall_thickness_m - cfg.clearance_m) / 0.05)
        .floor()
        * 0.05;
    let width = (w >= 0.2 - 1e-9 && w < spec.corridor_width_m - 1e-9).then(|| Spec {
        corridor_width_m: w,
        ..spec.clone()
    });
    [lap, hall, width, None]
}

/// The first seed (of [`PROBE_SEEDS`] from `seed`) whose capped run accepts `spec`.
fn builds(
    spec: &Spec,
    cfg: &ConstructorConfig,
    seed: u64,
    deadline: &Deadline,
) -> Option<(u64, u32)> {
    if !screen(spec, cfg).passed {
        return None;
    }
    let probe_cfg = ConstructorConfig {
        max_candidates: cfg.max_candidates.min(PROBE_CANDIDATES),
        ..*cfg
    };
    for i in 0..PROBE_SEEDS {
        let s = seed.wrapping_add(i);
        match generate(spec, &probe_cfg, s, deadline) {
            Ok(Outcome::Accepted {
                candidate_index, ..
            }) => return Some((s, candidate_index)),
            _ if deadline.stopped().is_some() => return None,
            _ => {}
        }
    }
    None
}

/// Whether probe `p` is no nearer to `spec` than the anchor (in its direction's value).
fn beyond_anchor(field: &str, spec: &Spec, p: &Spec, anchor: Option<&Spec>) -> bool {
    let Some(a) = anchor else { return false };
    let dist = |s: &Spec| match field {
        "lap_length_m" => (s.lap_length_m - spec.lap_length_m).abs(),
        "hall" => (s.hall_x_m - spec.hall_x_m).abs(),
        "corridor_width_m" => (s.corridor_width_m - spec.corridor_width_m).abs(),
        _ => 0.0,
    };
    dist(p) >= dist(a)
}

/// Search the nearest specs that build (see the module doc). `deadline` bounds the whole
/// search; the probes and their order never depend on time, only how far it gets.
pub fn nearest_specs(
    spec: &Spec,
    cfg: &ConstructorConfig,
    seed: u64,
    deadline: &Deadline,
) -> NearestReport {
    let directions: [(&'static str, Vec<Spec>); 4] = [
        ("lap_length_m", lap_probes(spec)),
        ("hall", hall_probes(spec)),
        ("corridor_width_m", width_probes(spec)),
        ("features", feature_probes(spec)),
    ];
    // Per direction: the suggestion found and its rank (probe index; an anchor ranks
    // after every probe, so any probe that builds replaces it).
    let mut found: [Option<(usize, Suggestion)>; 4] = [None, None, None, None];
    let mut probes = 0;
    let anchors = anchors(spec, cfg);
    let mut attempt =
        |i: usize, rank: usize, p: &Spec, found: &mut [Option<(usize, Suggestion)>; 4]| {
            probes += 1;
            if let Some((s, k)) = builds(p, cfg, seed, deadline) {
                found[i] = Some((
                    rank,
                    Suggestion {
                        field: directions[i].0,
                        spec: p.clone(),
                        seed: s,
                        candidate_index: k,
                    },
                ));
            }
        };
    for (i, anchor) in anchors.iter().enumerate() {
        if let Some(p) = anchor {
            if deadline.stopped().is_some() {
                break;
            }
            attempt(i, usize::MAX, p, &mut found);
        }
    }
    let rounds = directions.iter().map(|d| d.1.len()).max().unwrap_or(0);
    'outer: for r in 0..rounds {
        for (i, (field, list)) in directions.iter().enumerate() {
            if found[i].as_ref().is_some_and(|(rank, _)| *rank <= r) {
                continue;
            }
            let Some(p) = list.get(r) else {
                continue;
            };
            // Past the anchor: a probe farther than the anchor that built is no nearer.
            if found[i].is_some() && beyond_anchor(field, spec, p, anchors[i].as_ref()) {
                continue;
            }
            // A lap above the anchor's fill only gets harder when lengthened.
            if i == 0 && anchors[0].is_some() && p.lap_length_m > spec.lap_length_m {
                continue;
            }
            if deadline.stopped().is_some() {
                break 'outer;
            }
            attempt(i, r, p, &mut found);
        }
    }
    NearestReport {
        suggestions: found.into_iter().flatten().map(|(_, g)| g).collect(),
        probes,
        exhausted: deadline.stopped().is_some(),
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
            direction: crate::generate::spec::Direction::Counterclockwise,
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
        assert_eq!(laps[..4], [56.0, 64.0, 53.0, 67.0]);
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
    fn anchors_put_the_lap_at_half_of_l_max() {
        let cfg = ConstructorConfig::default();
        let s = spec(110.0, 0.8, 16.0, 12.0, 1, 0, 0);
        let [lap, hall, width, feats] = anchors(&s, &cfg);
        let fill = |p: &Spec| p.lap_length_m / derive(p, &cfg).l_max;
        for a in [&lap, &hall] {
            let a = a.as_ref().expect("an anchor");
            assert!((0.4..=0.5).contains(&fill(a)), "{a:?}: {}", fill(a));
        }
        let hall = hall.unwrap();
        assert!((hall.hall_x_m / hall.hall_y_m - 16.0 / 12.0).abs() < 0.05);
        // No corridor of at least 0.2 m halves this fill; no feature anchor.
        assert!(width.is_none() && feats.is_none());
        let w = anchors(&spec(80.0, 1.5, 20.0, 15.0, 0, 0, 0), &cfg)[2].clone();
        assert!(w.is_some_and(|w| fill(&w) <= 0.5 && w.corridor_width_m < 1.5));
        // A lap already under half of L_max has no anchors.
        assert!(anchors(&spec(30.0, 1.5, 20.0, 15.0, 0, 0, 0), &cfg)
            .iter()
            .all(Option::is_none));
    }

    #[test]
    fn dropped_features_leave_the_order_of_the_rest() {
        use FeatureKind::*;
        let mut s = spec(60.0, 1.0, 20.0, 15.0, 2, 1, 0);
        s.feature_order = vec![Hairpin, Chicane, Hairpin];
        let probes = feature_probes(&s);
        assert_eq!((probes[0].hairpins, probes[0].chicanes), (2, 0));
        assert_eq!(probes[0].feature_order, vec![Hairpin, Hairpin]);
        let p = probes
            .iter()
            .find(|p| (p.hairpins, p.chicanes) == (1, 1))
            .expect("one hairpin dropped");
        assert_eq!(p.feature_order, vec![Hairpin, Chicane]);
    }

    #[test]
    fn a_failed_long_lap_gets_suggestions_that_build_again() {
        // 60 m at w = 0.8 m in 12 × 9 m (fill 0.87): a sweep miss.
        let s = spec(60.0, 0.8, 12.0, 9.0, 0, 0, 0);
        let cfg = ConstructorConfig::default();
        let r = nearest_specs(&s, &cfg, 0, &Deadline::new(Some(60.0), None));
        assert!(!r.suggestions.is_empty(), "{r:?}");
        for g in &r.suggestions {
            match generate(&g.spec, &cfg, g.seed, &Deadline::default()).unwrap() {
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
