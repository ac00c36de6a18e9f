//! The map-to-geometry pipeline shared by the USD stage and the physics worlds:
//!
//! 1. `corridor`: isolate the drivable ring ([`isolate_corridor`]);
//! 2. `crop`: work on the corridor's bounding box plus the margin the barriers need;
//! 3. `distance`: exact EDTs to the corridor, the infield and the outer side, giving the
//!    signed free-space distance `φ` (cells; < 0 in the corridor, 0 on its boundary);
//! 4. `walls`: marching squares on `φ = wall_offset / Δ`, Douglas–Peucker simplified —
//!    the collision walls (free space on the left of each loop);
//! 5. `ducts`: the level set `φ = (wall_offset + tube radius) / Δ` — the corridor border
//!    offset outward by the tube radius, without self-intersections — smoothed and
//!    simplified: the centre lines of the visual air-duct tubes;
//! 6. `centreline`: the medial loop between infield and outer side, smoothed, counter-
//!    clockwise, resampled at `centreline_spacing_m`;
//! 7. `meshes`: extruded walls, swept tubes with rings, floor quad;
//! 8. `roundtrip`: walls re-rasterised (even–odd) → IoU with the corridor, and the
//!    worst deviation of the walls from the exact level set (cells).

use super::centreline::medial_loop;
use super::corridor::{isolate_corridor, Corridor};
use super::params::BuildParams;
use crate::error::{ArenaError, Result};
use crate::geometry::contour::marching_squares;
use crate::geometry::fill::{fill_even_odd, iou};
use crate::geometry::mesh::{extrude_walls, TriMesh};
use crate::geometry::smooth::{resample_closed, simplify_closed, smooth_closed};
use crate::geometry::tube::{bounds, floor_quad, rings_along, sweep_closed_tube};
use crate::geometry::{signed_area, Polyline};
use crate::grid::edt::edt;
use crate::grid::{bilinear, OccupancyGrid};
use std::time::Instant;

