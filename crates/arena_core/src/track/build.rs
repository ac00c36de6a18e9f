//! The map-to-geometry pipeline shared by the USD stage and the physics worlds:
//!
//! 1. `corridor`: isolate the drivable ring ([`isolate_corridor`]);
//! 2. `crop`: work on the corridor's bounding box plus the margin the barriers need;
//! 3. `distance`: three exact EDTs, each capped where larger values are never read:
//!    to the infield and to the outer side (up to the widest inscribed radius), whose
//!    minimum is φ inside the corridor, and to the corridor (up to the duct level), φ
//!    outside — the signed free-space distance `φ` (cells; < 0 in the corridor);
//! 4. `walls`: marching squares on `φ = wall_offset / Δ`, Douglas–Peucker simplified —
//!    the collision walls (free space on the left of each loop);
//! 5. `ducts`: the level set `φ = (wall_offset + tube radius) / Δ` — the corridor border
//!    offset outward by the tube radius, without self-intersections — smoothed and
//!    simplified: the centre lines of the visual air-duct tubes;
//! 6. `centreline`: the medial loop between infield and outer side, smoothed
//!    (5 × `smoothing_iterations` Taubin passes), counter-clockwise, resampled at
//!    `centreline_spacing_m`;
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
use crate::geometry::tube::{bounds, closed_tube_mesh, closed_tube_st, floor_quad, rings_along};
use crate::geometry::{signed_area, Polyline};
use crate::grid::edt::edt_within;
use crate::grid::{bilinear, OccupancyGrid};
use std::time::Instant;

