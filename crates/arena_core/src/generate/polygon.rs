//! The polygon constructor: a convex loop of free corner angles with the features as
//! short turn groups, for laps too short for the ring's rectangle (issue 15: "smaller
//! feature templates when the lap is short").
//!
//! The ring needs four 90° corners, each ≥ 3.5 r_c from the next same-sense turn (below
//! that the detector merges them into a hairpin; measured on a rounded rectangle), plus
//! that spacing around every feature. Here the loop turns through 360° at 1–6 corners of
//! any angle in [55°, 125°] (a rectangle half the time), and the features are turn groups
//! joined by short links:
//!
//! * hairpin: two 70–90° turns one short link apart (the detector merges them; below 90°
//!   the legs open away from it, so one hairpin and two corners make a trapezoid);
//! * chicane: two opposite 60–75° turns one short link apart;
//! * sweeper: a corner rounded with one arc of [`SWEEPER_ARC`] r_c.
//!
//! Every other pair of neighbouring turns is a *long* link (≥ [`LONG_STRAIGHT`] of
//! straight between the fillets), except that a chicane turn and an opposite-turning
//! corner next to it may be short. With every heading fixed, the loop's end point and
//! length are linear in the segment lengths: each segment gets its least length, and the
//! spare length is shared over the long segments so that the loop closes exactly at
//! length L ([`spare_shares`]). Hall fit (any rotation), direction and the analytic checks
//! are the caller's, as for the ring.
//!
//! When every drawn loop is longer than the lap and the spec asks for one hairpin and one
//! chicane, the candidate is the teardrop instead (`teardrop`), which needs one gap fewer.

use super::rounding::round_polygon_radii;
use super::spec::{Derived, Spec, STRAIGHT_CAP_MARGIN};
use super::teardrop;
use crate::geometry::polyline::extent;
use crate::track::features::FeatureKind;
use rand_chacha::rand_core::Rng;
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

/// Straight (in r_c) kept between the fillets of neighbouring turns that must stay apart,
/// drawn per candidate in this range: the detector merges same-sense turns closer than
/// 0.8 r_c after smoothing, which a rounded rectangle shows at a side of 3.5 r_c
/// (1.5 r_c of straight, the lower end); the analytic check and the raster validator
/// judge each candidate with the same detector.
pub const LONG_STRAIGHT: (f64, f64) = (1.5, 1.85);
/// Straight (in r_c) inside a hairpin: its two halves must merge into one turn.
const HAIRPIN_LINK: f64 = 0.1;
/// Straight (in r_c) between a chicane's two turns: under the detector's 0.8 r_c pairing
/// gap, but long enough that smoothing does not cancel the opposite curvatures.
const CHICANE_LINK: f64 = 0.3;
/// Chicane turn range (degrees), nominal; each must read ≥ 45° after smoothing (at a
/// 0.1 r_c link two 65° turns read as 37° and 49°).
const CHICANE_DEG: (f64, f64) = (60.0, 75.0);
/// Corner angles of the convex loop (degrees): a sweeper must read as 45–135°.
const CORNER_DEG: (f64, f64) = (55.0, 125.0);
/// Sweeper fillet radius (in r_c): one arc whose peak radius the detector reads ≥ 1.5 r_c
/// (10 % margin for the raster), cheaper in a short lap than the ring's chamfer (two
/// 45° arcs of 2 r_c on 1.5 r_c legs).
const SWEEPER_ARC: f64 = 1.65;
/// Largest amount each hairpin half turns less than 90° (rad, 20°: the merged turn stays
/// ≥ 140°, above the detector's 135°; the analytic check reads it as the validator does).
const HAIRPIN_NARROW: f64 = 0.35;
/// Why a turn sequence fails when its least length exceeds the lap.
const TOO_SHORT: &str = "polygon: lap too short for the turns";
/// Turn sequences drawn before a candidate gives up on closing.
const CLOSURE_DRAWS: usize = 256;
/// Most features the polygon places: it is for short laps, and the closure's triangle
/// search is cubic in the number of segments (≤ 2 · 12 + 6 here).
pub const MAX_FEATURES: usize = 12;

/// One turn of the polygon: signed angle (rad, + = left), sweeper flag, and the straight
/// (in r_c) of a short link to the next turn (inside a feature), `None` for a long link.
#[derive(Debug, Clone, Copy)]
struct Turn {
    angle: f64,
    sweeper: bool,
    short_next: Option<f64>,
}

