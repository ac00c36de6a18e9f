//! Marching squares: iso-lines of a scalar field sampled at cell centres, with sub-cell
//! linear interpolation along the lattice edges.
//!
//! The field is a row-major grid like [`OccupancyGrid::data`](crate::grid::OccupancyGrid)
//! (row 0 = top). Lines are returned in *grid units*: `(u, v)` measured from the
//! lower-left grid corner, u right, v up, so cell (col, row) has its centre at
//! `(col + 0.5, height − row − 0.5)`; [`OccupancyGrid::grid_to_world`](crate::grid::OccupancyGrid::grid_to_world)
//! turns them into map metres. The region outside the grid counts as *not inside*, so
//! every line is closed (a region touching the border is closed along the grid edge).
//!
//! Orientation: the *inside* region `f < level` lies on the left of every loop, so an
//! outer boundary runs counter-clockwise and the boundary of a hole clockwise. Saddle
//! squares are resolved by the mean of their four corners. Work and memory are linear
//! in the number of cells plus the number of crossings.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// A multiplicative hasher for the integer edge keys (SipHash is needlessly slow here).
#[derive(Default)]
struct KeyHasher(u64);
impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, _: &[u8]) {
        unreachable!("only u64 keys are hashed")
    }
    fn write_u64(&mut self, k: u64) {
        self.0 = (k ^ (k >> 29)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}
type KeyMap<V> = HashMap<u64, V, BuildHasherDefault<KeyHasher>>;

/// Closed iso-lines `f = level` (see the module docs for units and orientation).
/// Loops are returned in raster order of their first crossing, without a repeated end
/// point; degenerate loops of fewer than 3 points are dropped.
pub fn marching_squares(f: &[f32], width: usize, height: usize, level: f32) -> Vec<Vec<[f64; 2]>> {
    assert_eq!(
        f.len(),
        width * height,
        "field size does not match width × height"
    );
    let lat = Lattice {
        f,
        w: width as i64,
        h: height as i64,
        level,
    };
    // next[start edge] = (end edge, point on start edge); order = starts in raster order.
    let mut links = Links::default();
    // Inside flags of two lattice rows (padding included), reused row to row.
    let (mut lo, mut hi) = (Vec::with_capacity(width + 2), Vec::with_capacity(width + 2));
    lat.flags(0, &mut hi);
    for j in 0..=lat.h {
        std::mem::swap(&mut lo, &mut hi);
        lat.flags(j + 1, &mut hi);
        for i in 0..=lat.w {
            let iu = i as usize;
            let case = lo[iu] | lo[iu + 1] << 1 | hi[iu + 1] << 2 | hi[iu] << 3;
            if case != 0 && case != 15 {
                lat.link_square(i, j, case, &mut links);
            }
        }
    }
    links.loops()
}

/// The field on the lattice of cell centres: node (i, j), i in 0..=w+1, j in 0..=h+1,
/// the outer ring being padding (v up, so node row j is grid row h − j).
struct Lattice<'a> {
    f: &'a [f32],
    w: i64,
    h: i64,
    level: f32,
}

impl Lattice<'_> {
    /// Value at lattice node (i, j); `None` outside the grid (= not inside).
    fn at(&self, i: i64, j: i64) -> Option<f32> {
        let (w, h) = (self.w, self.h);
        (i >= 1 && i <= w && j >= 1 && j <= h).then(|| self.f[((h - j) * w + (i - 1)) as usize])
    }

    /// Key of the lattice edge from node (i, j) along `dir` (0 = +u, 1 = +v).
    fn key(&self, i: i64, j: i64, dir: i64) -> u64 {
        ((j * (self.w + 2) + i) * 2 + dir) as u64
    }

    /// Crossing point on the lattice edge from node (i, j) along `dir`.
    fn crossing(&self, i: i64, j: i64, dir: i64) -> [f64; 2] {
        let (i2, j2) = if dir == 0 { (i + 1, j) } else { (i, j + 1) };
        let t = match (self.at(i, j), self.at(i2, j2)) {
            (Some(a), Some(b)) if a != b => ((self.level - a) / (b - a)).clamp(0.0, 1.0) as f64,
            _ => 0.5, // one end in the padding: the crossing is the grid edge
        };
        let (u, v) = (i as f64 - 0.5, j as f64 - 0.5);
        if dir == 0 {
            [u + t, v]
        } else {
            [u, v + t]
        }
    }

    /// Inside flags (`f < level`) of lattice row `j` into `out`, padding included.
    fn flags(&self, j: i64, out: &mut Vec<u8>) {
        let (w, h) = (self.w, self.h);
        out.clear();
        out.push(0);
        if j >= 1 && j <= h {
            let row = &self.f[((h - j) * w) as usize..((h - j + 1) * w) as usize];
            out.extend(row.iter().map(|&x| (x < self.level) as u8));
        } else {
            out.extend(std::iter::repeat_n(0u8, w as usize));
        }
        out.push(0);
    }

    /// Link each out-edge of the square with lower-left node (i, j) and corner case
    /// `case` (bit k: corner k inside, counter-clockwise from lower left) to its in-edge.
    fn link_square(&self, i: i64, j: i64, case: u8, links: &mut Links) {
        let level = self.level;
        let v = [
            self.at(i, j),
            self.at(i + 1, j),
            self.at(i + 1, j + 1),
            self.at(i, j + 1),
        ];
        let b = [case & 1 != 0, case & 2 != 0, case & 4 != 0, case & 8 != 0];
        // Square edge k runs from corner k to corner k+1 (counter-clockwise).
        let edges = [(i, j, 0), (i + 1, j, 1), (i, j + 1, 0), (i, j, 1)];
        let saddle = case == 5 || case == 10;
        let centre_inside =
            saddle && v.iter().map(|x| x.unwrap_or(level) as f64).sum::<f64>() / 4.0 < level as f64;
        for k in 0..4 {
            if !b[k] || b[(k + 1) % 4] {
                continue; // not an out-edge (inside → outside walking counter-clockwise)
            }
            let end = if saddle {
                if centre_inside {
                    (k + 1) % 4
                } else {
                    (k + 3) % 4
                }
            } else {
                (0..4)
                    .find(|&m| !b[m] && b[(m + 1) % 4])
                    .expect("one in-edge")
            };
            let (si, sj, sd) = edges[k];
            let (ei, ej, ed) = edges[end];
            let s = self.key(si, sj, sd);
            links
                .next
                .insert(s, (self.key(ei, ej, ed), self.crossing(si, sj, sd)));
            links.order.push(s);
        }
    }
}