/// Everything the builder derives from a map (map-frame metres, Z up).
#[derive(Debug, Clone)]
pub struct Geometry {
    /// Collision wall loops (closed, no repeated end point, free space on the left).
    pub walls: Vec<Polyline>,
    /// Centre lines of the visual ducts (closed).
    pub ducts: Vec<Polyline>,
    /// Medial centreline: closed, counter-clockwise, evenly resampled; empty for an
    /// open map (no corridor ring).
    pub centreline: Polyline,
    pub floor: TriMesh,
    pub wall_mesh: TriMesh,
    /// Visual duct tubes: per duct, `n` cross-sections of `tube_segments` vertices,
    /// quads `[p, t, r], [p, q, t]` (see `geometry::tube`), ducts one after another.
    pub duct_mesh: TriMesh,
    /// Texture coordinates of `duct_mesh`, face-varying: `(u` metres along the duct, `v`
    /// 0..1 around it) values and one index per triangle corner (`geometry::tube::closed_tube_st`).
    pub duct_st: (Vec<[f32; 2]>, Vec<u32>),
    /// Visual rings around the ducts, every `ring_spacing_m`.
    pub ring_mesh: TriMesh,
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

/// Smoothing passes of the centreline per `smoothing_iterations`.
const CENTRELINE_SMOOTHING: usize = 5;

/// The working window: the corridor's bounding box plus a margin, extending at most
/// one cell beyond the map where the corridor touches its edge. Cells beyond the map
/// count as outer (the map edge is a wall), so every distance sees it.
struct Crop {
    /// Column and row of the window's top-left cell in the map (may be −1).
    c0: i64,
    r0: i64,
    w: usize,
    h: usize,
    /// Grid units of the window's lower-left corner in the map.
    u0: f64,
    v0: f64,
}

impl Crop {
    fn new(g: &OccupancyGrid, bbox: (usize, usize, usize, usize), margin: usize) -> Self {
        let (bc0, br0, bc1, br1) = bbox;
        let m = margin as i64;
        let c0 = (bc0 as i64 - m).max(-1);
        let r0 = (br0 as i64 - m).max(-1);
        let c1 = (bc1 as i64 + m).min(g.width as i64);
        let r1 = (br1 as i64 + m).min(g.height as i64);
        let (w, h) = ((c1 - c0 + 1) as usize, (r1 - r0 + 1) as usize);
        Crop {
            c0,
            r0,
            w,
            h,
            u0: c0 as f64,
            v0: (g.height as i64 - 1 - r1) as f64,
        }
    }
    /// The window of a full-map mask; `false` beyond the map.
    fn take(&self, full: &[bool], full_w: usize, full_h: usize) -> Vec<bool> {
        let mut out = vec![false; self.w * self.h];
        let cols = self.c0.max(0)..(self.c0 + self.w as i64).min(full_w as i64);
        for (k, r) in (self.r0..self.r0 + self.h as i64).enumerate() {
            if r < 0 || r >= full_h as i64 {
                continue;
            }
            let dst = k * self.w + (cols.start - self.c0) as usize;
            let src = r as usize * full_w;
            out[dst..dst + cols.clone().count()]
                .copy_from_slice(&full[src + cols.start as usize..src + cols.end as usize]);
        }
        out
    }
    fn to_world(&self, g: &OccupancyGrid, l: &[[f64; 2]]) -> Polyline {
        l.iter()
            .map(|p| g.grid_to_world(self.u0 + p[0], self.v0 + p[1]))
            .collect()
    }
}

/// Run the whole pipeline. `start` = optional (x, y) seed of the corridor (map metres).
pub fn build_geometry(
    g: &OccupancyGrid,
    params: &BuildParams,
    start: Option<[f64; 2]>,
) -> Result<Geometry> {
    build_around(g, params, |g| isolate_corridor(g, start))
}

/// The pipeline on the drivable region `region` finds. A region with no infield (an
/// open map's floor, `super::open`) gets walls, ducts and meshes but no centreline
/// (an empty one).
pub(super) fn build_around(
    g: &OccupancyGrid,
    params: &BuildParams,
    region: impl FnOnce(&OccupancyGrid) -> Result<Corridor>,
) -> Result<Geometry> {
    let mut clock = Stopwatch::new();
    params.validate()?;
    g.check()?;
    let p = params.effective(g.resolution);
    let res = g.resolution;
    let corridor = region(g)?;
    let ring = corridor.infield.contains(&true);
    clock.lap("corridor");

    let radius = p.tube_diameter_m / 2.0;
    let win = Window::new(g, &corridor, &p);
    let (crop, cw, ch) = (&win.crop, win.crop.w, win.crop.h);
    clock.lap("crop");

    let level = (p.wall_offset_m / res) as f32;
    let duct_level = level + (radius / res) as f32;
    let dist = Distances::new(&win, level, duct_level);
    let phi = &dist.phi;
    clock.lap("distance");

    let tol = p.simplify_tolerance_m / res;
    let walls_uv: Vec<Polyline> = marching_squares(phi, cw, ch, level)
        .iter()
        .map(|l| simplify_closed(l, tol))
        .collect();
    let walls: Vec<Polyline> = walls_uv.iter().map(|l| crop.to_world(g, l)).collect();
    clock.lap("walls");

    let ducts: Vec<Polyline> = marching_squares(phi, cw, ch, duct_level)
        .iter()
        .map(|l| {
            crop.to_world(
                g,
                &simplify_closed(&smooth_closed(l, p.smoothing_iterations), tol),
            )
        })
        .collect();
    clock.lap("ducts");

    let centreline = if ring {
        centreline_of(g, crop, &dist.d_inf, &dist.d_out, &p)?
    } else {
        Vec::new()
    };
    clock.lap("centreline");

    if walls.is_empty() {
        return Err(ArenaError::Corridor(format!(
            "no collision walls at wall_offset_m = {} m: the offset leaves no corridor \
             (use a value closer to 0)",
            p.wall_offset_m
        )));
    }
    let meshes = Meshes::new(&walls, &ducts, &p)?;
    clock.lap("meshes");

    let filled = fill_even_odd(&walls_uv, cw, ch);
    let iou = iou(&filled, &win.corr);
    let max_wall_deviation_cells = walls_uv
        .iter()
        .map(|l| max_deviation(l, phi, cw, ch, level))
        .fold(0.0, f64::max);
    clock.lap("roundtrip");
    Ok(Geometry {
        walls,
        ducts,
        centreline,
        floor: meshes.floor,
        wall_mesh: meshes.wall_mesh,
        duct_mesh: meshes.duct_mesh,
        duct_st: meshes.duct_st,
        ring_mesh: meshes.ring_mesh,
        iou,
        max_wall_deviation_cells,
        corridor,
        timings: clock.total(),
        params: p,
    })
}

/// Seconds per pipeline stage, in order, ending with "total".
struct Stopwatch {
    start: Instant,
    lap_start: Instant,
    timings: Vec<(&'static str, f64)>,
}

impl Stopwatch {
    fn new() -> Self {
        Stopwatch {
            start: Instant::now(),
            lap_start: Instant::now(),
            timings: Vec::new(),
        }
    }

