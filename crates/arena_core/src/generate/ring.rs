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
//! Features keep 1.7–2 feature edges of run between them and the corners (the lattice
//! keeps two), so the detector does not merge neighbouring turns. The loop closes by
//! construction: the top and left sides absorb the chicane steps, and `A` follows from
//! `L` in closed form once `B` is drawn, because every corner's saving is known (see
//! `rounding`). A lap longer than the hall's rectangle gets plain notches (wide U's with
//! four ordinary corners) in its long side, and inward hairpins are deepened, to one
//! depth that `L` fixes. A lap too long for any notch count gets the side-notch shape
//! instead when it is featureless or has a chicane (`side_notch`).

use super::rounding::{round_polygon, savings};
use super::spec::{centreline_box, ConstructorConfig, Derived, Spec};
use crate::geometry::polyline::extent;
use crate::track::features::FeatureKind;
use rand_chacha::rand_core::Rng;
use rand_chacha::ChaCha8Rng;

/// One element inserted on a side, in the side's own frame (u forward, v to the left =
/// towards the infield of a counter-clockwise loop).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Insert {
    /// A notch `width` wide and `depth` deep: a hairpin when `width` is one feature edge,
    /// a plain U (four ordinary corners, no feature) when it is two or more.
    Notch {
        inward: bool,
        width: f64,
        depth: f64,
    },
    Chicane {
        inward: bool,
    },
}

/// Feature edge `e` as a multiple of `s_min` (inside the lattice's pitch range, so the
/// detector's one-edge merge gap holds).
const EDGE_FACTORS: [f64; 3] = [1.05, 1.15, 1.3];
/// Run kept between features and corners, in feature edges: the lattice's two edges,
/// or less (the detector's merge gap is 0.8 r_c of straight; the validator judges).
const GAP_EDGES: [f64; 3] = [1.7, 1.85, 2.0];

/// Plain notches (on the long side) that lengthen a loop the hall cannot hold as a
/// rounded rectangle: at most this many, each `PLAIN_WIDTHS` feature edges wide (deep
/// at least one gap, so its corners stay ordinary).
const MAX_PLAIN_NOTCHES: u32 = 8;
/// Plain notch widths (and least depth) in feature edges: wide enough that the
/// detector's smoothing does not merge its corners into a hairpin or a chicane.
const PLAIN_WIDTHS: [f64; 3] = [1.8, 2.1, 2.5];

/// Largest relative shortfall of the lap the ring builds when the hall's rectangle
/// cannot hold L: a third of the validator's 3 % tolerance, the rest left to the raster.
pub const LAP_SLACK: f64 = 0.01;

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
fn layout(
    order: &[FeatureKind],
    rng: &mut ChaCha8Rng,
    inward_bias: u32,
    e: f64,
    depth: f64,
) -> Option<Layout> {
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
            FeatureKind::Hairpin => Insert::Notch {
                inward,
                width: e,
                depth,
            },
            _ => Insert::Chicane { inward },
        };
        l.sides[(slot / 2) % 4].push(ins);
    }
    Some(l)
}

