//! Corridor isolation: which free cells form the drivable ring.
//!
//! Free cells (254) are grouped into 4-connected components, all other cells (walls and
//! unknown) into 8-connected ones, on the grid surrounded by a one-cell ring of
//! non-free padding ([`crate::grid::regions`], linear time on row runs). With these complementary connectivities the components nest as a
//! tree rooted at the padding (the "outside"): a thin-line map gives
//! outside → exterior free area → outer wall → corridor → inner wall → infield, a filled
//! map outside/walls → corridor → infield. Flood fill on that tree removes the exterior
//! (free cells connected to the map border) and the infield in one linear pass.
//!
//! Default: the corridor is the largest *outermost* free component that does not leak
//! and encloses a significant region (its largest enclosed subtree holds at least 1 % of
//! its own cells) — the infield. With a start pose, the free component under the start
//! is taken instead.
//!
//! A component *leaks* when it reaches the map border along more than 2 % of the border
//! cells: that is the exterior of a thin-line map (or a corridor merged with it through
//! a gap in the wall), and the error says where. A ring that merely touches the border
//! at a few cells (e.g. `vegas`, whose track grazes the image corner, or a SLAM map whose
//! hallway runs off the edge) is accepted: the map edge acts as a wall there, as it does
//! for every simulator, and [`Corridor::border_contact`] reports how many cells touch it.

use crate::error::{ArenaError, Result};
use crate::grid::regions::{region_tree, RegionTree, NONE};
use crate::grid::{OccupancyGrid, FREE};

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
    /// Corridor cells on the map border (the map edge closes the corridor there).
    pub border_contact: usize,
}

/// Fraction of the corridor's own cell count a hole must reach to count as an infield.
const MIN_INFIELD_FRACTION: f64 = 0.01;
/// Fraction of the map's border cells a free region may touch before it counts as leaking.
const MAX_BORDER_FRACTION: f64 = 0.02;

/// The region tree plus the corridor rules on top of it.
struct Tree {
    t: RegionTree,
    /// Border contact above which a free region leaks.
    leak_threshold: f64,
}

