//! Polyomino growth on a square lattice (the paper's lattice constructor, first half).
//!
//! A cell set grows one 4-neighbour at a time inside a `cols × rows` box, refusing any
//! cell that would close a hole or create a diagonal-only contact, so the outer boundary
//! is always one simple closed loop; that loop (scaled by the lattice pitch and rounded,
//! see `rounding`) is the centreline. Growth is *steered*: every legal cell is scored by
//! how far the resulting boundary is from the target perimeter and from the requested
//! feature pattern, and the seeded RNG picks among the best. Boundary patterns mirror
//! the curvature detector in `track::features`:
//!
//! * corners one edge apart with the same sense merge into a hairpin (≥ 180°);
//! * a lone corner followed one edge later by an opposite-sense lone corner is a chicane;
//! * a lone corner with ≥ 2 edges on both sides may become a sweeper.

use super::deadline::Deadline;
use crate::track::features::FeatureKind;
use rand_chacha::rand_core::Rng;
use rand_chacha::ChaCha8Rng;

/// A boundary corner: lattice point, turn sense (+1 left, −1 right) and the number of
/// lattice edges to the next corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Corner {
    pub at: (i32, i32),
    pub sense: i8,
    pub run_after: u32,
}

/// The boundary as the constructor sees it.
#[derive(Debug, Clone)]
pub struct Boundary {
    pub corners: Vec<Corner>,
    pub perimeter: u32,
    /// Feature pattern in boundary order (counter-clockwise).
    pub features: Vec<(FeatureKind, usize)>,
    /// Corners that may be turned into sweepers (index into `corners`).
    pub sweeper_slots: Vec<usize>,
    pub longest_run: u32,
}

impl Boundary {
    pub fn count(&self, k: FeatureKind) -> u32 {
        self.features.iter().filter(|f| f.0 == k).count() as u32
    }
}

/// What the growth aims for.
#[derive(Debug, Clone)]
pub struct Target {
    pub perimeter: u32,
    pub hairpins: u32,
    pub chicanes: u32,
    pub sweepers: u32,
    /// Minimum number of lattice edges in the longest run (0 = no requirement).
    pub min_run: u32,
    /// Maximum number of lattice edges in any run (0 = no cap): the speed cap.
    pub max_run: u32,
    /// Wanted cyclic order (counter-clockwise boundary order), empty = any.
    pub order: Vec<FeatureKind>,
}

/// A cell set in a box, padded by one empty ring so neighbour lookups never go out.
#[derive(Debug, Clone)]
pub struct Polyomino {
    pub cols: i32,
    pub rows: i32,
    cells: Vec<bool>,
}