/// The line pieces of all squares: `next[start edge] = (end edge, point on start edge)`,
/// and the start edges in raster order.
#[derive(Default)]
struct Links {
    next: KeyMap<(u64, [f64; 2])>,
    order: Vec<u64>,
}

impl Links {
    /// Chain the pieces into closed loops, each from its first start edge in raster order.
    fn loops(mut self) -> Vec<Vec<[f64; 2]>> {
        let mut loops = Vec::new();
        for s in self.order {
            let Some(&(mut nxt, p)) = self.next.get(&s) else {
                continue;
            };
            self.next.remove(&s);
            let mut pts = vec![p];
            while nxt != s {
                match self.next.remove(&nxt) {
                    Some((n2, q)) => {
                        pts.push(q);
                        nxt = n2;
                    }
                    None => break, // cannot happen for a consistent table; drop the open chain
                }
            }
            if nxt == s && pts.len() >= 3 {
                loops.push(pts);
            }
        }
        loops
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{polyline_length, signed_area};
    use std::f64::consts::PI;

    fn disc_field(n: usize, cx: f64, cy: f64) -> Vec<f32> {
        // signed distance (cells) to a circle of radius r, in grid units, row 0 at top
        (0..n * n)
            .map(|k| {
                let (col, row) = (k % n, k / n);
                let (u, v) = (col as f64 + 0.5, (n - 1 - row) as f64 + 0.5);
                ((u - cx).hypot(v - cy)) as f32
            })
            .collect()
    }

    #[test]
    fn circle_has_right_length_area_and_orientation() {
        let (n, r) = (80, 25.0);
        let f = disc_field(n, 40.3, 38.9);
        let loops = marching_squares(&f, n, n, r as f32);
        assert_eq!(loops.len(), 1);
        let l = &loops[0];
        assert!((polyline_length(l, true) - 2.0 * PI * r).abs() / (2.0 * PI * r) < 0.005);
        assert!(
            (signed_area(l) - PI * r * r).abs() / (PI * r * r) < 0.005,
            "area {}",
            signed_area(l)
        );
        for p in l {
            assert!(((p[0] - 40.3).hypot(p[1] - 38.9) - r).abs() < 0.05);
        }
    }

    #[test]
    fn annulus_gives_ccw_outer_and_cw_inner_loop() {
        let n = 60;
        let d = disc_field(n, 30.0, 30.0);
        let ring: Vec<f32> = d.iter().map(|&x| (x - 18.0).abs() - 6.0).collect(); // inside: 12 < r < 24
        let loops = marching_squares(&ring, n, n, 0.0);
        assert_eq!(loops.len(), 2);
        let mut areas: Vec<f64> = loops.iter().map(|l| signed_area(l)).collect();
        areas.sort_by(f64::total_cmp);
        assert!(areas[0] < 0.0 && areas[1] > 0.0, "{areas:?}");
        assert!((areas[1] - PI * 24.0 * 24.0).abs() < 0.01 * PI * 576.0);
        assert!((areas[0] + PI * 144.0).abs() < 0.02 * PI * 144.0);
    }

    #[test]
    fn region_touching_the_border_is_closed_along_it() {
        let f = vec![-1.0f32; 12]; // everything inside
        let loops = marching_squares(&f, 4, 3, 0.0);
        assert_eq!(loops.len(), 1);
        assert!((signed_area(&loops[0]) - 11.5).abs() < 1e-9); // grid edge, corners cut by 1/8 cell
        let one = marching_squares(&[-1.0], 1, 1, 0.0);
        assert_eq!(one.len(), 1);
        assert!(marching_squares(&[1.0; 4], 2, 2, 0.0).is_empty());
    }

    #[test]
    fn saddles_follow_the_centre_value() {
        // checkerboard 2x2: inside on the diagonal
        let f = [-1.0f32, 1.0, 1.0, -1.0];
        let joined = marching_squares(&f, 2, 2, 0.5); // centre mean 0 < 0.5: joined
        assert_eq!(joined.len(), 1);
        let split = marching_squares(&f, 2, 2, -0.5); // only strongly negative inside: split
        assert_eq!(split.len(), 2);
    }
}