    /// Record the stage `name` as the time since the last lap.
    fn lap(&mut self, name: &'static str) {
        self.timings
            .push((name, self.lap_start.elapsed().as_secs_f64()));
        self.lap_start = Instant::now();
    }

    fn total(mut self) -> Vec<(&'static str, f64)> {
        self.timings
            .push(("total", self.start.elapsed().as_secs_f64()));
        self.timings
    }
}

/// The crop stage: the window around the corridor, with the corridor, infield and
/// outer masks cut to it.
struct Window {
    crop: Crop,
    corr: Vec<bool>,
    infield: Vec<bool>,
    outer: Vec<bool>,
}

impl Window {
    /// The window keeps the margin the walls, ducts and rings reach beyond the corridor.
    fn new(g: &OccupancyGrid, corridor: &Corridor, p: &BuildParams) -> Self {
        let res = g.resolution;
        let radius = p.tube_diameter_m / 2.0;
        let reach = p.wall_offset_m.max(0.0) + radius * p.ring_scale.max(1.0) + 2.0 * res;
        let margin = (reach / res).ceil() as usize + 2;
        let crop = Crop::new(g, corridor.bbox, margin);
        let corr = crop.take(&corridor.mask, g.width, g.height);
        let infield = crop.take(&corridor.infield, g.width, g.height);
        let outer: Vec<bool> = corr.iter().zip(&infield).map(|(&c, &i)| !c && !i).collect();
        Window {
            crop,
            corr,
            infield,
            outer,
        }
    }
}

/// The distance stage: distances (cells) to the infield and to the outer side, and the
/// signed free-space distance `phi` (< 0 in the corridor).
struct Distances {
    d_inf: Vec<f32>,
    d_out: Vec<f32>,
    phi: Vec<f32>,
}

impl Distances {
    /// Each transform capped where larger values are never read, for the wall level and
    /// the duct level (cells).
    fn new(win: &Window, level: f32, duct_level: f32) -> Self {
        let (cw, ch) = (win.crop.w, win.crop.h);
        // Distances to the infield and to the outer side. Inside the corridor their
        // minimum is the distance to the nearest non-corridor cell (φ inside), and the
        // medial loop lies where they are equal, i.e. at most the widest inscribed radius
        // r_max away. So both are needed only up to r_max + 2 (u8 column distances for
        // corridors up to ~500 cells wide); a cheap upper bound of r_max sets the cap.
        let cap = inscribed_radius_bound(&win.corr, cw, ch) + 2.0;
        // φ outside is only read up to the duct level (+ a margin for interpolation).
        let band = (duct_level.max(level) as f64).max(0.0) + 3.0;
        // The three transforms are independent: run them side by side when threads allow.
        let ((d_inf, d_out), d_corr) = rayon::join(
            || {
                rayon::join(
                    || edt_within(&win.infield, cw, ch, cap),
                    || edt_within(&win.outer, cw, ch, cap),
                )
            },
            || edt_within(&win.corr, cw, ch, band),
        );
        let d_nc: Vec<f32> = d_inf.iter().zip(&d_out).map(|(a, b)| a.min(*b)).collect();
        let phi: Vec<f32> = (0..cw * ch)
            .map(|i| {
                if win.corr[i] {
                    0.5 - d_nc[i]
                } else {
                    d_corr[i] - 0.5
                }
            })
            .collect();
        Distances { d_inf, d_out, phi }
    }
}

/// The meshes stage: extruded walls, duct tubes (with texture coordinates), rings and
/// the floor.
struct Meshes {
    wall_mesh: TriMesh,
    duct_mesh: TriMesh,
    duct_st: (Vec<[f32; 2]>, Vec<u32>),
    ring_mesh: TriMesh,
    floor: TriMesh,
}

impl Meshes {
    /// Refuses a ring spacing whose rings would exceed the derived-count limit.
    fn new(walls: &[Polyline], ducts: &[Polyline], p: &BuildParams) -> Result<Self> {
        let radius = p.tube_diameter_m / 2.0;
        if p.ring_spacing_m > 0.0 {
            let duct_length: f64 = ducts
                .iter()
                .map(|d| crate::geometry::polyline_length(d, true))
                .sum();
            // Each ring is a band of 2 × tube_segments vertices: bound the mesh, not the
            // rings.
            crate::limits::derived_count_each(
                "geometry.ring_spacing_m",
                duct_length,
                p.ring_spacing_m,
                2 * p.tube_segments,
            )?;
        }
        let wall_mesh = extrude_walls(walls, 0.0, p.wall_height_m);
        let (mut duct_mesh, mut ring_mesh) = (TriMesh::default(), TriMesh::default());
        let mut duct_st: (Vec<[f32; 2]>, Vec<u32>) = Default::default();
        for d in ducts {
            duct_mesh.append(&closed_tube_mesh(d, radius, radius, p.tube_segments));
            let (st, idx) = closed_tube_st(d, p.tube_segments);
            let base = duct_st.0.len() as u32;
            duct_st.1.extend(idx.into_iter().map(|i| i + base));
            duct_st.0.extend(st);
            ring_mesh.append(&rings_along(
                d,
                p.ring_spacing_m,
                p.ring_width_m,
                radius * p.ring_scale,
                radius,
                p.tube_segments,
            ));
        }
        let pad = radius * p.ring_scale + p.floor_margin_m;
        let b = bounds(ducts)
            .or_else(|| bounds(walls))
            .expect("a corridor has walls");
        let floor = floor_quad(b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad);
        Ok(Meshes {
            wall_mesh,
            duct_mesh,
            duct_st,
            ring_mesh,
            floor,
        })
    }
}

/// The medial loop between infield and outer side, smoothed, counter-clockwise, resampled.
fn centreline_of(
    g: &OccupancyGrid,
    crop: &Crop,
    d_inf: &[f32],
    d_out: &[f32],
    p: &BuildParams,
) -> Result<Polyline> {
    let medial = medial_loop(d_inf, d_out, crop.w, crop.h).ok_or_else(|| {
        ArenaError::Corridor("no closed centreline found between the inner and outer walls".into())
    })?;
    // The medial curve of a raster corridor zig-zags by up to half a cell: smooth it more.
    let mut centreline = crop.to_world(
        g,
        &smooth_closed(&medial, CENTRELINE_SMOOTHING * p.smoothing_iterations),
    );
    if signed_area(&centreline) < 0.0 {
        centreline.reverse();
    }
    crate::limits::derived_count(
        "geometry.centreline_spacing_m",
        crate::geometry::polyline_length(&centreline, true),
        p.centreline_spacing_m,
    )?;
    Ok(resample_closed(&centreline, p.centreline_spacing_m))
}

/// An upper bound (cells) of the largest disc inside the corridor: at every corridor
/// cell the distance to the nearest other cell is at most the distance along its
/// column and along its row. Linear (three sweeps), no square roots.
fn inscribed_radius_bound(corr: &[bool], w: usize, h: usize) -> f64 {
    // down[i]: corridor cells from i upwards to the nearest non-corridor cell (1 = adjacent)
    let mut down = vec![0u16; w * h];
    for r in 0..h {
        for c in 0..w {
            let i = r * w + c;
            down[i] = if !corr[i] {
                0
            } else if r == 0 {
                1
            } else {
                down[i - w].saturating_add(1)
            };
        }
    }
    let mut up = vec![0u16; w];
    let mut left = vec![0u16; w];
    let mut best = 0u16;
    for r in (0..h).rev() {
        let row = &corr[r * w..(r + 1) * w];
        for c in 0..w {
            up[c] = if row[c] { up[c].saturating_add(1) } else { 0 };
            left[c] = if !row[c] {
                0
            } else if c == 0 {
                1
            } else {
                left[c - 1].saturating_add(1)
            };
        }
        let mut right = 0u16;
        for c in (0..w).rev() {
            right = if row[c] { right.saturating_add(1) } else { 0 };
            if row[c] {
                let d = down[r * w + c].min(up[c]).min(left[c]).min(right);
                best = best.max(d);
            }
        }
    }
    best as f64
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
            let v = bilinear(
                phi,
                w,
                h,
                a[0] + s * (b[0] - a[0]),
                a[1] + s * (b[1] - a[1]),
            );
            worst = worst.max((v - level as f64).abs());
        }
    }
    worst
}

#[cfg(test)]
#[path = "build_tests.rs"]
mod tests;