/// Turtle moves of one side: (run length, turn at its end: +1 left, −1 right, 0 none).
/// Gaps are the straights between inserts (len = inserts + 1).
fn side_moves(inserts: &[Insert], gaps: &[f64], e: f64, out: &mut Vec<(f64, i8)>) {
    for (i, ins) in inserts.iter().enumerate() {
        let g = gaps[i];
        match *ins {
            Insert::Notch {
                inward,
                width,
                depth,
            } => {
                let t: i8 = if inward { 1 } else { -1 };
                out.push((g, t));
                out.push((depth, -t));
                out.push((width, -t));
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
        Insert::Notch { width, .. } => (u + width, v),
        Insert::Chicane { inward } => (u, v + if inward { e } else { -e }),
    })
}

/// Polygon length the inserts add beyond the four sides, and their number of turns.
fn inserts_extra(inserts: &[Insert], e: f64) -> (f64, usize) {
    inserts.iter().fold((0.0, 0), |(x, n), ins| match *ins {
        Insert::Notch { depth, .. } => (x + 2.0 * depth, n + 4),
        Insert::Chicane { .. } => (x + e, n + 2),
    })
}

/// Split `total` straight into `n + 1` gaps each ≥ `g_min`, the excess shared at random.
/// End gaps next to a sweeper corner get `sweeper_room` more (the chamfer's legs).
fn split_gaps(
    total: f64,
    n: usize,
    g_min: f64,
    ends: [f64; 2],
    rng: &mut ChaCha8Rng,
) -> Option<Vec<f64>> {
    let mut mins = vec![g_min; n + 1];
    mins[0] += ends[0];
    mins[n] += ends[1];
    let excess = total - mins.iter().sum::<f64>();
    if excess < 0.0 {
        return None;
    }
    let w: Vec<f64> = (0..=n)
        .map(|_| 0.5 + (rng.next_u32() % 1000) as f64 / 1000.0)
        .collect();
    let sum: f64 = w.iter().sum();
    Some(
        mins.iter()
            .zip(&w)
            .map(|(m, x)| m + excess * x / sum)
            .collect(),
    )
}

/// Least length side `i` needs along its own direction (gaps, notch widths, sweeper room).
fn side_need(inserts: &[Insert], e: f64, g_min: f64, ends: [f64; 2]) -> f64 {
    (inserts.len() as f64 + 1.0) * g_min + ends[0] + ends[1] + inserts_uv(inserts, e).0
}

/// The lengths one ring candidate draws up front, and the layout arithmetic built on
/// them (the loop's length and each side's floor, for any layout and sides A, B).
struct RingSizes {
    /// Feature edge (m): a hairpin's width, a chicane's step.
    e: f64,
    /// Least run between inserts and next to the corners (m).
    g_min: f64,
    /// Length one ordinary corner and one sweeper corner save by rounding (`savings`).
    saving: (f64, f64),
    /// Room a sweeper corner's chamfer takes from each adjacent side.
    sweeper_room: f64,
}

impl RingSizes {
    /// Extra room at the start and at the end of side `i` (a sweeper chamfer's legs).
    fn ends(&self, i: usize, l: &Layout) -> [f64; 2] {
        [
            if l.sweeper[(i + 3) % 4] {
                self.sweeper_room
            } else {
                0.0
            },
            if l.sweeper[i] { self.sweeper_room } else { 0.0 },
        ]
    }

    /// Length of the rounded loop for sides A (0, 2) and B (1, 3): U0 = A, U1 = B;
    /// closure gives U2 = A − V1 + V3 and U3 = B + V0 − V2; length = ΣU + inserts −
    /// savings.
    fn length(&self, l: &Layout, a: f64, b: f64) -> f64 {
        let (o, sw) = self.saving;
        let mut turns = 4usize;
        let mut extra = 0.0;
        for s in &l.sides {
            let (x, n) = inserts_extra(s, self.e);
            extra += x;
            turns += n;
        }
        let v: Vec<f64> = l.sides.iter().map(|s| inserts_uv(s, self.e).1).collect();
        let n_sw = l.sweeper.iter().filter(|&&b| b).count();
        let saved = (turns - n_sw) as f64 * o + n_sw as f64 * sw;
        2.0 * a + 2.0 * b + (v[3] - v[1]) + (v[0] - v[2]) + extra - saved
    }

    /// Side-length floors (A, B): what each side's inserts need, through the closure
    /// relations.
    fn floors(&self, l: &Layout) -> (f64, f64) {
        let v: Vec<f64> = l.sides.iter().map(|s| inserts_uv(s, self.e).1).collect();
        let need: Vec<f64> = (0..4)
            .map(|i| side_need(&l.sides[i], self.e, self.g_min, self.ends(i, l)))
            .collect();
        (
            need[0].max(need[2] + v[1] - v[3]),
            need[1].max(need[3] - v[0] + v[2]),
        )
    }
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
    let lay =
        layout(order, rng, 75, e, depth).ok_or("ring: features do not fit the ring's slots")?;
    let [bx, by] = centreline_box(spec, cfg);
    let (ux, uy) = (bx.max(by), bx.min(by));
    let g_min = GAP_EDGES[(rng.next_u32() as usize) % GAP_EDGES.len()] * e;
    let sizes = RingSizes {
        e,
        g_min,
        saving: savings(rc),
        sweeper_room: 1.6 * rc,
    };
    let floors = sizes.floors(&lay);
    // A + B for the plain ring (`length` is linear in A + B with slope 2).
    let mut k_ab = (spec.lap_length_m - sizes.length(&lay, 0.0, 0.0)) / 2.0;
    // A lap just too long for the hall's rectangle takes the whole rectangle when that
    // is within LAP_SLACK of L (the validator allows 3 %).
    let k_short = (spec.lap_length_m * (1.0 - LAP_SLACK) - sizes.length(&lay, 0.0, 0.0)) / 2.0;
    if k_ab > ux + uy && k_short <= ux + uy {
        k_ab = ux + uy;
    }
    let t = (rng.next_u32() % 1000) as f64 / 999.0;
    let (lay, a, b) = if k_ab - uy.min(ux) <= ux {
        let (a, b) = rectangle_sides(k_ab, floors, ux, uy, t)?;
        (lay, a, b)
    } else {
        match deepened_layout(spec, d, &sizes, &lay, ux, uy, t, rng) {
            Some(fit) => fit,
            // The side-notch shape may still hold it (featureless, or one chicane with
            // at most two hairpins and one sweeper).
            None => return super::side_notch::side_notch_loop(spec, d, ux, uy, rng),
        }
    };
    let (verts, is_sweeper) = ring_polygon(&sizes, &lay, a, b, rng)?;
    let ext = extent(&verts);
    if !((ext[0] <= ux + 1e-9 && ext[1] <= uy + 1e-9)
        || (ext[1] <= ux + 1e-9 && ext[0] <= uy + 1e-9))
    {
        return Err("ring: hall fit");
    }
    let line = round_polygon(&verts, &is_sweeper, rc, 0.02).ok_or("fillets overlap")?;
    Ok((line, e))
}

/// Sides (A, B) of a rounded rectangle that holds the lap (A + B = `k_ab`) above the
/// side floors `(a_lo, b_lo)`: B drawn by `t` ∈ [0, 1], biased towards the full height.
fn rectangle_sides(
    k_ab: f64,
    (a_lo, b_lo): (f64, f64),
    ux: f64,
    uy: f64,
    t: f64,
) -> Result<(f64, f64), &'static str> {
    let b_hi = uy.min(k_ab - a_lo);
    let b_lo = b_lo.max(k_ab - ux);
    if k_ab < a_lo + b_lo {
        return Err("ring: lap too short for the features' spacing");
    }
    if b_hi < b_lo {
        return Err("ring: hall too small for the lap");
    }
    let b = b_hi - (b_hi - b_lo) * t * t;
    Ok((k_ab - b, b))
}

