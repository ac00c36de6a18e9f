//! The nesting tree of free and non-free regions of a grid, built from row runs.
//!
//! Free cells form 4-connected regions, all other cells 8-connected ones, and the grid
//! is thought of as surrounded by a ring of non-free padding (the *outside*). With these
//! complementary connectivities the regions' adjacency graph is a tree rooted at the
//! outside: every region's parent is the region that encloses it.
//!
//! Everything runs on maximal horizontal runs of equal kind (free / non-free), found in
//! one pass over the cells; labelling is union-find over runs, adjacency comes from
//! consecutive runs in a row and overlapping runs in consecutive rows. Work is linear in
//! the number of cells (one scan) plus the number of runs, memory linear in the runs.

/// A maximal horizontal run of cells of one kind: columns `start..end` of `row`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Run {
    pub row: u32,
    pub start: u32,
    pub end: u32,
    pub free: bool,
}

impl Run {
    pub fn len(&self) -> usize {
        (self.end - self.start) as usize
    }
    pub fn is_empty(&self) -> bool {
        self.end == self.start
    }
}

/// No region (the parent of the root).
pub const NONE: u32 = u32::MAX;

/// Regions of a grid and how they nest (see the module docs).
#[derive(Debug, Clone)]
pub struct RegionTree {
    pub width: usize,
    pub height: usize,
    pub runs: Vec<Run>,
    /// Index of the first run of each row; `row_start[height] == runs.len()`.
    pub row_start: Vec<usize>,
    /// Region of each run.
    pub run_region: Vec<u32>,
    /// Per region: made of free cells?
    pub free: Vec<bool>,
    /// Per region: number of cells (the root's count excludes the virtual padding).
    pub size: Vec<usize>,
    /// Per region: the enclosing region (`NONE` for the root).
    pub parent: Vec<u32>,
    pub children: Vec<Vec<u32>>,
    /// Per region: cells in its subtree (itself and everything it encloses).
    pub subtree: Vec<usize>,
    /// Per region: cells on the grid border.
    pub border_contact: Vec<usize>,
    /// The outside: the padding ring plus every non-free region touching the border.
    pub root: u32,
}

struct UnionFind(Vec<u32>);
impl UnionFind {
    fn find(&mut self, mut a: u32) -> u32 {
        while self.0[a as usize] != a {
            let p = self.0[self.0[a as usize] as usize];
            self.0[a as usize] = p;
            a = p;
        }
        a
    }
    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            self.0[hi as usize] = lo;
        }
    }
}

/// Build the region tree of `data` (row-major `width × height`), free where `is_free`.
pub fn region_tree(
    data: &[u8],
    width: usize,
    height: usize,
    is_free: impl Fn(u8) -> bool,
) -> RegionTree {
    assert_eq!(
        data.len(),
        width * height,
        "data size does not match width × height"
    );
    let (runs, row_start) = row_runs(data, width, height, is_free);
    let (mut uf, edges) = connect_runs(&runs, &row_start, width, height);
    let (run_region, free, root) = compact_regions(&mut uf, &runs);
    let n = free.len();
    let (size, border_contact) = region_sizes(&runs, &run_region, n, width, height);
    let adj = region_adjacency(edges, &run_region, root, n);
    let (parent, children, subtree) = nest(&adj, root, &size);
    RegionTree {
        width,
        height,
        runs,
        row_start,
        run_region,
        free,
        size,
        parent,
        children,
        subtree,
        border_contact,
        root,
    }
}

/// The maximal runs of each row, row by row, and the index of each row's first run
/// (`height + 1` entries, the last one `runs.len()`).
fn row_runs(
    data: &[u8],
    width: usize,
    height: usize,
    is_free: impl Fn(u8) -> bool,
) -> (Vec<Run>, Vec<usize>) {
    let mut runs = Vec::new();
    let mut row_start = Vec::with_capacity(height + 1);
    for r in 0..height {
        row_start.push(runs.len());
        let row = &data[r * width..(r + 1) * width];
        let mut c = 0;
        while c < width {
            let f = is_free(row[c]);
            let s = c;
            while c < width && is_free(row[c]) == f {
                c += 1;
            }
            runs.push(Run {
                row: r as u32,
                start: s as u32,
                end: c as u32,
                free: f,
            });
        }
    }
    row_start.push(runs.len());
    (runs, row_start)
}