impl Polyomino {
    pub fn new(cols: i32, rows: i32) -> Self {
        Polyomino {
            cols,
            rows,
            cells: vec![false; ((cols + 2) * (rows + 2)) as usize],
        }
    }
    #[inline]
    fn idx(&self, c: i32, r: i32) -> usize {
        ((r + 1) * (self.cols + 2) + (c + 1)) as usize
    }
    /// Is cell (c, r) filled? Out-of-box cells are empty.
    #[inline]
    pub fn get(&self, c: i32, r: i32) -> bool {
        c >= -1 && r >= -1 && c <= self.cols && r <= self.rows && self.cells[self.idx(c, r)]
    }
    pub fn set(&mut self, c: i32, r: i32, v: bool) {
        let i = self.idx(c, r);
        self.cells[i] = v;
    }
    pub fn len(&self) -> usize {
        self.cells.iter().filter(|&&c| c).count()
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Can (c, r) be added keeping one simply connected, diagonal-contact-free set?
    pub fn can_add(&self, c: i32, r: i32) -> bool {
        if c < 0 || r < 0 || c >= self.cols || r >= self.rows || self.get(c, r) {
            return false;
        }
        let n4 = [(1, 0), (-1, 0), (0, 1), (0, -1)]
            .iter()
            .filter(|(dc, dr)| self.get(c + dc, r + dr))
            .count();
        if n4 == 0 && !self.is_empty() {
            return false;
        }
        // Diagonal-only contact: a filled diagonal neighbour whose two shared
        // 4-neighbours are both empty.
        for (dc, dr) in [(1, 1), (1, -1), (-1, 1), (-1, -1)] {
            if self.get(c + dc, r + dr) && !self.get(c + dc, r) && !self.get(c, r + dr) {
                return false;
            }
        }
        // A hole closes iff the empty 4-neighbours of the new cell stop being connected
        // to each other through the empty region (checked on the padded box).
        let mut trial = self.clone();
        trial.set(c, r, true);
        trial.empty_is_connected()
    }

    fn empty_is_connected(&self) -> bool {
        let (w, h) = (self.cols + 2, self.rows + 2);
        let total = self.cells.iter().filter(|&&x| !x).count();
        let mut seen = vec![false; self.cells.len()];
        let mut stack = vec![0usize];
        seen[0] = true;
        let mut n = 0;
        while let Some(i) = stack.pop() {
            n += 1;
            let (x, y) = ((i as i32) % w, (i as i32) / w);
            for (dx, dy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                let (nx, ny) = (x + dx, y + dy);
                if nx >= 0 && ny >= 0 && nx < w && ny < h {
                    let j = (ny * w + nx) as usize;
                    if !self.cells[j] && !seen[j] {
                        seen[j] = true;
                        stack.push(j);
                    }
                }
            }
        }
        n == total
    }

    /// Trace the outer boundary counter-clockwise (cells on the left).
    pub fn boundary(&self) -> Boundary {
        // Start: lowest row, leftmost cell; its bottom edge heading +x.
        let mut start = None;
        'outer: for r in 0..self.rows {
            for c in 0..self.cols {
                if self.get(c, r) {
                    start = Some((c, r));
                    break 'outer;
                }
            }
        }
        let Some((c0, r0)) = start else {
            return Boundary {
                corners: vec![],
                perimeter: 0,
                features: vec![],
                sweeper_slots: vec![],
                longest_run: 0,
            };
        };
        let v0 = (c0, r0);
        let (mut v, mut d) = (v0, (1i32, 0i32));
        let mut corners: Vec<((i32, i32), i8)> = Vec::new();
        let mut perimeter = 0u32;
        let mut run_lengths: Vec<u32> = Vec::new();
        let mut run = 0u32;
        loop {
            // Move one edge.
            v = (v.0 + d.0, v.1 + d.1);
            perimeter += 1;
            run += 1;
            // Cells ahead-left / ahead-right of vertex v w.r.t. heading d.
            let n = (-d.1, d.0);
            let cell = |ox: i32, oy: i32| -> (i32, i32) {
                // Cell whose centre is v + 0.5 (ox, oy); floor of the centre.
                ((2 * v.0 + ox).div_euclid(2), (2 * v.1 + oy).div_euclid(2))
            };
            let al = cell(d.0 + n.0, d.1 + n.1);
            let ar = cell(d.0 - n.0, d.1 - n.1);
            let (fl, fr) = (self.get(al.0, al.1), self.get(ar.0, ar.1));
            let turn: i8 = if fl && fr {
                -1
            } else if fl {
                0
            } else {
                1
            };
            if turn != 0 {
                d = if turn > 0 { (-d.1, d.0) } else { (d.1, -d.0) };
                corners.push((v, turn));
                run_lengths.push(run);
                run = 0;
            }
            if v == v0 && d == (1, 0) {
                break;
            }
        }
        // run_lengths[i] is the run *ending* at corner i; the run after corner i is the
        // one ending at corner i + 1 (the final partial run joins the first).
        let m = corners.len();
        if m > 0 {
            run_lengths[0] += run;
        }
        let corners: Vec<Corner> = (0..m)
            .map(|i| Corner {
                at: corners[i].0,
                sense: corners[i].1,
                run_after: run_lengths[(i + 1) % m],
            })
            .collect();
        let longest_run = corners.iter().map(|c| c.run_after).max().unwrap_or(0);
        let (features, sweeper_slots) = classify(&corners);
        Boundary {
            corners,
            perimeter,
            features,
            sweeper_slots,
            longest_run,
        }
    }
}