/// Fillet radius of a turn (m): r_c, or [`SWEEPER_ARC`] r_c for a sweeper.
fn radius(t: &Turn, rc: f64) -> f64 {
    if t.sweeper {
        SWEEPER_ARC * rc
    } else {
        rc
    }
}

/// Length a turn's fillet takes from each adjacent segment (m).
fn tangent(t: &Turn, rc: f64) -> f64 {
    radius(t, rc) * (t.angle.abs() / 2.0).tan()
}

/// Length the fillet removes from the polygon at one turn (m).
fn saving(t: &Turn, rc: f64) -> f64 {
    let a = t.angle.abs();
    radius(t, rc) * (2.0 * (a / 2.0).tan() - a)
}

fn uniform(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u32() as f64) / (u32::MAX as f64)
}

/// The turn sequence: features in `order` (counter-clockwise boundary order) with plain
/// corners between them, the corners sharing what the hairpins leave of 360°.
fn turns(order: &[FeatureKind], capped: bool, rng: &mut ChaCha8Rng) -> Option<Vec<Turn>> {
    let h = order.iter().filter(|&&k| k == FeatureKind::Hairpin).count();
    let s = order.iter().filter(|&&k| k == FeatureKind::Sweeper).count();
    if h > 2 || order.len() > MAX_FEATURES {
        return None;
    }
    // Each hairpin turns 180° less 2δ, so the legs open away from it (a lone hairpin
    // with two plain corners is a trapezoid; at 180° it would be a rectangle whose other
    // end is a second hairpin).
    let narrow: Vec<f64> = (0..h).map(|_| HAIRPIN_NARROW * uniform(rng)).collect();
    let corner_turn = 2.0 * PI - h as f64 * PI + 2.0 * narrow.iter().sum::<f64>();
    let angles = corner_angles(corner_turn, s, capped, rng)?;
    // Slots: the features in order, the plain corners spread between them at random.
    let plain = angles.len() - s;
    let mut items: Vec<Option<FeatureKind>> = order.iter().map(|&f| Some(f)).collect();
    for _ in 0..plain {
        let at = (rng.next_u32() as usize) % (items.len() + 1);
        items.insert(at, None);
    }
    let mut out = slot_turns(&items, angles, narrow, rng)?;
    shorten_links_after_chicanes(&mut out, rng);
    (out.len() >= 3).then_some(out)
}

