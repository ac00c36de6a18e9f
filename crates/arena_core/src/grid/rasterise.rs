//! Centreline → ROS occupancy grid (the paper's Eq. 3), with constant or variable width.
//!
//! For a cell centre `x` let `m(x) = min_seg (d(x, seg) − w_seg(t)/2)` where `w_seg(t)` is the
//! full corridor width interpolated linearly along the segment at the nearest point. Then
//! `FREE` where `m ≤ −Δ/2`, `OCCUPIED` where `−Δ/2 < m ≤ t_w`, `UNKNOWN` elsewhere. With a
//! constant width this is exactly Eq. 3 (`d ≤ w/2 − Δ/2` free, `≤ w/2 + t_w` wall); with a
//! variable width it is the union of the per-segment stamps, so a narrowing never punches
//! a wall spike into a neighbouring wider section. Each segment stamps only its bounding
//! box (grown by its half-width plus the wall), so the cost is O(Σ bbox), not O(N·cells).

use super::{OccupancyGrid, FREE, OCCUPIED, UNKNOWN};
use crate::error::{ArenaError, Result};

/// Rasterise a closed centreline (map metres; the last point need not repeat the first).
///
/// * `widths`: full corridor width (m) at each vertex, same length as `centreline`.
/// * `resolution`: metres per cell (Δ); `wall_thickness`: t_w (m); `margin`: extra space
///   (m) of `UNKNOWN` around the outer wall. The origin is chosen so the map covers the
///   whole corridor plus margin, with yaw 0.
pub fn rasterise_centreline(
    centreline: &[[f64; 2]],
    widths: &[f64],
    resolution: f64,
    wall_thickness: f64,
    margin: f64,
) -> Result<OccupancyGrid> {
    check_inputs(centreline, widths, resolution, wall_thickness, margin)?;
    let (pts, ws) = drop_closing_duplicate(centreline, widths);
    let n = pts.len();
    let reach = ws.iter().cloned().fold(0.0, f64::max) / 2.0 + wall_thickness;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in &pts {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let pad = reach + margin + resolution;
    let origin = [lo[0] - pad, lo[1] - pad, 0.0];
    let width = ((hi[0] - lo[0] + 2.0 * pad) / resolution).ceil() as usize;
    let height = ((hi[1] - lo[1] + 2.0 * pad) / resolution).ceil() as usize;
    // Size, extent and origin are checked before the grid is allocated.
    crate::limits::check_grid_header(width, height, resolution, origin)
        .map_err(|e| ArenaError::invalid(format!("rasterise: {e}")))?;
    // Signed margin m(x) per cell (metres), f32 keeps 10-MP maps at 40 MB.
    let mut m = vec![f32::INFINITY; width * height];
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        stamp_segment(
            &mut m,
            width,
            height,
            origin,
            resolution,
            a,
            b,
            ws[i],
            ws[(i + 1) % n],
            wall_thickness,
        );
    }
    let free_bound = -(resolution / 2.0) as f32;
    let wall_bound = wall_thickness as f32;
    let data = m
        .iter()
        .map(|&v| {
            if v <= free_bound {
                FREE
            } else if v <= wall_bound {
                OCCUPIED
            } else {
                UNKNOWN
            }
        })
        .collect();
    Ok(OccupancyGrid {
        width,
        height,
        resolution,
        origin,
        data,
    })
}

/// Constant-width convenience wrapper (the generated tracks).
pub fn rasterise_constant(
    centreline: &[[f64; 2]],
    width_m: f64,
    resolution: f64,
    wall_thickness: f64,
    margin: f64,
) -> Result<OccupancyGrid> {
    rasterise_centreline(
        centreline,
        &vec![width_m; centreline.len()],
        resolution,
        wall_thickness,
        margin,
    )
}

fn check_inputs(c: &[[f64; 2]], w: &[f64], res: f64, tw: f64, margin: f64) -> Result<()> {
    if c.len() < 3 {
        return Err(ArenaError::invalid(format!(
            "rasterise: a closed centreline needs ≥ 3 points, got {}",
            c.len()
        )));
    }
    if w.len() != c.len() {
        return Err(ArenaError::invalid(format!(
            "rasterise: {} widths for {} centreline points; give one width per point",
            w.len(),
            c.len()
        )));
    }
    if let Some(i) = c
        .iter()
        .position(|p| !p[0].is_finite() || !p[1].is_finite())
    {
        return Err(ArenaError::invalid(format!(
            "rasterise: centreline point {i} is not finite"
        )));
    }
    if let Some(i) = w.iter().position(|x| !x.is_finite() || *x <= 0.0) {
        return Err(ArenaError::invalid(format!(
            "rasterise: width {i} = {} must be a positive finite number",
            w[i]
        )));
    }
    if !(res.is_finite() && res > 0.0) {
        return Err(ArenaError::invalid(format!(
            "rasterise: resolution {res} must be > 0"
        )));
    }
    if !(tw.is_finite() && tw > 0.0 && margin.is_finite() && margin >= 0.0) {
        return Err(ArenaError::invalid(format!(
            "rasterise: wall thickness {tw} must be > 0 and margin {margin} ≥ 0"
        )));
    }
    Ok(())
}

fn drop_closing_duplicate(c: &[[f64; 2]], w: &[f64]) -> (Vec<[f64; 2]>, Vec<f64>) {
    let mut n = c.len();
    if n > 3 && crate::geometry::dist(c[0], c[n - 1]) < 1e-12 {
        n -= 1;
    }
    (c[..n].to_vec(), w[..n].to_vec())
}