/// Feature pattern of a corner cycle (see the module docs). Scanning starts after the
/// longest run, as the curvature detector starts on the straightest sample.
pub fn classify(corners: &[Corner]) -> (Vec<(FeatureKind, usize)>, Vec<usize>) {
    let m = corners.len();
    if m == 0 {
        return (vec![], vec![]);
    }
    let longest = (0..m)
        .max_by_key(|&i| (corners[i].run_after, std::cmp::Reverse(i)))
        .unwrap();
    let first = (longest + 1) % m;
    let at = |k: usize| (first + k) % m;
    // Groups of same-sense corners linked by single edges.
    let mut groups: Vec<(usize, usize)> = Vec::new(); // (first corner k, size)
    let mut k = 0;
    while k < m {
        let start = k;
        while k + 1 < m
            && corners[at(k)].run_after == 1
            && corners[at(k + 1)].sense == corners[at(k)].sense
        {
            k += 1;
        }
        groups.push((start, k - start + 1));
        k += 1;
    }
    let mut feats = Vec::new();
    let mut slots = Vec::new();
    let mut used = vec![false; groups.len()];
    for g in 0..groups.len() {
        if used[g] {
            continue;
        }
        used[g] = true;
        let (k0, size) = groups[g];
        if size >= 2 {
            feats.push((FeatureKind::Hairpin, at(k0)));
            continue;
        }
        let h = (g + 1) % groups.len();
        let c = corners[at(k0)];
        if h != g
            && !used[h]
            && groups[h].1 == 1
            && c.run_after == 1
            && corners[at(groups[h].0)].sense != c.sense
        {
            used[h] = true;
            feats.push((FeatureKind::Chicane, at(k0)));
            continue;
        }
        let before = corners[(at(k0) + m - 1) % m].run_after;
        if before >= 2 && c.run_after >= 2 {
            slots.push(at(k0));
        }
    }
    (feats, slots)
}

/// Distance of a boundary from the target (0 = matches), used to steer growth.
pub fn score(b: &Boundary, t: &Target) -> u32 {
    let diff = |a: u32, b: u32| a.abs_diff(b);
    let mut s = diff(b.perimeter, t.perimeter) / 2;
    s += 2
        * (diff(b.count(FeatureKind::Hairpin), t.hairpins)
            + diff(b.count(FeatureKind::Chicane), t.chicanes));
    s += 2 * t.sweepers.saturating_sub(b.sweeper_slots.len() as u32);
    if b.longest_run < t.min_run {
        s += 1;
    }
    if t.max_run > 0 && b.longest_run > t.max_run {
        s += 1;
    }
    if s == 0 && !t.order.is_empty() && t.sweepers == 0 {
        let got: Vec<FeatureKind> = b.features.iter().map(|f| f.0).collect();
        if !crate::track::features::is_cyclic_order(&got, &t.order) {
            s += 1;
        }
    }
    s
}