/// A lap too long for the hall's rectangle: deepen the inward notches (inward hairpins,
/// and `n` plain notches pushed into the long side A), all to one depth that keeps the
/// pitch from the opposite side. For each `n` the depth, or B, follows from L; one `n`
/// that fits is drawn, with its layout and sides (A, B). `None` if no `n` fits.
#[allow(clippy::too_many_arguments)]
fn deepened_layout(
    spec: &Spec,
    d: &Derived,
    sizes: &RingSizes,
    lay: &Layout,
    ux: f64,
    uy: f64,
    t: f64,
    rng: &mut ChaCha8Rng,
) -> Option<(Layout, f64, f64)> {
    let e = sizes.e;
    let width = PLAIN_WIDTHS[(rng.next_u32() as usize) % PLAIN_WIDTHS.len()] * e;
    let mut fits: Vec<(Layout, f64, f64)> = Vec::new();
    for n in 0..=MAX_PLAIN_NOTCHES {
        let mut l = lay.clone();
        for _ in 0..n {
            let side = &mut l.sides[0];
            let at = (rng.next_u32() as usize) % (side.len() + 1);
            side.insert(
                at,
                Insert::Notch {
                    inward: true,
                    width,
                    depth: 0.0,
                },
            );
        }
        let deep = set_inward_depth(&mut l, 0.0);
        if deep == 0 {
            continue;
        }
        let (a_lo, b_lo) = sizes.floors(&l);
        if a_lo > ux || uy < b_lo {
            break; // more notches only need more room
        }
        // L = len(0, 0) + 2A + 2B + 2·deep·depth. With A near the hall's length: at
        // full height B the depth makes up the rest; if that is too shallow, the
        // notches take their least depth and B shrinks instead.
        let du_lo = if n > 0 { PLAIN_WIDTHS[0] * e } else { e };
        let nf = deep as f64;
        let a = ux - (ux - a_lo) * 0.15 * t;
        let rest = spec.lap_length_m - sizes.length(&l, a, 0.0);
        let (mut b, mut du) = (uy, (rest - 2.0 * uy) / (2.0 * nf));
        if du < du_lo {
            du = du_lo;
            b = (rest - 2.0 * nf * du) / 2.0;
        }
        if a < a_lo || b < b_lo || b > uy + 1e-9 || du > a.min(b) - d.pitch {
            continue;
        }
        set_inward_depth(&mut l, du);
        fits.push((l, a, b));
    }
    if fits.is_empty() {
        return None;
    }
    Some(fits.swap_remove((rng.next_u32() as usize) % fits.len()))
}