/// Union-find over the runs plus one virtual padding element (index `runs.len()`):
/// runs of one region joined, and the edges between runs of different kinds that touch.
fn connect_runs(
    runs: &[Run],
    row_start: &[usize],
    width: usize,
    height: usize,
) -> (UnionFind, Vec<(u32, u32)>) {
    let nr = runs.len();
    let pad = nr as u32; // virtual padding element
    let mut uf = UnionFind((0..=nr as u32).collect());
    let mut edges: Vec<(u32, u32)> = Vec::new();
    let (w, h) = (width as u32, height as u32);
    for (i, run) in runs.iter().enumerate() {
        let on_border = run.row == 0 || run.row + 1 == h || run.start == 0 || run.end == w;
        if on_border {
            if run.free {
                edges.push((i as u32, pad));
            } else {
                uf.union(i as u32, pad);
            }
        }
    }
    for r in 0..height {
        // horizontal neighbours alternate kinds
        for i in row_start[r] + 1..row_start[r + 1] {
            edges.push(((i - 1) as u32, i as u32));
        }
        if r > 0 {
            connect_rows(
                runs,
                row_start[r - 1]..row_start[r],
                row_start[r]..row_start[r + 1],
                &mut uf,
                &mut edges,
            );
        }
    }
    (uf, edges)
}

/// Join or link the runs of two consecutive rows (`prev` above `cur`, index ranges into
/// `runs`): same kind joins (free runs when they share a column, non-free ones when they
/// touch, diagonally too), different kinds sharing a column are an edge.
fn connect_rows(
    runs: &[Run],
    prev: std::ops::Range<usize>,
    cur: std::ops::Range<usize>,
    uf: &mut UnionFind,
    edges: &mut Vec<(u32, u32)>,
) {
    let mut p0 = prev.start;
    for j in cur {
        let b = runs[j];
        while p0 < prev.end && runs[p0].end < b.start {
            p0 += 1; // cannot touch b or any later run, even diagonally
        }
        let mut p = p0;
        while p < prev.end && runs[p].start <= b.end {
            let a = runs[p];
            let shares_column = a.start < b.end && b.start < a.end;
            if a.free == b.free {
                // free: 4-connected (share a column); non-free: 8-connected (touch)
                if shares_column || !a.free {
                    uf.union(p as u32, j as u32);
                }
            } else if shares_column {
                edges.push((p as u32, j as u32));
            }
            p += 1;
        }
    }
}

/// Compact region ids, in order of each region's first run: the region of each run,
/// whether each region is free, and the root (the padding's region).
fn compact_regions(uf: &mut UnionFind, runs: &[Run]) -> (Vec<u32>, Vec<bool>, u32) {
    let nr = runs.len();
    let mut id = vec![NONE; nr + 1];
    let mut free = Vec::new();
    let mut run_region = Vec::with_capacity(nr);
    for i in 0..=nr {
        let root = uf.find(i as u32) as usize;
        if id[root] == NONE {
            id[root] = free.len() as u32;
            free.push(if root < nr { runs[root].free } else { false });
        }
        if i < nr {
            run_region.push(id[root]);
        }
    }
    let root = id[uf.find(nr as u32) as usize];
    (run_region, free, root)
}

/// Per region of `n`: its cells, and its cells on the grid border.
fn region_sizes(
    runs: &[Run],
    run_region: &[u32],
    n: usize,
    width: usize,
    height: usize,
) -> (Vec<usize>, Vec<usize>) {
    let (w, h) = (width as u32, height as u32);
    let mut size = vec![0usize; n];
    let mut border_contact = vec![0usize; n];
    for (run, &reg) in runs.iter().zip(run_region) {
        size[reg as usize] += run.len();
        border_contact[reg as usize] += if run.row == 0 || run.row + 1 == h {
            run.len()
        } else {
            (run.start == 0) as usize + (run.end == w && !(run.start == 0 && w == 1)) as usize
        };
    }
    (size, border_contact)
}

/// The regions' adjacency lists from the run edges (the padding element is `root`'s),
/// each neighbour once, in ascending pair order.
fn region_adjacency(
    edges: Vec<(u32, u32)>,
    run_region: &[u32],
    root: u32,
    n: usize,
) -> Vec<Vec<u32>> {
    let nr = run_region.len();
    let region = |e: u32| {
        if (e as usize) < nr {
            run_region[e as usize]
        } else {
            root
        }
    };
    let mut pairs: Vec<(u32, u32)> = edges
        .into_iter()
        .map(|(a, b)| {
            let (x, y) = (region(a), region(b));
            if x < y {
                (x, y)
            } else {
                (y, x)
            }
        })
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (a, b) in pairs {
        adj[a as usize].push(b);
        adj[b as usize].push(a);
    }
    adj
}

/// The adjacency tree hung from `root` (breadth first): each region's parent, its
/// children, and the cells of its subtree.
fn nest(adj: &[Vec<u32>], root: u32, size: &[usize]) -> (Vec<u32>, Vec<Vec<u32>>, Vec<usize>) {
    let n = adj.len();
    let mut parent = vec![NONE; n];
    let mut children: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut seen = vec![false; n];
    let mut order = vec![root];
    seen[root as usize] = true;
    let mut k = 0;
    while k < order.len() {
        let u = order[k];
        k += 1;
        for &v in &adj[u as usize] {
            if !seen[v as usize] {
                seen[v as usize] = true;
                parent[v as usize] = u;
                children[u as usize].push(v);
                order.push(v);
            }
        }
    }
    let mut subtree = size.to_vec();
    for &u in order.iter().rev() {
        if parent[u as usize] != NONE {
            subtree[parent[u as usize] as usize] += subtree[u as usize];
        }
    }
    (parent, children, subtree)
}

