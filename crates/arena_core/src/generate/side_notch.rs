//! The ring's last resort for a lap too long for its comb: two shallow notches in the
//! long side under one notch from the short side that runs across the hall. It holds no
//! features, or one chicane (a step in the top side) with at most two hairpins (the side
//! notch, then the first bottom notch, one feature edge wide, so their tip corners merge)
//! and at most one sweeper (the bottom-left corner, chamfered as the ring's).
//!
//! The comb holds two plain notches in a 17.9 m side (three need four gaps and three
//! widths of ≥ 3.5 r_c each), and notches from both long sides need more length than the
//! side has: of a 110 m lap at w = 0.8 m in a 20 × 15 m hall the comb holds ≈ 103 m, and
//! the validator wants ≥ 106.7 m. Here the short
//! side's notch takes most of the hall's length, and the long side's two notches stay
//! under it, one pitch below its lower leg:
//!
//! ```text
//!  +-----------------------------+
//!  |  +--------------------------+  ← the side notch, `dr` deep, one gap wide
//!  |  +--------------------------+
//!  |     +--+          +--+      |  ← two notches `du` deep, one gap wide
//!  +-----+  +----------+  +------+
//! ```
//!
//! Same-sense corners stay [`GAP`] r_c apart (centre to centre, so the detector keeps
//! them apart), passes one pitch (plus [`CLEAR`]) apart. The lap is exact when the shape
//! holds it, else as long as the shape allows down to [`SHORT_SLACK`] below L (the
//! validator allows 3 %).

use super::rounding::{round_polygon, savings};
use super::spec::{Derived, Spec};
use rand_chacha::rand_core::Rng;
use rand_chacha::ChaCha8Rng;

/// Corner spacing, centre to centre, in r_c: drawn in this range (1.6–1.8 r_c of
/// straight between the fillets; the detector merges plain 90° arcs at 1.5 r_c). A lap
/// at the shape's limit fits only the tighter draws; the others are refused.
const GAP: (f64, f64) = (3.6, 3.8);
/// Feature edge (hairpin width, chicane step) as a multiple of `s_min`, the ring's
/// smallest: its two turns merge (hairpin) or pair (chicane) in the detector.
const FEATURE_EDGE: f64 = 1.05;
/// Room (in r_c) a sweeper corner's chamfer takes from each adjacent side (the ring's).
const SWEEPER_ROOM: f64 = 1.6;
/// Extra clearance between parallel passes, as a share of the pitch.
const CLEAR: f64 = 0.02;
/// Largest relative shortfall of the lap: two thirds of the validator's 3 %.
pub const SHORT_SLACK: f64 = 0.02;