/// Set every inward notch of `l` (hairpin or plain) to `depth`; returns their number.
fn set_inward_depth(l: &mut Layout, depth: f64) -> usize {
    let mut count = 0usize;
    for ins in l.sides.iter_mut().flatten() {
        if let Insert::Notch {
            inward: true,
            depth: d,
            ..
        } = ins
        {
            *d = depth;
            count += 1;
        }
    }
    count
}

/// The ring's polygon for sides A, B: each side's gaps drawn and its inserts laid out
/// as turtle moves, then the moves walked into vertices; returns the vertices and each
/// one's sweeper flag.
fn ring_polygon(
    sizes: &RingSizes,
    lay: &Layout,
    a: f64,
    b: f64,
    rng: &mut ChaCha8Rng,
) -> Result<(Vec<[f64; 2]>, Vec<bool>), &'static str> {
    let e = sizes.e;
    let v: Vec<f64> = lay.sides.iter().map(|s| inserts_uv(s, e).1).collect();
    let u = [a, b, a - v[1] + v[3], b + v[0] - v[2]];
    let mut moves: Vec<(f64, i8)> = Vec::new();
    let mut side_ends = [0usize; 4];
    for i in 0..4 {
        let ins = &lay.sides[i];
        let straight = u[i] - inserts_uv(ins, e).0;
        let gaps = split_gaps(straight, ins.len(), sizes.g_min, sizes.ends(i, lay), rng)
            .ok_or("ring: side too short")?;
        side_moves(ins, &gaps, e, &mut moves);
        let last = moves.len() - 1;
        moves[last].1 = 1; // the rectangle's corner (left turn)
        side_ends[i] = last;
    }
    walk_moves(&moves, &side_ends, &lay.sweeper)
}

/// Turtle moves `(run, turn)` → polygon vertices (the point of every turn), each with its
/// sweeper flag: set on the rectangle's corners (the turns at `side_ends`) that are
/// sweepers. `Err` unless the walk closes where it started, heading the same way.
fn walk_moves(
    moves: &[(f64, i8)],
    side_ends: &[usize; 4],
    sweeper: &[bool; 4],
) -> Result<(Vec<[f64; 2]>, Vec<bool>), &'static str> {
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
                .is_some_and(|c| sweeper[c]),
        );
    }
    // The loop closes exactly by construction; guard against rounding.
    let gap = [p[0] + h.0 * run_acc, p[1] + h.1 * run_acc];
    if gap[0].hypot(gap[1]) > 1e-6 || h != (1.0, 0.0) {
        return Err("ring: loop does not close");
    }
    Ok((verts, is_sweeper))
}