impl RegionTree {
    /// Region of cell (col, row).
    pub fn region_at(&self, col: usize, row: usize) -> u32 {
        let rs = &self.runs[self.row_start[row]..self.row_start[row + 1]];
        let k = rs.partition_point(|r| (r.end as usize) <= col);
        self.run_region[self.row_start[row] + k]
    }

    /// Number of regions.
    pub fn len(&self) -> usize {
        self.free.len()
    }

    pub fn is_empty(&self) -> bool {
        self.free.is_empty()
    }

    /// Cells on the grid border belonging to `region`, as (col, row), in raster order.
    pub fn border_cells_of(&self, region: u32) -> Vec<(usize, usize)> {
        let (w, h) = (self.width as u32, self.height as u32);
        let mut out = Vec::new();
        for (run, &reg) in self.runs.iter().zip(&self.run_region) {
            if reg != region {
                continue;
            }
            let r = run.row as usize;
            if run.row == 0 || run.row + 1 == h {
                out.extend((run.start..run.end).map(|c| (c as usize, r)));
            } else {
                if run.start == 0 {
                    out.push((0, r));
                }
                if run.end == w && w > 1 {
                    out.push(((w - 1) as usize, r));
                }
            }
        }
        out
    }

    /// Per region: is it `region` or enclosed by it?
    pub fn subtree_flags(&self, region: u32) -> Vec<bool> {
        let mut flags = vec![false; self.len()];
        let mut stack = vec![region];
        while let Some(u) = stack.pop() {
            flags[u as usize] = true;
            stack.extend(&self.children[u as usize]);
        }
        flags
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::flood::{label_components, Connectivity};
    use proptest::prelude::*;

    #[test]
    fn thin_line_rings_nest() {
        // 9 × 9: free background, wall square ring at 2..=6, free inside
        let mut d = vec![1u8; 81];
        for i in 2..=6 {
            for (c, r) in [(i, 2), (i, 6), (2, i), (6, i)] {
                d[r * 9 + c] = 0;
            }
        }
        let t = region_tree(&d, 9, 9, |v| v == 1);
        assert_eq!(t.len(), 4); // outside(+pad), exterior free, wall ring, inside free
        let inside = t.region_at(4, 4);
        let wall = t.region_at(2, 2);
        let ext = t.region_at(0, 0);
        assert_eq!(t.parent[inside as usize], wall);
        assert_eq!(t.parent[wall as usize], ext);
        assert_eq!(t.parent[ext as usize], t.root);
        assert_eq!((t.size[inside as usize], t.subtree[ext as usize]), (9, 81));
        assert_eq!(t.border_contact[ext as usize], 32);
        assert_eq!(t.border_cells_of(ext).len(), 32);
    }

    proptest! {
        #[test]
        fn regions_match_flood_labelling(w in 1usize..12, h in 1usize..12, bits in proptest::collection::vec(0u8..3, 144)) {
            let d: Vec<u8> = (0..w * h).map(|i| bits[i]).collect();
            let t = region_tree(&d, w, h, |v| v == 0);
            let free: Vec<bool> = d.iter().map(|&v| v == 0).collect();
            let non: Vec<bool> = free.iter().map(|f| !f).collect();
            let (fl, fs) = label_components(&free, w, h, Connectivity::Four);
            let (nl, _) = label_components(&non, w, h, Connectivity::Eight);
            // same partition: two cells share a region iff they share a flood label,
            // except non-free regions touching the border, which all merge into the root.
            let touches: Vec<bool> = {
                let mut v = vec![false; nl.iter().copied().max().unwrap_or(0) as usize + 1];
                for i in crate::grid::flood::border_cells(w, h) { if !free[i] { v[nl[i] as usize] = true; } }
                v
            };
            for i in 0..w * h {
                let ri = t.region_at(i % w, i / w);
                prop_assert_eq!(t.free[ri as usize], free[i]);
                if free[i] { prop_assert_eq!(t.size[ri as usize], fs[fl[i] as usize - 1]); }
                if !free[i] && touches[nl[i] as usize] { prop_assert_eq!(ri, t.root); }
                for j in 0..i {
                    let same_flood = if free[i] != free[j] { false } else if free[i] { fl[i] == fl[j] } else {
                        nl[i] == nl[j] || (touches[nl[i] as usize] && touches[nl[j] as usize])
                    };
                    prop_assert_eq!(t.region_at(j % w, j / w) == ri, same_flood);
                }
            }
            // a tree: every region but the root has a parent of the other kind
            for r in 0..t.len() as u32 {
                if r != t.root {
                    let p = t.parent[r as usize];
                    prop_assert!(p != NONE);
                    prop_assert!(t.free[p as usize] != t.free[r as usize]);
                }
            }
            prop_assert_eq!(t.subtree[t.root as usize], w * h);
        }
    }
}