#[allow(clippy::too_many_arguments)]
fn stamp_segment(
    m: &mut [f32],
    width: usize,
    height: usize,
    origin: [f64; 3],
    res: f64,
    a: [f64; 2],
    b: [f64; 2],
    wa: f64,
    wb: f64,
    tw: f64,
) {
    let reach = wa.max(wb) / 2.0 + tw + res;
    let to_col = |x: f64| ((x - origin[0]) / res).floor();
    let to_v = |y: f64| ((y - origin[1]) / res).floor();
    let c0 = to_col(a[0].min(b[0]) - reach).max(0.0) as usize;
    let c1 = (to_col(a[0].max(b[0]) + reach).max(0.0) as usize).min(width - 1);
    let v0 = to_v(a[1].min(b[1]) - reach).max(0.0) as usize;
    let v1 = (to_v(a[1].max(b[1]) + reach).max(0.0) as usize).min(height - 1);
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let (xlo, xhi) = (a[0].min(b[0]), a[0].max(b[0]));
    let (ylo, yhi) = (a[1].min(b[1]), a[1].max(b[1]));
    for v in v0..=v1 {
        let y = origin[1] + (v as f64 + 0.5) * res;
        let row = height - 1 - v;
        // Cells farther than `reach` from the segment (so from its bounding box) would
        // get m > t_w + Δ, which classifies as UNKNOWN either way: skip them.
        let gap = (ylo - y).max(y - yhi).max(0.0);
        if gap > reach {
            continue;
        }
        let half = (reach * reach - gap * gap).sqrt();
        let lo = ((xlo - half - origin[0]) / res - 0.5).floor() - 1.0;
        let hi = ((xhi + half - origin[0]) / res - 0.5).ceil() + 1.0;
        let (cl, ch) = (c0.max(lo.max(0.0) as usize), c1.min(hi.max(0.0) as usize));
        for c in cl..=ch {
            let x = origin[0] + (c as f64 + 0.5) * res;
            let t = if len2 > 0.0 {
                (((x - a[0]) * dx + (y - a[1]) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (px, py) = (a[0] + t * dx - x, a[1] + t * dy - y);
            let d = (px * px + py * py).sqrt() - (wa + t * (wb - wa)) / 2.0;
            let cell = &mut m[row * width + c];
            if (d as f32) < *cell {
                *cell = d as f32;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn circle(r: f64, n: usize) -> Vec<[f64; 2]> {
        (0..n)
            .map(|i| {
                let a = 2.0 * PI * i as f64 / n as f64;
                [r * a.cos(), r * a.sin()]
            })
            .collect()
    }

    #[test]
    fn circle_matches_eq3_cell_by_cell() {
        let (r, w, res, tw) = (3.0, 1.5, 0.05, 0.15);
        let g = rasterise_constant(&circle(r, 2000), w, res, tw, 0.5).unwrap();
        let mut counts = [0usize; 3];
        for row in 0..g.height {
            for col in 0..g.width {
                let [x, y] = g.cell_center(col, row);
                let d = ((x * x + y * y).sqrt() - r).abs();
                let expect = if d <= w / 2.0 - res / 2.0 {
                    FREE
                } else if d <= w / 2.0 + tw {
                    OCCUPIED
                } else {
                    UNKNOWN
                };
                // The 2000-gon deviates from the circle by < 0.03 mm: only knife-edge cells may differ.
                let near_edge =
                    (d - (w / 2.0 - res / 2.0)).abs() < 1e-3 || (d - (w / 2.0 + tw)).abs() < 1e-3;
                if !near_edge {
                    assert_eq!(g.get(col, row), expect, "cell ({col},{row}) at d = {d}");
                }
                counts[[FREE, OCCUPIED, UNKNOWN]
                    .iter()
                    .position(|&v| v == g.get(col, row))
                    .unwrap()] += 1;
            }
        }
        // Free area ≈ 2πr·(w − Δ) + one cell of half-cell rounding.
        let free_area = counts[0] as f64 * res * res;
        assert!(
            (free_area - 2.0 * PI * r * (w - res)).abs() / (2.0 * PI * r * w) < 0.01,
            "free area {free_area}"
        );
        // The map covers the corridor plus margin on every side.
        assert!(g.origin[0] <= -r - w / 2.0 - tw - 0.5 && g.origin[1] <= -r - w / 2.0 - tw - 0.5);
    }

    #[test]
    fn variable_width_interpolates_along_segment() {
        // Rectangle loop whose width grows from 1 m to 2 m along the bottom edge.
        let c = vec![[0.0, 0.0], [10.0, 0.0], [10.0, 6.0], [0.0, 6.0]];
        let w = vec![1.0, 2.0, 2.0, 1.0];
        let g = rasterise_centreline(&c, &w, 0.02, 0.1, 0.2).unwrap();
        let free_at = |x: f64, y: f64| {
            let (col, row) = g.world_to_cell(x, y).unwrap();
            g.get(col, row) == FREE
        };
        // At x = 5 the local width is 1.5 m: free to ±0.74, wall beyond 0.75.
        assert!(free_at(5.0, 0.70) && !free_at(5.0, 0.80));
        assert!(free_at(1.0, 0.50) && !free_at(1.0, 0.60));
    }

    #[test]
    fn bad_inputs_are_errors() {
        let c = circle(2.0, 10);
        assert!(rasterise_centreline(&c, &[1.0; 3], 0.05, 0.1, 0.0).is_err());
        assert!(rasterise_constant(&c, -1.0, 0.05, 0.1, 0.0).is_err());
        assert!(rasterise_constant(&c, 1.0, 0.0, 0.1, 0.0).is_err());
        assert!(rasterise_constant(&c[..2], 1.0, 0.05, 0.1, 0.0).is_err());
        let mut nan = c.clone();
        nan[3][0] = f64::NAN;
        assert!(rasterise_constant(&nan, 1.0, 0.05, 0.1, 0.0).is_err());
    }
}
