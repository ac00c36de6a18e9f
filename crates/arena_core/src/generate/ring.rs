//! The ring constructor: a rounded rectangle of free side lengths with the requested
//! features inserted on its sides and corners (the "obvious construction" the lattice
//! misses when the hall leaves only a few lattice cells).
//!
//! The lattice ties both sides of the loop to one pitch `s ∈ [s_min, 1.4 s_min]`, so a
//! 30 m lap in a 12 × 9 m hall has no lattice perimeter that fits. The ring keeps the
//! lattice's local feature patterns (so the same curvature detector sees the same
//! features) but lets the two side lengths `A × B` take any value:
//!
//! * hairpin: a one-edge notch, pushed in (`L, R, R, L`) or out (`R, L, L, R`); the two
//!   same-sense corners one feature edge `e` apart merge into a ≥ 180° turn;
//! * chicane: a one-edge step (`L, R` inwards or `R, L` outwards) of height `e`;
//! * sweeper: a corner of the rectangle cut by the rounding's 45° chamfer.
//!
//! Features keep at least two feature edges of straight between them and the corners,
//! as the lattice's two-edge rule does. The loop closes by construction: the top and left
//! sides absorb the chicane steps, and `A` follows from `L` in closed form once `B` is
//! drawn, because every corner's saving is known (see `rounding`).

use super::rounding::{round_polygon, savings};
use super::spec::{ConstructorConfig, Derived, Spec};
use crate::track::features::FeatureKind;
use rand_chacha::rand_core::Rng;
use rand_chacha::ChaCha8Rng;

/// One element inserted on a side, in the side's own frame (u forward, v to the left =
/// towards the infield of a counter-clockwise loop).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Insert {
    Hairpin { inward: bool },
    Chicane { inward: bool },
}

/// Feature edge `e` as a multiple of `s_min` (inside the lattice's pitch range, so the
/// detector's one-edge merge gap holds).
const EDGE_FACTORS: [f64; 3] = [1.05, 1.15, 1.3];
/// Run kept between features and corners, in feature edges: the lattice's two edges,
/// or less (the detector's merge gap is 0.8 r_c of straight; the validator judges).
const GAP_EDGES: [f64; 3] = [1.4, 1.6, 2.0];

/// A ring layout: inserts per side (counter-clockwise from the bottom side) and which
/// of the four corners (end of side i) are sweepers.
#[derive(Debug, Clone, Default)]
struct Layout {
    sides: [Vec<Insert>; 4],
    sweeper: [bool; 4],
}

/// Map the features onto 4 sides and 4 corners in cyclic driving order (counter-
/// clockwise boundary order). `None` if they do not fit (a sweeper needs a corner,
/// at most one per corner).
fn layout(order: &[FeatureKind], rng: &mut ChaCha8Rng, inward_bias: u32) -> Option<Layout> {
    let mut l = Layout::default();
    // Slots: side 0, corner 0, side 1, corner 1, ... ; start at a random side.
    let start = (rng.next_u32() % 4) as usize;
    let mut slot = 2 * start; // even = side, odd = corner
    let end = slot + 8;
    for &k in order {
        if k == FeatureKind::Sweeper {
            if slot % 2 == 0 {
                slot += 1;
            }
            if slot >= end {
                return None;
            }
            l.sweeper[(slot / 2) % 4] = true;
            slot += 1;
            continue;
        }
        // Hairpins and chicanes go on the current side or a later one; spread them so
        // no side holds far more than its share.
        if slot % 2 == 1 {
            slot += 1;
        }
        // Stay on this side or move on (order kept): sides fill at random.
        let here = l.sides[(slot / 2) % 4].len();
        if here > 0 && slot + 2 < end && rng.next_u32() % 100 < 60 {
            slot += 2;
        }
        if slot >= end {
            return None;
        }
        let inward = rng.next_u32() % 100 < inward_bias;
        let ins = match k {
            FeatureKind::Hairpin => Insert::Hairpin { inward },
            _ => Insert::Chicane { inward },
        };
        l.sides[(slot / 2) % 4].push(ins);
    }
    Some(l)
}

/// Turtle moves of one side: (run length, turn at its end: +1 left, −1 right, 0 none).
/// Gaps are the straights between inserts (len = inserts + 1).
fn side_moves(inserts: &[Insert], gaps: &[f64], e: f64, depth: f64, out: &mut Vec<(f64, i8)>) {
    for (i, ins) in inserts.iter().enumerate() {
        let g = gaps[i];
        match *ins {
            Insert::Hairpin { inward } => {
                let t: i8 = if inward { 1 } else { -1 };
                out.push((g, t));
                out.push((depth, -t));
                out.push((e, -t));
                out.push((depth, t));
            }
            Insert::Chicane { inward } => {
                let t: i8 = if inward { 1 } else { -1 };
                out.push((g, t));
                out.push((e, -t));
            }
        }
    }
    // The last gap runs into the corner; the caller adds the corner turn.
    out.push((gaps[inserts.len()], 0));
}

/// Net (u, v) displacement of a side's inserts (v: towards the infield).
fn inserts_uv(inserts: &[Insert], e: f64) -> (f64, f64) {
    inserts.iter().fold((0.0, 0.0), |(u, v), ins| match *ins {
        Insert::Hairpin { .. } => (u + e, v),
        Insert::Chicane { inward } => (u, v + if inward { e } else { -e }),
    })
}

