//! Raster measurements for the validator: corridor and infield topology, the centreline
//! recovered from the raster (sub-cell, as the zero level set of `d_in − d_out`, the
//! medial curve between the inner and outer boundary), and the free width along it.
//!
//! This is deliberately independent of the analytic curve: only the occupancy values
//! are read. (When the builder's `isolate_corridor` is on main, the validator can take
//! its centreline instead; the measurement contract is the same.)

use crate::error::{ArenaError, Result};
use crate::grid::bilinear_with;
use crate::grid::edt::{edt, edt_within};
use crate::grid::regions::region_tree;
use crate::grid::{OccupancyGrid, FREE};
use crate::track::centreline::longest_zero_loop;

/// What the raster says about the track.
#[derive(Debug, Clone)]
pub struct RasterTrack {
    /// Free components holding ≥ 0.5 % of the largest one's cells.
    pub corridor_components: usize,
    /// Non-corridor components enclosed by the corridor (not touching the map border).
    pub infields: usize,
    /// Closed, counter-clockwise centreline (map metres, no repeated end point).
    pub centreline: Vec<[f64; 2]>,
    /// Length (m) of the closed centreline.
    pub centreline_length_m: f64,
    /// Local free width (m) at each centreline vertex: distance between the nearest wall
    /// cell centres on either side minus one cell (exact on axis-aligned runs, up to ~Δ
    /// low on oblique ones).
    pub widths: Vec<f64>,
    /// Mean free width (m): corridor area / centreline length + Δ/2. Eq. 3 frees a band
    /// of width w − Δ whose cell-centre area lies in [(w − Δ)L, wL]; the Δ/2 midpoint
    /// correction bounds the error by Δ/2 at any orientation.
    pub mean_width_m: f64,
    /// Extent (m) of the non-unknown cells (walls and free): (x, y).
    pub extent_m: [f64; 2],
}

/// Measure a map. Fails with `ArenaError::Corridor` if no closed corridor exists.
///
/// Topology comes from the run-based region tree (`grid::regions`): the corridor is the
/// largest free (4-connected) region; the other cells split into the part outside it and
/// one enclosed component per region the corridor directly encloses (its children with
/// their subtrees), the biggest of which is the infield. The distance fields are capped
/// (`edt_within`); the cap is checked on the corridor, so every value the zero loop and
/// the widths read is exact, and the full transform is the fallback when it is not.
pub fn measure_raster(g: &OccupancyGrid) -> Result<RasterTrack> {
    g.check()?;
    measure_with_cap(g, DISTANCE_CAP)
}