/// Candidate centreline (counter-clockwise, in the centreline box `ux` × `uy`, `ux ≥ uy`)
/// and its feature edge.
pub fn side_notch_loop(
    spec: &Spec,
    d: &Derived,
    ux: f64,
    uy: f64,
    rng: &mut ChaCha8Rng,
) -> Result<(Vec<[f64; 2]>, f64), &'static str> {
    // Featureless, or one chicane (a step in the top side) with at most one hairpin (the
    // side notch one feature edge wide). A lone hairpin stays with the comb, which
    // deepens it.
    let (hairpin, chicane, sweeper) = (spec.hairpins >= 1, spec.chicanes == 1, spec.sweepers == 1);
    let features = spec.hairpins + spec.chicanes + spec.sweepers;
    if features > 0 && !chicane || spec.hairpins > 2 || spec.chicanes > 1 || spec.sweepers > 1 {
        return Err("ring: no notch count fits the lap");
    }
    let rc = d.corner_radius;
    let u = (rng.next_u32() % 1000) as f64 / 999.0;
    let g = (GAP.0 + (GAP.1 - GAP.0) * u) * rc;
    let p = d.pitch * (1.0 + CLEAR);
    let e = FEATURE_EDGE * d.s_min;
    let (x, y) = (ux, uy);
    // Heights: the long side's notches `du` deep, one pitch under the side notch (`wr`
    // wide), one gap under the top side; with a chicane the top side's left part steps
    // down by `e` and stays one pitch above the side notch.
    let wr = if hairpin { e } else { g };
    let mut du_max = y - g - wr - p;
    if chicane {
        du_max = du_max.min(y - e - wr - 2.0 * p);
    }
    let dr_max = x - p;
    // Legs at least one gap long (no chicane).
    if du_max < g {
        return Err("ring: side notch does not fit the hall");
    }
    // A second hairpin is the first bottom notch one feature edge wide; a sweeper is the
    // bottom-left corner, chamfered, with the ring's room on its sides.
    let w1 = if spec.hairpins == 2 { e } else { g };
    let room = if sweeper { SWEEPER_ROOM * rc } else { 0.0 };
    if x < 4.0 * g + w1 + room {
        return Err("ring: side notch does not fit the hall");
    }
    let corners = if chicane { 18.0 } else { 16.0 };
    let (o, sw) = savings(rc);
    let n_sw = if sweeper { 1.0 } else { 0.0 };
    let saved = (corners - n_sw) * o + n_sw * sw;
    let length = |du: f64, dr: f64| 2.0 * (x + y) + 4.0 * du + 2.0 * dr - saved;
    let lap = spec.lap_length_m;
    let longest = length(du_max, dr_max);
    if longest < lap * (1.0 - SHORT_SLACK) {
        return Err("ring: side notch too short for the lap");
    }
    // The side notch gives up length first (it stays at least half the hall long).
    let dr = ((lap - length(du_max, 0.0)) / 2.0).clamp(x / 2.0, dr_max);
    let du = ((lap - length(0.0, dr)) / 4.0).clamp(g, du_max);
    if (length(du, dr) - lap).abs() > lap * SHORT_SLACK && length(du, dr) > lap {
        return Err("ring: side notch too long for the lap");
    }
    let (x1, x2) = (g + room, x - 2.0 * g);
    let y1 = du + p;
    let mut verts = vec![
        [0.0, 0.0],
        [x1, 0.0],
        [x1, du],
        [x1 + w1, du],
        [x1 + w1, 0.0],
        [x2, 0.0],
        [x2, du],
        [x2 + g, du],
        [x2 + g, 0.0],
        [x, 0.0],
        [x, y1],
        [x - dr, y1],
        [x - dr, y1 + wr],
        [x, y1 + wr],
        [x, y],
    ];
    if chicane {
        // The step: a left and a right turn one feature edge apart, a gap or more from
        // the corners either side.
        let xs = x / 2.0;
        verts.extend([[xs, y], [xs, y - e], [0.0, y - e]]);
    } else {
        verts.push([0.0, y]);
    }
    let mut is_sweeper = vec![false; verts.len()];
    is_sweeper[0] = sweeper;
    let line = round_polygon(&verts, &is_sweeper, rc, 0.02).ok_or("fillets overlap")?;
    Ok((line, d.s_min))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::construct::{generate, Outcome};
    use crate::generate::deadline::Deadline;
    use crate::generate::spec::{centreline_box, derive, ConstructorConfig};
    use crate::geometry::{polyline_length, signed_area};
    use rand_chacha::rand_core::SeedableRng;

    fn spec(l: f64, hx: f64, hy: f64) -> Spec {
        Spec::plain(l, 0.8, hx, hy)
    }

    #[test]
    fn a_110_m_featureless_lap_in_20_by_15_m_builds_and_validates() {
        // The sweep's miss at fill 0.5997: the comb holds ≈ 102.8 m, the side notch ≈ 108 m.
        let s = spec(110.0, 20.0, 15.0);
        let cfg = ConstructorConfig::default();
        let d = derive(&s, &cfg);
        let [bx, by] = centreline_box(&s, &cfg);
        // Only the tighter corner spacings hold it: some draws are refused.
        let mut built = 0;
        for seed in 0..20 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            if let Ok((line, _)) = side_notch_loop(&s, &d, bx.max(by), bx.min(by), &mut rng) {
                let l = polyline_length(&line, true);
                assert!((110.0 * (1.0 - SHORT_SLACK)..=110.0).contains(&l), "{l}");
                assert!(signed_area(&line) > 0.0);
                built += 1;
            }
        }
        assert!(built > 0);
        match generate(&s, &cfg, 1, &Deadline::default()).unwrap() {
            Outcome::Accepted { report, .. } => assert!(report.valid),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_hairpin_and_a_chicane_fit_the_shape_and_features_without_a_chicane_do_not() {
        // The hairpin is the side notch one feature edge wide, the chicane a step in the top.
        let mut s = spec(110.0, 20.0, 15.0);
        (s.hairpins, s.chicanes) = (1, 1);
        let cfg = ConstructorConfig::default();
        match generate(&s, &cfg, 0, &Deadline::default()).unwrap() {
            Outcome::Accepted { report, .. } => assert!(report.valid),
            other => panic!("{other:?}"),
        }
        let d = derive(&s, &cfg);
        let [bx, by] = centreline_box(&s, &cfg);
        for (h, c, sw) in [(1, 0, 0), (0, 0, 1), (3, 1, 0), (0, 2, 0), (2, 1, 2)] {
            (s.hairpins, s.chicanes, s.sweepers) = (h, c, sw);
            let mut rng = ChaCha8Rng::seed_from_u64(0);
            assert!(side_notch_loop(&s, &d, bx.max(by), bx.min(by), &mut rng).is_err());
        }
    }

    #[test]
    fn a_lap_beyond_the_shape_or_a_small_hall_is_refused() {
        let cfg = ConstructorConfig::default();
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        for s in [spec(115.0, 20.0, 15.0), spec(40.0, 8.0, 6.0)] {
            let d = derive(&s, &cfg);
            let [bx, by] = centreline_box(&s, &cfg);
            assert!(side_notch_loop(&s, &d, bx.max(by), bx.min(by), &mut rng).is_err());
        }
    }
}