/// Split `total` straight into `n + 1` gaps each ≥ `g_min`, the excess shared at random.
fn split_gaps(total: f64, n: usize, g_min: f64, rng: &mut ChaCha8Rng) -> Option<Vec<f64>> {
    let excess = total - (n as f64 + 1.0) * g_min;
    if excess < 0.0 {
        return None;
    }
    let w: Vec<f64> = (0..=n)
        .map(|_| 0.5 + (rng.next_u32() % 1000) as f64 / 1000.0)
        .collect();
    let sum: f64 = w.iter().sum();
    Some(w.iter().map(|x| g_min + excess * x / sum).collect())
}

/// Candidate `k` of the ring constructor: a closed, rounded, counter-clockwise centreline
/// of length `spec.lap_length_m`, and its feature edge. Hall fit, direction and the
/// analytic checks are the caller's (shared with the lattice).
pub fn ring_candidate(
    spec: &Spec,
    cfg: &ConstructorConfig,
    d: &Derived,
    order: &[FeatureKind],
    rng: &mut ChaCha8Rng,
) -> Result<(Vec<[f64; 2]>, f64), &'static str> {
    let rc = d.corner_radius;
    let e = d.s_min * EDGE_FACTORS[(rng.next_u32() as usize) % EDGE_FACTORS.len()];
    let depth = e * if rng.next_u32() % 3 == 0 { 1.5 } else { 1.0 };
    let lay = layout(order, rng, 75).ok_or("ring: features do not fit the ring's slots")?;
    let wall = spec.corridor_width_m + 2.0 * cfg.wall_thickness_m;
    let ux = spec.hall_x_m.max(spec.hall_y_m) - 2.0 * cfg.hall_margin_m - wall;
    let uy = spec.hall_x_m.min(spec.hall_y_m) - 2.0 * cfg.hall_margin_m - wall;
    let g_min = GAP_EDGES[(rng.next_u32() as usize) % GAP_EDGES.len()] * e;
    // Corner savings, and the polygon length the inserts add beyond A and B.
    let (o, sw) = savings(rc);
    let mut turns = 4usize;
    let mut extra = 0.0;
    let uv: Vec<(f64, f64)> = lay.sides.iter().map(|s| inserts_uv(s, e)).collect();
    for s in &lay.sides {
        for ins in s {
            match ins {
                Insert::Hairpin { .. } => {
                    turns += 4;
                    extra += 2.0 * depth;
                }
                Insert::Chicane { .. } => {
                    turns += 2;
                    extra += e;
                }
            }
        }
    }
    let n_sw = lay.sweeper.iter().filter(|&&b| b).count();
    let saved = (turns - n_sw) as f64 * o + n_sw as f64 * sw;
    // Side displacements U_i along each side: U0 = A, U1 = B; closure gives
    // U2 = A − V1 + V3 and U3 = B + V0 − V2. Perimeter = ΣU + extra.
    let (v0, v1, v2, v3) = (uv[0].1, uv[1].1, uv[2].1, uv[3].1);
    let k_ab = (spec.lap_length_m + saved - extra - (v3 - v1) - (v0 - v2)) / 2.0; // = A + B
                                                                                  // The short side B: drawn between what the inserts need and what the hall leaves.
    let b_hi = uy.min(k_ab - g_min);
    let b_lo = g_min;
    if b_hi <= b_lo {
        return Err("ring: hall too small for the lap");
    }
    let t = (rng.next_u32() % 1000) as f64 / 999.0;
    // Bias towards the full hall height (the straightest, roundest loop).
    let b = b_hi - (b_hi - b_lo) * t * t;
    let a = k_ab - b;
    let u = [a, b, a - v1 + v3, b + v0 - v2];
    let mut moves: Vec<(f64, i8)> = Vec::new();
    let mut side_ends = [0usize; 4];
    for i in 0..4 {
        let ins = &lay.sides[i];
        let straight = u[i] - uv[i].0;
        let gaps = split_gaps(straight, ins.len(), g_min, rng).ok_or("ring: side too short")?;
        side_moves(ins, &gaps, e, depth, &mut moves);
        let last = moves.len() - 1;
        moves[last].1 = 1; // the rectangle's corner (left turn)
        side_ends[i] = last;
    }
    // Turtle → polygon vertices (the point of every turn); sweeper flags on the
    // rectangle's corners (the turn that ends each side).
    let (mut p, mut h) = ([0.0f64, 0.0], (1.0f64, 0.0f64));
    let mut verts: Vec<[f64; 2]> = Vec::new();
    let mut is_sweeper: Vec<bool> = Vec::new();
    let mut run_acc = 0.0;
    for (j, &(run, turn)) in moves.iter().enumerate() {
        run_acc += run;
        if turn == 0 {
            continue;
        }
        p = [p[0] + h.0 * run_acc, p[1] + h.1 * run_acc];
        run_acc = 0.0;
        verts.push(p);
        h = if turn > 0 { (-h.1, h.0) } else { (h.1, -h.0) };
        is_sweeper.push(
            side_ends
                .iter()
                .position(|&x| x == j)
                .is_some_and(|c| lay.sweeper[c]),
        );
    }
    // The loop must close exactly (it does by construction; guard against rounding).
    let gap = [p[0] + h.0 * run_acc, p[1] + h.1 * run_acc];
    if gap[0].hypot(gap[1]) > 1e-6 || h != (1.0, 0.0) {
        return Err("ring: loop does not close");
    }
    let ext = extent(&verts);
    if !((ext[0] <= ux + 1e-9 && ext[1] <= uy + 1e-9)
        || (ext[1] <= ux + 1e-9 && ext[0] <= uy + 1e-9))
    {
        return Err("ring: hall fit");
    }
    let line = round_polygon(&verts, &is_sweeper, rc, 0.02).ok_or("fillets overlap")?;
    Ok((line, e))
}

fn extent(p: &[[f64; 2]]) -> [f64; 2] {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in p {
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    [hi[0] - lo[0], hi[1] - lo[1]]
}