impl Tree {
    fn new(g: &OccupancyGrid) -> Self {
        let t = region_tree(&g.data, g.width, g.height, |v| v == FREE);
        let border_total = (2 * (g.width + g.height)).saturating_sub(4).max(1);
        Tree {
            t,
            leak_threshold: MAX_BORDER_FRACTION * border_total as f64,
        }
    }
    /// The child subtree of free region `f` with most cells, if it qualifies as an infield.
    fn infield_of(&self, f: u32) -> Option<u32> {
        let t = &self.t;
        let best = t.children[f as usize]
            .iter()
            .copied()
            .max_by_key(|&c| (t.subtree[c as usize], u32::MAX - c))?;
        (t.subtree[best as usize] as f64 >= MIN_INFIELD_FRACTION * t.size[f as usize] as f64
            && t.subtree[best as usize] >= 4)
            .then_some(best)
    }
    fn leaks(&self, f: u32) -> bool {
        self.t.border_contact[f as usize] as f64 > self.leak_threshold
    }
    fn is_ring(&self, f: u32) -> bool {
        self.t.free[f as usize] && !self.leaks(f) && self.infield_of(f).is_some()
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
        return Err(ArenaError::Corridor(
            "empty map: no free cells (value 254), nothing to drive on".into(),
        ));
    }
    let t = Tree::new(g);
    let chosen = match start {
        Some([x, y]) => {
            let (c, r) = g.world_to_cell(x, y).ok_or_else(|| {
                ArenaError::Corridor(format!("start {} is outside the map", fmt_xy([x, y])))
            })?;
            if g.get(c, r) != FREE {
                return Err(ArenaError::Corridor(format!(
                    "start {} is not on a free cell (value {})",
                    fmt_xy([x, y]),
                    g.get(c, r)
                )));
            }
            let f = t.t.region_at(c, r);
            if t.leaks(f) {
                // Report the border cell of the leaking region nearest to the start.
                let leak =
                    t.t.border_cells_of(f)
                        .into_iter()
                        .map(|(c, r)| g.cell_center(c, r))
                        .min_by(|a, b| {
                            (a[0] - x)
                                .hypot(a[1] - y)
                                .total_cmp(&(b[0] - x).hypot(b[1] - y))
                        })
                        .expect("a leaking region has border cells");
                return Err(ArenaError::Corridor(format!(
                    "the walls leak: the free region around the start {} reaches the map border at {} — close the gap in the walls",
                    fmt_xy([x, y]),
                    fmt_xy(leak)
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
    let in_infield = t.t.subtree_flags(infield_root);
    let w = g.width;
    let mut mask = vec![false; w * g.height];
    let mut infield = vec![false; w * g.height];
    let (mut c0, mut r0, mut c1, mut r1) = (usize::MAX, usize::MAX, 0, 0);
    for (run, &reg) in t.t.runs.iter().zip(&t.t.run_region) {
        let (r, a, b) = (run.row as usize, run.start as usize, run.end as usize);
        if reg == chosen {
            mask[r * w + a..r * w + b].fill(true);
            (c0, r0, c1, r1) = (c0.min(a), r0.min(r), c1.max(b - 1), r1.max(r));
        } else if in_infield[reg as usize] {
            infield[r * w + a..r * w + b].fill(true);
        }
    }
    Ok(Corridor {
        mask,
        infield,
        cells: t.t.size[chosen as usize],
        holes: t.t.children[chosen as usize].len(),
        bbox: (c0, r0, c1, r1),
        border_contact: t.t.border_contact[chosen as usize],
    })
}

fn auto_select(g: &OccupancyGrid, t: &Tree) -> Result<u32> {
    let tt = &t.t;
    let rings: Vec<u32> = (0..tt.len() as u32).filter(|&f| t.is_ring(f)).collect();
    // Outermost rings only: a ring nested inside another ring is part of its infield.
    let outermost = rings.iter().copied().filter(|&f| {
        let mut p = tt.parent[f as usize];
        while p != NONE {
            if t.is_ring(p) {
                return false;
            }
            p = tt.parent[p as usize];
        }
        true
    });
    if let Some(best) = outermost.max_by_key(|&f| (tt.size[f as usize], u32::MAX - f)) {
        return Ok(best);
    }
    // Diagnose: a free region around an infield that reaches the border is a leak.
    let leaking = (0..tt.len() as u32)
        .filter(|&f| tt.free[f as usize] && t.leaks(f) && t.infield_of(f).is_some())
        .max_by_key(|&f| tt.size[f as usize]);
    if let Some(f) = leaking {
        let border = tt.border_cells_of(f);
        let (c, r) = border[border.len() / 2];
        return Err(ArenaError::Corridor(format!(
            "no closed corridor: the walls leak — the free region around the infield reaches the map border \
             ({} border cells, e.g. at {}); close the gap or pass a start pose inside a closed corridor",
            border.len(),
            fmt_xy(g.cell_center(c, r))
        )));
    }
    let free = g.data.iter().filter(|&&v| v == FREE).count();
    let largest = (0..tt.len())
        .filter(|&f| tt.free[f])
        .max_by_key(|&f| tt.size[f])
        .expect("the map has free cells");
    let blank = free * 100 >= g.data.len() * 99;
    Err(ArenaError::Corridor(format!(
        "no closed corridor: no free region encloses an infield{} ({:.1} % of the map is free; the largest free region has {} cells{})",
        if blank { " — the map is blank (no walls)" } else { "" },
        100.0 * free as f64 / g.data.len() as f64,
        tt.size[largest],
        if tt.border_contact[largest] > 0 { " and touches the map border" } else { "" }
    )))
}

#[cfg(test)]
#[path = "corridor_tests.rs"]
mod tests;