/// The corners' angles (sweepers among them, at least `sweepers`): a count `k` whose
/// equal share of `corner_turn` lies in the corner band is drawn, then half the time
/// the angles are perturbed pairwise (sum kept) within the band. `None` if no count
/// fits, or sweepers are asked for with nothing left to turn.
fn corner_angles(
    corner_turn: f64,
    sweepers: usize,
    capped: bool,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<f64>> {
    let (lo, hi) = (CORNER_DEG.0.to_radians(), CORNER_DEG.1.to_radians());
    // Corners k (sweepers among them) with corner_turn / k inside the corner band.
    let ks: Vec<usize> = (sweepers.max(1)..=6)
        .filter(|&k| corner_turn / k as f64 >= lo && corner_turn / k as f64 <= hi)
        .collect();
    let k = if corner_turn <= 1e-9 {
        if sweepers > 0 {
            return None;
        }
        0
    } else {
        // Fewer corners leave more of a short lap to the features: the least of two
        // draws favours them; under a straight cap more corners keep the sides short,
        // so the greater of two draws.
        let m = ks.len().max(1);
        let (a, b) = ((rng.next_u32() as usize) % m, (rng.next_u32() as usize) % m);
        let pick = if capped { a.max(b) } else { a.min(b) };
        *ks.get(pick)?
    };
    let mut angles = vec![corner_turn / k.max(1) as f64; k];
    // Half the time the corners keep equal angles: four 90° corners make a rectangle,
    // the shape that holds the most lap in a rectangular hall.
    let perturb = if rng.next_u32() % 2 == 0 { k } else { 0 };
    for _ in 0..perturb {
        let (i, j) = ((rng.next_u32() as usize) % k, (rng.next_u32() as usize) % k);
        let d = (uniform(rng) - 0.5) * 0.5;
        if i != j && (lo..=hi).contains(&(angles[i] + d)) && (lo..=hi).contains(&(angles[j] - d)) {
            angles[i] += d;
            angles[j] -= d;
        }
    }
    Some(angles)
}

/// The turns of the slots in order: a hairpin is two turns of 90° − δ (its `narrow`
/// δ), a chicane two opposite turns of a drawn angle, a sweeper or a plain corner one
/// turn of the next corner angle.
fn slot_turns(
    items: &[Option<FeatureKind>],
    angles: Vec<f64>,
    narrow: Vec<f64>,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Turn>> {
    let mut out = Vec::new();
    let mut corner = angles.into_iter();
    let mut narrow = narrow.into_iter();
    for &it in items {
        match it {
            Some(FeatureKind::Hairpin) => {
                let d = narrow.next()?;
                out.push(Turn {
                    angle: PI / 2.0 - d,
                    sweeper: false,
                    short_next: Some(HAIRPIN_LINK),
                });
                out.push(Turn {
                    angle: PI / 2.0 - d,
                    sweeper: false,
                    short_next: None,
                });
            }
            Some(FeatureKind::Chicane) => {
                let a =
                    (CHICANE_DEG.0 + (CHICANE_DEG.1 - CHICANE_DEG.0) * uniform(rng)).to_radians();
                let sgn = if rng.next_u32() % 2 == 0 { 1.0 } else { -1.0 };
                out.push(Turn {
                    angle: sgn * a,
                    sweeper: false,
                    short_next: Some(CHICANE_LINK),
                });
                out.push(Turn {
                    angle: -sgn * a,
                    sweeper: false,
                    short_next: None,
                });
            }
            Some(FeatureKind::Sweeper) | None => out.push(Turn {
                angle: corner.next()?,
                sweeper: it.is_some(),
                short_next: None,
            }),
        }
    }
    Some(out)
}

/// A chicane turn and the plain corner beyond it turn opposite ways: the link between
/// them may be short too (the detector pairs the chicane's own turns first, so the
/// count stays one), which is what lets a chicane into a 20 m lap. Drawn for 3 in 4.
fn shorten_links_after_chicanes(out: &mut [Turn], rng: &mut ChaCha8Rng) {
    let n = out.len();
    for i in 0..n {
        let j = (i + 1) % n;
        if out[i].short_next.is_none()
            && out[i].angle * out[j].angle < 0.0
            && rng.next_u32() % 4 != 0
        {
            out[i].short_next = Some(CHICANE_LINK);
        }
    }
}

/// Share of the spare length per long segment that closes the loop: weights `λ ≥ 0`,
/// `Σ λ = 1`, `Σ λ_i u_i = c` (the closing direction `c`, |c| ≤ 1). Every triangle of
/// segment directions that contains `c` gives one solution (its barycentric weights);
/// a random convex mix of them is another. `None` if no triangle contains `c`.
fn spare_shares(u: &[[f64; 2]], c: [f64; 2], rng: &mut ChaCha8Rng) -> Option<Vec<f64>> {
    let n = u.len();
    let mut mix = vec![0.0; n];
    let mut total = 0.0;
    for a in 0..n {
        for b in a + 1..n {
            for k in b + 1..n {
                let (p, q, r) = (u[a], u[b], u[k]);
                let det = (q[0] - p[0]) * (r[1] - p[1]) - (r[0] - p[0]) * (q[1] - p[1]);
                if det.abs() < 1e-9 {
                    continue;
                }
                let lb = ((c[0] - p[0]) * (r[1] - p[1]) - (r[0] - p[0]) * (c[1] - p[1])) / det;
                let lk = ((q[0] - p[0]) * (c[1] - p[1]) - (c[0] - p[0]) * (q[1] - p[1])) / det;
                let la = 1.0 - lb - lk;
                if la < 0.0 || lb < 0.0 || lk < 0.0 {
                    continue;
                }
                let w = 0.05 + uniform(rng);
                mix[a] += w * la;
                mix[b] += w * lb;
                mix[k] += w * lk;
                total += w;
            }
        }
    }
    (total > 0.0).then(|| mix.iter().map(|x| x / total).collect())
}

/// Segment headings and lengths for turn sequence `t`: every segment at least its least
/// length, the loop closed and `lap` long once rounded.
fn lengths(
    t: &[Turn],
    lap: f64,
    rc: f64,
    cap: Option<f64>,
    rng: &mut ChaCha8Rng,
) -> Result<(Vec<f64>, Vec<f64>), &'static str> {
    let n = t.len();
    // Segment i runs from turn i to turn i + 1; its least length and its heading.
    let mut heading = Vec::with_capacity(n);
    let mut h = 0.0f64;
    for ti in t {
        h += ti.angle;
        heading.push(h);
    }
    let long_gap = LONG_STRAIGHT.0 + (LONG_STRAIGHT.1 - LONG_STRAIGHT.0) * uniform(rng);
    let min_len: Vec<f64> = (0..n)
        .map(|i| {
            let gap = t[i].short_next.unwrap_or(long_gap);
            tangent(&t[i], rc) + tangent(&t[(i + 1) % n], rc) + gap * rc
        })
        .collect();
    let target = lap + t.iter().map(|x| saving(x, rc)).sum::<f64>();
    let spare = target - min_len.iter().sum::<f64>();
    if spare < 0.0 {
        return Err(TOO_SHORT);
    }
    let long: Vec<usize> = (0..n).filter(|&i| t[i].short_next.is_none()).collect();
    let dir = |i: usize| [heading[i].cos(), heading[i].sin()];
    // At least lengths the loop ends at `end`; the spare length, shared over the long
    // segments, must bring it back: Σ x_i u_i = −end with Σ x_i = spare, x ≥ 0.
    let mut end = [0.0f64; 2];
    for (i, l) in min_len.iter().enumerate() {
        end[0] += l * dir(i)[0];
        end[1] += l * dir(i)[1];
    }
    if spare <= 1e-9 {
        return Err(TOO_SHORT);
    }
    let c = [-end[0] / spare, -end[1] / spare];
    let u: Vec<[f64; 2]> = long.iter().map(|&i| dir(i)).collect();
    let shares =
        spare_shares(&u, c, rng).ok_or("polygon: the spare length cannot close the loop")?;
    let mut len = min_len;
    for (j, &i) in long.iter().enumerate() {
        len[i] += spare * shares[j];
    }
    // The speed cap: every straight between two fillets stays under it (another draw
    // shares the spare length differently).
    if let Some(cap) = cap {
        let over = (0..n).any(|i| {
            len[i] - tangent(&t[i], rc) - tangent(&t[(i + 1) % n], rc) > STRAIGHT_CAP_MARGIN * cap
        });
        if over {
            return Err("polygon: a straight above the cap");
        }
    }
    Ok((heading, len))
}

/// Candidate of the polygon constructor: a closed, rounded, counter-clockwise centreline
/// of length `spec.lap_length_m`. Hall fit, direction and the analytic checks are the
/// caller's.
pub fn polygon_candidate(
    spec: &Spec,
    d: &Derived,
    order: &[FeatureKind],
    rng: &mut ChaCha8Rng,
) -> Result<(Vec<[f64; 2]>, f64), &'static str> {
    let rc = d.corner_radius;
    // Each draw takes new corner angles, hairpin widening and spare shares: the closure
    // of a loop with long legs holds only for some of them.
    let mut why = "polygon: features do not fit a convex loop";
    let mut found = None;
    // Draws whose turn sequence was too long for the lap, of those that drew one.
    let (mut drawn, mut short) = (0, 0);
    for _ in 0..CLOSURE_DRAWS {
        let Some(t) = turns(order, spec.max_straight_m.is_some(), rng) else {
            continue;
        };
        drawn += 1;
        match lengths(&t, spec.lap_length_m, rc, spec.max_straight_m, rng) {
            Ok((heading, len)) => {
                found = Some((t, heading, len));
                break;
            }
            Err(e) => {
                short += usize::from(e == TOO_SHORT);
                why = e;
            }
        }
    }
    let Some((t, heading, len)) = found else {
        // Every drawn loop was longer than the lap: one hairpin and one chicane still fit
        // the teardrop, which needs one gap fewer (its module says why).
        if drawn > 0 && short == drawn && teardrop::holds(spec) {
            let (line, pitch) = teardrop::teardrop_loop(spec, d, rng)?;
            return Ok((best_fit_rotation(&line, spec), pitch));
        }
        return Err(why);
    };
    // Turtle: vertex i is where turn i happens; segment i leaves it.
    let mut verts = Vec::with_capacity(t.len());
    let mut p = [0.0f64, 0.0];
    for (l, h) in len.iter().zip(&heading) {
        verts.push(p);
        p = [p[0] + l * h.cos(), p[1] + l * h.sin()];
    }
    if p[0].hypot(p[1]) > 1e-6 {
        return Err("polygon: loop does not close");
    }
    let radii: Vec<f64> = t.iter().map(|x| radius(x, rc)).collect();
    let line = round_polygon_radii(&verts, &radii, 0.02).ok_or("fillets overlap")?;
    Ok((best_fit_rotation(&line, spec), d.s_min))
}