/// Everything the builder derives from a map (map-frame metres, Z up).
#[derive(Debug, Clone)]
pub struct Geometry {
    /// Collision wall loops (closed, no repeated end point, free space on the left).
    pub walls: Vec<Polyline>,
    /// Centre lines of the visual ducts (closed).
    pub ducts: Vec<Polyline>,
    /// Medial centreline: closed, counter-clockwise, evenly resampled.
    pub centreline: Polyline,
    pub floor: TriMesh,
    pub wall_mesh: TriMesh,
    /// Ducts and rings (visual only).
    pub barriers: TriMesh,
    /// IoU of the re-rasterised walls' drivable region with the corridor.
    pub iou: f64,
    /// Worst distance (cells) of the simplified walls from the exact level set.
    pub max_wall_deviation_cells: f64,
    pub corridor: Corridor,
    /// Seconds per stage, in pipeline order, ending with "total".
    pub timings: Vec<(&'static str, f64)>,
    /// The parameters used, automatic values resolved.
    pub params: BuildParams,
}

struct Crop {
    c0: usize,
    r0: usize,
    w: usize,
    h: usize,
    /// Grid units of the crop's lower-left corner in the full grid.
    u0: f64,
    v0: f64,
}

impl Crop {
    fn take<T: Copy>(&self, full: &[T], full_w: usize) -> Vec<T> {
        let mut out = Vec::with_capacity(self.w * self.h);
        for r in self.r0..self.r0 + self.h {
            out.extend_from_slice(&full[r * full_w + self.c0..r * full_w + self.c0 + self.w]);
        }
        out
    }
    fn to_world(&self, g: &OccupancyGrid, l: &[[f64; 2]]) -> Polyline {
        l.iter().map(|p| g.grid_to_world(self.u0 + p[0], self.v0 + p[1])).collect()
    }
}

/// Run the whole pipeline. `start` = optional (x, y) seed of the corridor (map metres).
pub fn build_geometry(g: &OccupancyGrid, params: &BuildParams, start: Option<[f64; 2]>) -> Result<Geometry> {
    let t_start = Instant::now();
    let mut timings: Vec<(&'static str, f64)> = Vec::new();
    let mut t = Instant::now();
    let mut lap = |name: &'static str, timings: &mut Vec<(&'static str, f64)>| {
        timings.push((name, t.elapsed().as_secs_f64()));
        t = Instant::now();
    };
    params.validate()?;
    if !(g.resolution.is_finite() && g.resolution > 0.0) || g.data.len() != g.width * g.height {
        return Err(ArenaError::invalid(format!("invalid map: resolution {} and {} cells for {}×{}", g.resolution, g.data.len(), g.width, g.height)));
    }
    let p = params.effective(g.resolution);
    let res = g.resolution;
    let corridor = isolate_corridor(g, start)?;
    lap("corridor", &mut timings);

    let radius = p.tube_diameter_m / 2.0;
    let reach = p.wall_offset_m.max(0.0) + radius * p.ring_scale.max(1.0) + 2.0 * res;
    let margin = (reach / res).ceil() as usize + 2;
    let (bc0, br0, bc1, br1) = corridor.bbox;
    let (c0, r0) = (bc0.saturating_sub(margin), br0.saturating_sub(margin));
    let (c1, r1) = ((bc1 + margin).min(g.width - 1), (br1 + margin).min(g.height - 1));
    let crop = Crop { c0, r0, w: c1 - c0 + 1, h: r1 - r0 + 1, u0: c0 as f64, v0: (g.height - 1 - r1) as f64 };
    let (cw, ch) = (crop.w, crop.h);
    let corr = crop.take(&corridor.mask, g.width);
    let infield = crop.take(&corridor.infield, g.width);
    let outer: Vec<bool> = corr.iter().zip(&infield).map(|(&c, &i)| !c && !i).collect();
    lap("crop", &mut timings);

    let d_corr = edt(&corr, cw, ch);
    let d_inf = edt(&infield, cw, ch);
    let d_out = edt(&outer, cw, ch);
    let phi: Vec<f32> = (0..cw * ch)
        .map(|i| if corr[i] { 0.5 - d_inf[i].min(d_out[i]) } else { d_corr[i] - 0.5 })
        .collect();
    drop(d_corr);
    lap("distance", &mut timings);

    let level = (p.wall_offset_m / res) as f32;
    let tol = p.simplify_tolerance_m / res;
    let walls_uv: Vec<Polyline> = marching_squares(&phi, cw, ch, level).iter().map(|l| simplify_closed(l, tol)).collect();
    let walls: Vec<Polyline> = walls_uv.iter().map(|l| crop.to_world(g, l)).collect();
    lap("walls", &mut timings);

    let duct_level = level + (radius / res) as f32;
    let ducts: Vec<Polyline> = marching_squares(&phi, cw, ch, duct_level)
        .iter()
        .map(|l| crop.to_world(g, &simplify_closed(&smooth_closed(l, p.smoothing_iterations), tol)))
        .collect();
    lap("ducts", &mut timings);

    let medial = medial_loop(&d_inf, &d_out, cw, ch)
        .ok_or_else(|| ArenaError::Corridor("no closed centreline found between the inner and outer walls".into()))?;
    let mut centreline = crop.to_world(g, &smooth_closed(&medial, p.smoothing_iterations));
    if signed_area(&centreline) < 0.0 {
        centreline.reverse();
    }
    let centreline = resample_closed(&centreline, p.centreline_spacing_m);
    lap("centreline", &mut timings);

    let wall_mesh = extrude_walls(&walls, 0.0, p.wall_height_m);
    let mut barriers = TriMesh::default();
    for d in &ducts {
        barriers.append(&sweep_closed_tube(d, radius, radius, p.tube_segments));
        barriers.append(&rings_along(d, p.ring_spacing_m, p.ring_width_m, radius * p.ring_scale, radius, p.tube_segments));
    }
    let pad = radius * p.ring_scale + p.floor_margin_m;
    let b = bounds(&ducts).or_else(|| bounds(&walls)).expect("a corridor has walls");
    let floor = floor_quad(b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad);
    lap("meshes", &mut timings);

    let filled = fill_even_odd(&walls_uv, cw, ch);
    let iou = iou(&filled, &corr);
    let max_wall_deviation_cells = walls_uv.iter().map(|l| max_deviation(l, &phi, cw, ch, level)).fold(0.0, f64::max);
    lap("roundtrip", &mut timings);
    timings.push(("total", t_start.elapsed().as_secs_f64()));
    Ok(Geometry { walls, ducts, centreline, floor, wall_mesh, barriers, iou, max_wall_deviation_cells, corridor, timings, params: p })
}

/// Largest |φ − level| (cells) sampled along a closed loop at ≤ ½-cell spacing.
fn max_deviation(l: &[[f64; 2]], phi: &[f32], w: usize, h: usize, level: f32) -> f64 {
    let n = l.len();
    let mut worst = 0.0f64;
    for i in 0..n {
        let (a, b) = (l[i], l[(i + 1) % n]);
        let steps = ((a[0] - b[0]).hypot(a[1] - b[1]) * 2.0).ceil().max(1.0) as usize;
        for k in 0..steps {
            let s = k as f64 / steps as f64;
            let v = bilinear(phi, w, h, a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]));
            worst = worst.max((v - level as f64).abs());
        }
    }
    worst
}

#[cfg(test)]
#[path = "build_tests.rs"]
mod tests;