fn measure_with_cap(g: &OccupancyGrid, cap: f64) -> Result<RasterTrack> {
    let (w, h) = (g.width, g.height);
    let tree = region_tree(&g.data, w, h, |v| v == FREE);
    let free_regions = || (0..tree.len()).filter(|&r| tree.free[r]);
    let largest = free_regions()
        .map(|r| tree.size[r])
        .max()
        .ok_or_else(|| ArenaError::Corridor("map has no free cells".into()))?;
    // Region ids follow the raster order of their first cell: ties go to the first.
    let corridor = free_regions().find(|&r| tree.size[r] == largest).unwrap() as u32;
    let corridor_components = free_regions()
        .filter(|&r| tree.size[r] * 200 >= largest)
        .count();
    let mut enclosed = tree.children[corridor as usize].clone();
    enclosed.sort_unstable();
    let infields = enclosed.len();
    if infields == 0 {
        return Err(ArenaError::Corridor(
            "the largest free region encloses nothing: no closed loop".into(),
        ));
    }
    // The biggest enclosed component is the infield the centreline goes around.
    let infield = *enclosed
        .iter()
        .max_by_key(|&&r| tree.subtree[r as usize])
        .unwrap();
    let in_infield = tree.subtree_flags(infield);
    // Corridor runs, and the two sides as EDT feature masks (outer = everything else).
    let mut corridor_runs = Vec::new();
    let mut inner = vec![false; w * h];
    let mut outer = vec![true; w * h];
    for (run, &reg) in tree.runs.iter().zip(&tree.run_region) {
        let cells =
            run.row as usize * w + run.start as usize..run.row as usize * w + run.end as usize;
        if reg == corridor {
            outer[cells.clone()].fill(false);
            corridor_runs.push(cells);
        } else if in_infield[reg as usize] {
            outer[cells.clone()].fill(false);
            inner[cells].fill(true);
        }
    }
    let (d_in, d_out) = corridor_distances(&inner, &outer, &corridor_runs, w, h, cap);
    let f: Vec<f32> = d_in.iter().zip(&d_out).map(|(a, b)| a - b).collect();

    let loop_uv = longest_zero_loop(&f, w, h).ok_or_else(|| {
        ArenaError::Corridor("no closed centreline found between the inner and outer walls".into())
    })?;
    let mut centreline: Vec<[f64; 2]> = loop_uv
        .iter()
        .map(|&[u, v]| g.grid_to_world(u, v))
        .collect();
    let mut uv = loop_uv;
    if crate::geometry::signed_area(&centreline) < 0.0 {
        centreline.reverse();
        uv.reverse();
    }
    let width_at = |i: usize| d_in[i] + d_out[i] - 1.0;
    let widths = uv
        .iter()
        .map(|&[u, v]| bilinear_with(w, h, u, v, width_at) * g.resolution)
        .collect();
    let area = tree.size[corridor as usize] as f64 * g.resolution * g.resolution;
    let centreline_length_m = crate::geometry::polyline_length(&centreline, true);
    let mean_width_m = area / centreline_length_m + g.resolution / 2.0;
    Ok(RasterTrack {
        corridor_components,
        infields,
        centreline,
        centreline_length_m,
        widths,
        mean_width_m,
        extent_m: known_extent(g),
    })
}

/// Cap (cells) of the distance fields; corridors are far narrower at any sane resolution.
const DISTANCE_CAP: f64 = 250.0;

/// Distances (cells) to the inner and outer side, exact on the corridor and its 8-ring.
/// Every other cell lies in one of the two sides, so one distance is 0 there and the
/// other only needs the right sign, which the cap keeps. The marching squares and the
/// width samples read exact values only from corridor cells and their neighbours (a
/// square with a sign change holds a corridor cell: the two sides are not 8-adjacent).
/// Neighbours differ by at most √2, hence the margin of 2 in the check.
fn corridor_distances(
    inner: &[bool],
    outer: &[bool],
    corridor_runs: &[std::ops::Range<usize>],
    w: usize,
    h: usize,
    cap: f64,
) -> (Vec<f32>, Vec<f32>) {
    let d_in = edt_within(inner, w, h, cap);
    let d_out = edt_within(outer, w, h, cap);
    let limit = (cap - 2.0) as f32;
    let ok = corridor_runs.iter().all(|cells| {
        d_in[cells.clone()]
            .iter()
            .chain(&d_out[cells.clone()])
            .all(|&d| d < limit)
    });
    if ok {
        (d_in, d_out)
    } else {
        (edt(inner, w, h), edt(outer, w, h))
    }
}

