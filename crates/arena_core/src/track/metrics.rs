//! Raster measurements for the validator: corridor and infield topology, the centreline
//! recovered from the raster (sub-cell, as the zero level set of `d_in − d_out`, the
//! medial curve between the inner and outer boundary), and the free width along it.
//!
//! This is deliberately independent of the analytic curve: only the occupancy values
//! are read. (When the builder's `isolate_corridor` is on main, the validator can take
//! its centreline instead; the measurement contract is the same.)

use crate::error::{ArenaError, Result};
use crate::grid::edt::edt;
use crate::grid::flood::{border_cells, label_components, Connectivity};
use crate::grid::{OccupancyGrid, FREE};
use crate::grid::bilinear;
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
pub fn measure_raster(g: &OccupancyGrid) -> Result<RasterTrack> {
    let (w, h) = (g.width, g.height);
    let free = g.mask_of(FREE);
    let (labels, sizes) = label_components(&free, w, h, Connectivity::Four);
    let largest = sizes.iter().copied().max().ok_or_else(|| ArenaError::Corridor("map has no free cells".into()))?;
    let corridor_label = sizes.iter().position(|&s| s == largest).unwrap() as u32 + 1;
    let corridor_components = sizes.iter().filter(|&&s| s * 200 >= largest).count();
    let corridor: Vec<bool> = labels.iter().map(|&l| l == corridor_label).collect();

    // Everything else splits into the region touching the border and enclosed regions.
    let rest: Vec<bool> = corridor.iter().map(|&c| !c).collect();
    let (rl, rs) = label_components(&rest, w, h, Connectivity::Eight);
    let mut touches = vec![false; rs.len() + 1];
    for i in border_cells(w, h) {
        touches[rl[i] as usize] = true;
    }
    let enclosed: Vec<usize> = (1..=rs.len()).filter(|&l| !touches[l]).collect();
    let infields = enclosed.len();
    if infields == 0 {
        return Err(ArenaError::Corridor("the largest free region encloses nothing: no closed loop".into()));
    }
    // The biggest enclosed region is the infield the centreline goes around.
    let infield_label = *enclosed.iter().max_by_key(|&&l| rs[l - 1]).unwrap() as u32;
    let inner: Vec<bool> = rl.iter().map(|&l| l == infield_label).collect();
    let outer: Vec<bool> = rl.iter().zip(&corridor).map(|(&l, &c)| !c && l != infield_label).collect();
    let d_in = edt(&inner, w, h);
    let d_out = edt(&outer, w, h);
    let f: Vec<f32> = d_in.iter().zip(&d_out).map(|(a, b)| a - b).collect();

    let loop_uv = longest_zero_loop(&f, w, h)
        .ok_or_else(|| ArenaError::Corridor("no closed centreline found between the inner and outer walls".into()))?;
    let mut centreline: Vec<[f64; 2]> = loop_uv.iter().map(|&[u, v]| g.grid_to_world(u, v)).collect();
    let mut uv = loop_uv;
    if crate::geometry::signed_area(&centreline) < 0.0 {
        centreline.reverse();
        uv.reverse();
    }
    let width_field: Vec<f32> = d_in.iter().zip(&d_out).map(|(a, b)| a + b - 1.0).collect();
    let widths = uv.iter().map(|&[u, v]| bilinear(&width_field, w, h, u, v) * g.resolution).collect();
    let area = corridor.iter().filter(|&&c| c).count() as f64 * g.resolution * g.resolution;
    let mean_width_m = area / crate::geometry::polyline_length(&centreline, true) + g.resolution / 2.0;
    Ok(RasterTrack { corridor_components, infields, centreline, widths, mean_width_m, extent_m: known_extent(g) })
}

/// Bounding-box size (m) of the cells that are not unknown, in the map's grid axes.
pub fn known_extent(g: &OccupancyGrid) -> [f64; 2] {
    let (mut c0, mut c1, mut r0, mut r1) = (usize::MAX, 0, usize::MAX, 0);
    for r in 0..g.height {
        for c in 0..g.width {
            if g.get(c, r) != crate::grid::UNKNOWN {
                c0 = c0.min(c);
                c1 = c1.max(c);
                r0 = r0.min(r);
                r1 = r1.max(r);
            }
        }
    }
    if c0 == usize::MAX {
        return [0.0, 0.0];
    }
    [(c1 - c0 + 1) as f64 * g.resolution, (r1 - r0 + 1) as f64 * g.resolution]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::rasterise::rasterise_constant;
    use std::f64::consts::PI;

    #[test]
    fn ring_centreline_and_width_are_recovered() {
        let (r, w) = (4.0, 1.5);
        let c: Vec<[f64; 2]> = (0..3000).map(|i| {
            let a = 2.0 * PI * i as f64 / 3000.0;
            [r * a.cos() + 1.0, r * a.sin() - 2.0]
        }).collect();
        let g = rasterise_constant(&c, w, 0.05, 0.15, 0.3).unwrap();
        let t = measure_raster(&g).unwrap();
        assert_eq!((t.corridor_components, t.infields), (1, 1));
        let len = crate::geometry::polyline_length(&t.centreline, true);
        assert!((len - 2.0 * PI * r).abs() / (2.0 * PI * r) < 0.01, "length {len}");
        assert!(crate::geometry::signed_area(&t.centreline) > 0.0);
        for p in &t.centreline {
            let rr = ((p[0] - 1.0).powi(2) + (p[1] + 2.0).powi(2)).sqrt();
            assert!((rr - r).abs() < 0.05, "centreline point off the ring: {rr}");
        }
        assert!((t.mean_width_m - w).abs() <= 0.026, "width {}", t.mean_width_m);
        let local = t.widths.iter().sum::<f64>() / t.widths.len() as f64;
        assert!(local <= w + 0.01 && local >= w - 0.1, "local width {local}");
        let ext = 2.0 * (r + w / 2.0 + 0.15);
        assert!((t.extent_m[0] - ext).abs() < 0.11 && (t.extent_m[1] - ext).abs() < 0.11, "{:?}", t.extent_m);
    }

    #[test]
    fn open_map_is_a_corridor_error() {
        let g = OccupancyGrid::filled(20, 20, 0.1, [0.0; 3], FREE);
        assert!(matches!(measure_raster(&g), Err(ArenaError::Corridor(_))));
    }
}