/// Rotate the loop to the angle (3° steps over 90°) whose bounding box leaves the most
/// room in the hall, long side along the hall's long side.
fn best_fit_rotation(line: &[[f64; 2]], spec: &Spec) -> Vec<[f64; 2]> {
    let (hl, hs) = (
        spec.hall_x_m.max(spec.hall_y_m),
        spec.hall_x_m.min(spec.hall_y_m),
    );
    let rot = |a: f64| -> Vec<[f64; 2]> {
        let (s, c) = a.sin_cos();
        line.iter()
            .map(|q| [c * q[0] - s * q[1], s * q[0] + c * q[1]])
            .collect()
    };
    let slack = |a: f64| {
        let e = extent(&rot(a));
        let (l, s) = (e[0].max(e[1]), e[0].min(e[1]));
        (hl - l).min(hs - s)
    };
    let best = (0..30)
        .map(|i| (i as f64 * 3.0).to_radians())
        .max_by(|a, b| slack(*a).total_cmp(&slack(*b)))
        .unwrap_or(0.0);
    rot(best)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::spec::{derive, ConstructorConfig};
    use rand_chacha::rand_core::SeedableRng;

    fn spec(l: f64, w: f64, h: u32, c: u32, s: u32) -> Spec {
        Spec {
            name: "p".into(),
            lap_length_m: l,
            corridor_width_m: w,
            hall_x_m: 20.0,
            hall_y_m: 15.0,
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
    fn loops_close_at_the_lap_length_with_the_requested_turns() {
        use crate::geometry::{polyline_length, signed_area};
        let cases = [
            (30.0, 1.5, vec![FeatureKind::Chicane]),
            (20.0, 1.5, vec![FeatureKind::Chicane]),
            (30.0, 2.0, vec![FeatureKind::Hairpin]),
            (40.0, 1.0, vec![FeatureKind::Sweeper, FeatureKind::Hairpin]),
            (40.0, 1.5, vec![]),
        ];
        for (l, w, order) in cases {
            let s = spec(l, w, 0, 0, 0);
            let d = derive(&s, &ConstructorConfig::default());
            let mut built = 0;
            for k in 0..20 {
                let mut rng = ChaCha8Rng::seed_from_u64(k);
                if let Ok((line, _)) = polygon_candidate(&s, &d, &order, &mut rng) {
                    let got = polyline_length(&line, true);
                    assert!((got - l).abs() < 0.02, "{l} m {order:?}: {got}");
                    assert!(signed_area(&line) > 0.0, "counter-clockwise");
                    built += 1;
                }
            }
            assert!(built > 0, "{l} m, w {w}, {order:?}: no loop in 20 draws");
        }
    }

    #[test]
    fn a_lap_too_short_for_every_loop_falls_back_to_the_teardrop_only_with_a_hairpin() {
        // 20 m at w = 2 m with a chicane: every polygon loop needs > 20.6 m.
        use crate::geometry::polyline_length;
        let order = [FeatureKind::Hairpin, FeatureKind::Chicane];
        let s = spec(20.0, 2.0, 1, 1, 0);
        let d = derive(&s, &ConstructorConfig::default());
        let built = (0..5)
            .filter_map(|k| {
                polygon_candidate(&s, &d, &order, &mut ChaCha8Rng::seed_from_u64(k)).ok()
            })
            .inspect(|(line, _)| {
                let l = polyline_length(line, true);
                assert!(
                    (20.0..=20.0 * (1.0 + teardrop::LONG_SLACK) + 0.01).contains(&l),
                    "{l}"
                );
            })
            .count();
        assert!(built > 0);
        // Without a hairpin the teardrop does not apply: the polygon's own reason stays.
        let s = spec(20.0, 2.0, 0, 1, 0);
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        let got = polygon_candidate(&s, &d, &[FeatureKind::Chicane], &mut rng);
        assert_eq!(got.err(), Some(TOO_SHORT));
    }

    #[test]
    fn three_hairpins_too_many_features_or_a_sweeper_without_a_corner_are_refused() {
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        assert!(turns(&[FeatureKind::Hairpin; 3], false, &mut rng).is_none());
        assert!(turns(&[FeatureKind::Chicane; MAX_FEATURES + 1], false, &mut rng).is_none());
        let two_and_sweeper = [
            FeatureKind::Hairpin,
            FeatureKind::Hairpin,
            FeatureKind::Sweeper,
        ];
        assert!(turns(&two_and_sweeper, false, &mut rng).is_none());
    }
}