/// Bounding-box size (m) of the cells that are not unknown, in the map's grid axes.
pub fn known_extent(g: &OccupancyGrid) -> [f64; 2] {
    let (mut c0, mut c1, mut r0, mut r1) = (usize::MAX, 0, usize::MAX, 0);
    for (r, row) in g.data.chunks_exact(g.width.max(1)).enumerate() {
        let Some(first) = row.iter().position(|&v| v != crate::grid::UNKNOWN) else {
            continue;
        };
        let last = row
            .iter()
            .rposition(|&v| v != crate::grid::UNKNOWN)
            .unwrap();
        c0 = c0.min(first);
        c1 = c1.max(last);
        r0 = r0.min(r);
        r1 = r1.max(r);
    }
    if c0 == usize::MAX {
        return [0.0, 0.0];
    }
    [
        (c1 - c0 + 1) as f64 * g.resolution,
        (r1 - r0 + 1) as f64 * g.resolution,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::rasterise::rasterise_constant;
    use std::f64::consts::PI;

    #[test]
    fn ring_centreline_and_width_are_recovered() {
        let (r, w) = (4.0, 1.5);
        let c: Vec<[f64; 2]> = (0..3000)
            .map(|i| {
                let a = 2.0 * PI * i as f64 / 3000.0;
                [r * a.cos() + 1.0, r * a.sin() - 2.0]
            })
            .collect();
        let g = rasterise_constant(&c, w, 0.05, 0.15, 0.3).unwrap();
        let t = measure_raster(&g).unwrap();
        assert_eq!((t.corridor_components, t.infields), (1, 1));
        let len = crate::geometry::polyline_length(&t.centreline, true);
        assert!(
            (len - 2.0 * PI * r).abs() / (2.0 * PI * r) < 0.01,
            "length {len}"
        );
        assert!(crate::geometry::signed_area(&t.centreline) > 0.0);
        for p in &t.centreline {
            let rr = ((p[0] - 1.0).powi(2) + (p[1] + 2.0).powi(2)).sqrt();
            assert!((rr - r).abs() < 0.05, "centreline point off the ring: {rr}");
        }
        assert!(
            (t.mean_width_m - w).abs() <= 0.026,
            "width {}",
            t.mean_width_m
        );
        let local = t.widths.iter().sum::<f64>() / t.widths.len() as f64;
        assert!(local <= w + 0.01 && local >= w - 0.1, "local width {local}");
        let ext = 2.0 * (r + w / 2.0 + 0.15);
        assert!(
            (t.extent_m[0] - ext).abs() < 0.11 && (t.extent_m[1] - ext).abs() < 0.11,
            "{:?}",
            t.extent_m
        );
    }

    fn ring(r: f64, w: f64) -> OccupancyGrid {
        let c: Vec<[f64; 2]> = (0..3000)
            .map(|i| {
                let a = 2.0 * PI * i as f64 / 3000.0;
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        rasterise_constant(&c, w, 0.05, 0.15, 0.3).unwrap()
    }

    fn same(a: &RasterTrack, b: &RasterTrack) -> bool {
        a.centreline == b.centreline
            && a.widths == b.widths
            && a.mean_width_m == b.mean_width_m
            && (a.corridor_components, a.infields) == (b.corridor_components, b.infields)
    }

    #[test]
    fn distance_cap_too_small_falls_back_to_the_exact_fields() {
        // 1.5 m corridor = 30 cells: distances up to ~30 exceed a cap of 8.
        let g = ring(3.0, 1.5);
        let exact = measure_with_cap(&g, f64::INFINITY).unwrap();
        assert!(same(&measure_with_cap(&g, 8.0).unwrap(), &exact));
        assert!(same(&measure_raster(&g).unwrap(), &exact));
    }

    #[test]
    fn topology_counts_islands_and_picks_the_biggest_infield() {
        let mut g = ring(3.0, 1.0);
        let (w, h) = (g.width, g.height);
        let (cx, cy) = (w / 2, h / 2);
        // A wall block in the corridor (second infield) and free cells in the infield
        // (a small free component that belongs to the infield, not a corridor).
        let rc = (3.0 / 0.05) as usize;
        for r in cy - 3..cy + 3 {
            for c in cx + rc - 3..cx + rc + 3 {
                g.data[r * w + c] = crate::grid::OCCUPIED;
            }
        }
        for r in cy - 2..cy + 2 {
            for c in cx - 2..cx + 2 {
                g.data[r * w + c] = FREE;
            }
        }
        let t = measure_raster(&g).unwrap();
        assert_eq!((t.corridor_components, t.infields), (1, 2));
        // The centreline still goes around the big infield.
        let len = crate::geometry::polyline_length(&t.centreline, true);
        assert!((len - 2.0 * PI * 3.0).abs() < 0.5, "length {len}");
    }

    /// The previous implementation (per-cell component labelling, full EDTs): topology
    /// and distance fields as a reference.
    fn reference(g: &OccupancyGrid) -> Option<(usize, usize, Vec<[f64; 2]>, Vec<f64>)> {
        use crate::grid::flood::{border_cells, label_components, Connectivity};
        let (w, h) = (g.width, g.height);
        let (labels, sizes) = label_components(&g.mask_of(FREE), w, h, Connectivity::Four);
        let largest = *sizes.iter().max()?;
        let cl = sizes.iter().position(|&s| s == largest).unwrap() as u32 + 1;
        let corridor: Vec<bool> = labels.iter().map(|&l| l == cl).collect();
        let rest: Vec<bool> = corridor.iter().map(|&c| !c).collect();
        let (rl, rs) = label_components(&rest, w, h, Connectivity::Eight);
        let mut touches = vec![false; rs.len() + 1];
        for i in border_cells(w, h) {
            touches[rl[i] as usize] = true;
        }
        let enclosed: Vec<usize> = (1..=rs.len()).filter(|&l| !touches[l]).collect();
        let il = *enclosed.iter().max_by_key(|&&l| rs[l - 1])? as u32;
        let inner: Vec<bool> = rl.iter().map(|&l| l == il).collect();
        let outer: Vec<bool> = rl
            .iter()
            .zip(&corridor)
            .map(|(&l, &c)| !c && l != il)
            .collect();
        let (d_in, d_out) = (edt(&inner, w, h), edt(&outer, w, h));
        let f: Vec<f32> = d_in.iter().zip(&d_out).map(|(a, b)| a - b).collect();
        let mut uv = longest_zero_loop(&f, w, h)?;
        let mut line: Vec<[f64; 2]> = uv.iter().map(|&[u, v]| g.grid_to_world(u, v)).collect();
        if crate::geometry::signed_area(&line) < 0.0 {
            line.reverse();
            uv.reverse();
        }
        let wf: Vec<f32> = d_in.iter().zip(&d_out).map(|(a, b)| a + b - 1.0).collect();
        let widths = uv
            .iter()
            .map(|&[u, v]| crate::grid::bilinear(&wf, w, h, u, v) * g.resolution)
            .collect();
        let ncomp = sizes.iter().filter(|&&s| s * 200 >= largest).count();
        Some((ncomp, enclosed.len(), line, widths))
    }

    #[test]
    fn matches_the_labelling_reference_bit_for_bit() {
        // A wobbly ring, a figure-of-eight-like pinch, and the ring with islands.
        let wobbly: Vec<[f64; 2]> = (0..2000)
            .map(|i| {
                let a = 2.0 * PI * i as f64 / 2000.0;
                let r = 3.0 + 0.6 * (3.0 * a).sin() + 0.3 * (7.0 * a).cos();
                [r * a.cos(), 0.7 * r * a.sin()]
            })
            .collect();
        let widths: Vec<f64> = (0..2000)
            .map(|i| 0.8 + 0.4 * (i as f64 / 300.0).sin().abs())
            .collect();
        let mut grids = vec![
            crate::grid::rasterise::rasterise_centreline(&wobbly, &widths, 0.05, 0.15, 0.3)
                .unwrap(),
            ring(2.0, 1.2),
        ];
        let mut g = ring(3.0, 1.0);
        let (w, cx, cy) = (g.width, g.width / 2, g.height / 2);
        for r in cy - 3..cy + 3 {
            for c in cx + 57..cx + 63 {
                g.data[r * w + c] = crate::grid::OCCUPIED;
            }
        }
        for r in cy - 2..cy + 2 {
            for c in cx - 2..cx + 2 {
                g.data[r * w + c] = FREE;
            }
        }
        grids.push(g);
        for g in &grids {
            let (n, inf, line, widths) = reference(g).unwrap();
            let t = measure_raster(g).unwrap();
            assert_eq!((t.corridor_components, t.infields), (n, inf));
            assert!(t.centreline == line && t.widths == widths);
        }
    }

    #[test]
    fn open_map_is_a_corridor_error() {
        let g = OccupancyGrid::filled(20, 20, 0.1, [0.0; 3], FREE);
        assert!(matches!(measure_raster(&g), Err(ArenaError::Corridor(_))));
    }
}