/// Grow one candidate; `None` if growth got stuck before matching the target.
pub fn grow(
    cols: i32,
    rows: i32,
    target: &Target,
    rng: &mut ChaCha8Rng,
    deadline: &Deadline,
) -> Option<(Polyomino, Boundary)> {
    let mut p = Polyomino::new(cols, rows);
    let (c, r) = (
        (rng.next_u32() % cols as u32) as i32,
        (rng.next_u32() % rows as u32) as i32,
    );
    p.set(c, r, true);
    let max_steps = cols as usize * rows as usize;
    for _ in 0..max_steps {
        if deadline.stopped().is_some() {
            return None;
        }
        let mut options: Vec<((i32, i32), u32)> = Vec::new();
        for r in 0..rows {
            for c in 0..cols {
                let touches = [(1, 0), (-1, 0), (0, 1), (0, -1)]
                    .iter()
                    .any(|(dc, dr)| p.get(c + dc, r + dr));
                if touches && p.can_add(c, r) {
                    p.set(c, r, true);
                    let b = p.boundary();
                    let s = score(&b, target);
                    p.set(c, r, false);
                    if s == 0 {
                        p.set(c, r, true);
                        return Some((p, b));
                    }
                    options.push(((c, r), s));
                }
            }
        }
        if options.is_empty() {
            return None;
        }
        // Mostly greedy (a random best), sometimes exploratory (best + 1), rarely random.
        let best = options.iter().map(|o| o.1).min().unwrap();
        let roll = rng.next_u32() % 100;
        let slack = if roll < 70 {
            0
        } else if roll < 95 {
            1
        } else {
            u32::MAX / 2
        };
        let pool: Vec<(i32, i32)> = options
            .iter()
            .filter(|o| o.1 <= best + slack)
            .map(|o| o.0)
            .collect();
        let (c, r) = pool[(rng.next_u32() as usize) % pool.len()];
        p.set(c, r, true);
        if p.boundary().perimeter > target.perimeter + 8 {
            return None;
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_chacha::rand_core::SeedableRng;

    fn from_rows(rows: &[&str]) -> Polyomino {
        let h = rows.len() as i32;
        let w = rows[0].len() as i32;
        let mut p = Polyomino::new(w, h);
        for (i, line) in rows.iter().enumerate() {
            for (c, ch) in line.chars().enumerate() {
                if ch == '#' {
                    p.set(c as i32, h - 1 - i as i32, true);
                }
            }
        }
        p
    }

    #[test]
    fn rectangle_has_four_left_corners() {
        let b = from_rows(&["###", "###"]).boundary();
        assert_eq!(b.perimeter, 10);
        assert_eq!(b.corners.len(), 4);
        assert!(b.corners.iter().all(|c| c.sense == 1));
        assert!(b.features.is_empty());
        assert_eq!(
            b.sweeper_slots.len(),
            4,
            "every corner has ≥ 2 edges on both sides"
        );
    }

    #[test]
    fn protrusion_is_a_hairpin_and_step_is_a_chicane() {
        let b = from_rows(&[".#..", "####", "####"]).boundary();
        assert_eq!(b.count(FeatureKind::Hairpin), 1, "{:?}", b.corners);
        let b = from_rows(&["..###", "..###", "#####", "###.."]).boundary();
        assert!(b.count(FeatureKind::Chicane) >= 1, "{:?}", b.features);
    }

    #[test]
    fn holes_and_diagonal_contacts_are_refused() {
        let p = from_rows(&["###", "#.#", "##."]);
        assert!(!p.can_add(2, 0), "would close a hole");
        let d = from_rows(&["..", "#."]);
        assert!(!d.can_add(1, 1), "diagonal-only contact");
        assert!(d.can_add(1, 0));
    }

    #[test]
    fn growth_is_deterministic_and_hits_the_target() {
        let t = Target {
            perimeter: 18,
            hairpins: 1,
            chicanes: 0,
            sweepers: 0,
            min_run: 0,
            max_run: 0,
            order: vec![],
        };
        let run = |seed| {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            (0..50)
                .find_map(|_| grow(7, 5, &t, &mut rng, &Deadline::default()))
                .map(|(p, b)| (p.cells.clone(), b.perimeter))
        };
        let a = run(3).expect("some candidate matches");
        assert_eq!(a.1, 18);
        assert_eq!(run(3).unwrap().0, a.0);
    }
}
