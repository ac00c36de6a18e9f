//! Corridor isolation: which free cells form the drivable ring.
//!
//! Free cells (254) are grouped into 4-connected components, all other cells (walls and
//! unknown) into 8-connected ones, on the grid surrounded by a one-cell ring of
//! non-free padding. With these complementary connectivities the components nest as a
//! tree rooted at the padding (the "outside"): a thin-line map gives
//! outside → exterior free area → outer wall → corridor → inner wall → infield, a filled
//! map outside/walls → corridor → infield. Flood fill on that tree removes the exterior
//! (free cells connected to the map border) and the infield in one linear pass.
//!
//! Default: the corridor is the largest *outermost* free component that does not touch
//! the map border and encloses a significant region (its largest enclosed subtree holds
//! at least 1 % of its own cells) — the infield. With a start pose, the free component
//! under the start is taken instead; if it reaches the map border the walls leak, and
//! the error says where.

use crate::error::{ArenaError, Result};
use crate::grid::flood::{label_components, Connectivity};
use crate::grid::{OccupancyGrid, FREE};
use std::collections::HashSet;

/// The drivable ring of a map.
#[derive(Debug, Clone)]
pub struct Corridor {
    /// Cells of the corridor (row-major like the grid).
    pub mask: Vec<bool>,
    /// Cells of the region the corridor goes around (inner wall, infield and anything
    /// nested in it). Every other non-corridor cell is "outer".
    pub infield: Vec<bool>,
    pub cells: usize,
    /// Enclosed regions inside the corridor: the infield plus obstacles.
    pub holes: usize,
    /// Inclusive bounding box of the corridor cells: (col0, row0, col1, row1).
    pub bbox: (usize, usize, usize, usize),
}

/// Fraction of the corridor's own cell count a hole must reach to count as an infield.
const MIN_INFIELD_FRACTION: f64 = 0.01;

struct Tree {
    /// Node per component: free components first (0..nf), then non-free ones.
    parent: Vec<u32>,
    children: Vec<Vec<u32>>,
    /// Cells in the node's subtree.
    subtree: Vec<usize>,
    size: Vec<usize>,
    nf: usize,
    /// Node of each padded cell.
    node: Vec<u32>,
    touches_border: Vec<bool>,
}

const NONE: u32 = u32::MAX;

fn build_tree(g: &OccupancyGrid) -> Tree {
    let (w, h) = (g.width + 2, g.height + 2);
    let mut free = vec![false; w * h];
    for r in 0..g.height {
        let src = &g.data[r * g.width..(r + 1) * g.width];
        for (c, &v) in src.iter().enumerate() {
            free[(r + 1) * w + c + 1] = v == FREE;
        }
    }
    let (fl, fs) = label_components(&free, w, h, Connectivity::Four);
    let nonfree: Vec<bool> = free.iter().map(|f| !f).collect();
    let (nl, ns) = label_components(&nonfree, w, h, Connectivity::Eight);
    let nf = fs.len();
    let n = nf + ns.len();
    let node: Vec<u32> = (0..w * h).map(|i| if free[i] { fl[i] - 1 } else { nf as u32 + nl[i] - 1 }).collect();
    drop((fl, nl, nonfree));
    let size: Vec<usize> = fs.iter().chain(ns.iter()).copied().collect();

    let mut edges: HashSet<(u32, u32)> = HashSet::new();
    let mut last = (NONE, NONE);
    let mut add = |a: u32, b: u32| {
        if ((a as usize) < nf) != ((b as usize) < nf) {
            let e = if a < b { (a, b) } else { (b, a) };
            if e != last {
                edges.insert(e);
                last = e;
            }
        }
    };
    for r in 0..h {
        for c in 0..w {
            let i = r * w + c;
            if c + 1 < w {
                add(node[i], node[i + 1]);
            }
            if r + 1 < h {
                add(node[i], node[i + w]);
            }
        }
    }
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut edge_list: Vec<(u32, u32)> = edges.into_iter().collect();
    edge_list.sort_unstable();
    for (a, b) in edge_list {
        adj[a as usize].push(b);
        adj[b as usize].push(a);
    }
    // BFS from the padding's component (node of padded cell 0).
    let root = node[0];
    let mut parent = vec![NONE; n];
    let mut children: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut order = vec![root];
    let mut seen = vec![false; n];
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
    let mut subtree = size.clone();
    for &u in order.iter().rev() {
        let p = parent[u as usize];
        if p != NONE {
            subtree[p as usize] += subtree[u as usize];
        }
    }
    let mut touches_border = vec![false; n];
    for c in 0..w {
        for r in [1, h - 2] {
            touches_border[node[r * w + c] as usize] |= free[r * w + c];
        }
    }
    for r in 0..h {
        for c in [1, w - 2] {
            touches_border[node[r * w + c] as usize] |= free[r * w + c];
        }
    }
    Tree { parent, children, subtree, size, nf, node, touches_border }
}

impl Tree {
    /// The child subtree of free node `f` with most cells, if it qualifies as an infield.
    fn infield_of(&self, f: u32) -> Option<u32> {
        let best = self.children[f as usize].iter().copied().max_by_key(|&c| (self.subtree[c as usize], u32::MAX - c))?;
        (self.subtree[best as usize] as f64 >= MIN_INFIELD_FRACTION * self.size[f as usize] as f64
            && self.subtree[best as usize] >= 4)
            .then_some(best)
    }
    fn is_ring(&self, f: u32) -> bool {
        !self.touches_border[f as usize] && self.infield_of(f).is_some()
    }
    /// Padded-grid index → map-frame point of the cell centre.
    fn world(&self, g: &OccupancyGrid, padded: usize) -> [f64; 2] {
        let w = g.width + 2;
        g.cell_center(padded % w - 1, padded / w - 1)
    }
}

fn fmt_xy(p: [f64; 2]) -> String {
    format!("({:.2}, {:.2}) m", p[0], p[1])
}

/// Isolate the drivable corridor; `start` = optional (x, y[, yaw]) seed in map metres.
pub fn isolate_corridor(g: &OccupancyGrid, start: Option<[f64; 2]>) -> Result<Corridor> {
    if g.width == 0 || g.height == 0 {
        return Err(ArenaError::Corridor("empty map: it has no cells".into()));
    }
    if !g.data.contains(&FREE) {
        return Err(ArenaError::Corridor("empty map: no free cells, nothing to drive on".into()));
    }
    let t = build_tree(g);
    let pw = g.width + 2;
    let chosen = match start {
        Some([x, y]) => {
            let (c, r) = g.world_to_cell(x, y).ok_or_else(|| {
                ArenaError::Corridor(format!("start {} is outside the map", fmt_xy([x, y])))
            })?;
            if g.get(c, r) != FREE {
                return Err(ArenaError::Corridor(format!("start {} is not on a free cell (value {})", fmt_xy([x, y]), g.get(c, r))));
            }
            let f = t.node[(r + 1) * pw + c + 1];
            if t.touches_border[f as usize] {
                // Report the border cell of the leaking region nearest to the start.
                let leak = (0..t.node.len())
                    .filter(|&i| t.node[i] == f && is_border(i, pw, g.height + 2))
                    .min_by(|&a, &b| {
                        let (pa, pb) = (t.world(g, a), t.world(g, b));
                        ((pa[0] - x).hypot(pa[1] - y)).total_cmp(&(pb[0] - x).hypot(pb[1] - y))
                    })
                    .unwrap();
                return Err(ArenaError::Corridor(format!(
                    "the walls leak: the free region around the start {} reaches the map border at {} — close the gap in the walls",
                    fmt_xy([x, y]),
                    fmt_xy(t.world(g, leak))
                )));
            }
            if t.infield_of(f).is_none() {
                return Err(ArenaError::Corridor(format!(
                    "no closed corridor: the free region around the start {} encloses no infield",
                    fmt_xy([x, y])
                )));
            }
            f
        }
        None => auto_select(g, &t)?,
    };
    let infield_root = t.infield_of(chosen).expect("chosen ring has an infield");
    let mut in_infield = vec![false; t.parent.len()];
    let mut stack = vec![infield_root];
    while let Some(u) = stack.pop() {
        in_infield[u as usize] = true;
        stack.extend(&t.children[u as usize]);
    }
    let (w, h) = (g.width, g.height);
    let mut mask = vec![false; w * h];
    let mut infield = vec![false; w * h];
    let (mut c0, mut r0, mut c1, mut r1) = (usize::MAX, usize::MAX, 0, 0);
    for r in 0..h {
        for c in 0..w {
            let nd = t.node[(r + 1) * pw + c + 1];
            let i = r * w + c;
            if nd == chosen {
                mask[i] = true;
                (c0, r0, c1, r1) = (c0.min(c), r0.min(r), c1.max(c), r1.max(r));
            } else if in_infield[nd as usize] {
                infield[i] = true;
            }
        }
    }
    Ok(Corridor { mask, infield, cells: t.size[chosen as usize], holes: t.children[chosen as usize].len(), bbox: (c0, r0, c1, r1) })
}

fn is_border(i: usize, w: usize, h: usize) -> bool {
    let (c, r) = (i % w, i / w);
    c == 1 || r == 1 || c == w - 2 || r == h - 2
}

fn auto_select(g: &OccupancyGrid, t: &Tree) -> Result<u32> {
    let rings: Vec<u32> = (0..t.nf as u32).filter(|&f| t.is_ring(f)).collect();
    // Outermost rings only: a ring nested inside another ring is part of its infield.
    let outermost = rings.iter().copied().filter(|&f| {
        let mut p = t.parent[f as usize];
        while p != NONE {
            if (p as usize) < t.nf && t.is_ring(p) {
                return false;
            }
            p = t.parent[p as usize];
        }
        true
    });
    if let Some(best) = outermost.max_by_key(|&f| (t.size[f as usize], u32::MAX - f)) {
        return Ok(best);
    }
    // Diagnose: a free region around an infield that reaches the border is a leak.
    let leaking = (0..t.nf as u32)
        .filter(|&f| t.touches_border[f as usize] && t.infield_of(f).is_some())
        .max_by_key(|&f| t.size[f as usize]);
    let pw = g.width + 2;
    if let Some(f) = leaking {
        let ph = g.height + 2;
        let border: Vec<usize> = (0..t.node.len()).filter(|&i| t.node[i] == f && is_border(i, pw, ph)).collect();
        let at = border[border.len() / 2];
        return Err(ArenaError::Corridor(format!(
            "no closed corridor: the walls leak — the free region around the infield reaches the map border \
             ({} border cells, e.g. at {}); close the gap or pass a start pose inside a closed corridor",
            border.len(),
            fmt_xy(t.world(g, at))
        )));
    }
    let free = g.data.iter().filter(|&&v| v == FREE).count();
    let largest = (0..t.nf).max_by_key(|&f| t.size[f]).unwrap();
    let blank = free * 100 >= g.data.len() * 99;
    Err(ArenaError::Corridor(format!(
        "no closed corridor: no free region encloses an infield{} ({:.1} % of the map is free; the largest free region has {} cells{})",
        if blank { " — the map is blank (no walls)" } else { "" },
        100.0 * free as f64 / g.data.len() as f64,
        t.size[largest],
        if t.touches_border[largest] { " and touches the map border" } else { "" }
    )))
}

#[cfg(test)]
#[path = "corridor_tests.rs"]
mod tests;
