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
use std::collections::HashMap;

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
    let largest = sizes
        .iter()
        .copied()
        .max()
        .ok_or_else(|| ArenaError::Corridor("map has no free cells".into()))?;
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
        return Err(ArenaError::Corridor(
            "the largest free region encloses nothing: no closed loop".into(),
        ));
    }
    // The biggest enclosed region is the infield the centreline goes around.
    let infield_label = *enclosed.iter().max_by_key(|&&l| rs[l - 1]).unwrap() as u32;
    let inner: Vec<bool> = rl.iter().map(|&l| l == infield_label).collect();
    let outer: Vec<bool> = rl
        .iter()
        .zip(&corridor)
        .map(|(&l, &c)| !c && l != infield_label)
        .collect();
    let d_in = edt(&inner, w, h);
    let d_out = edt(&outer, w, h);
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
    let width_field: Vec<f32> = d_in.iter().zip(&d_out).map(|(a, b)| a + b - 1.0).collect();
    let widths = uv
        .iter()
        .map(|&[u, v]| bilinear(&width_field, w, h, u, v) * g.resolution)
        .collect();
    let area = corridor.iter().filter(|&&c| c).count() as f64 * g.resolution * g.resolution;
    let mean_width_m =
        area / crate::geometry::polyline_length(&centreline, true) + g.resolution / 2.0;
    Ok(RasterTrack {
        corridor_components,
        infields,
        centreline,
        widths,
        mean_width_m,
        extent_m: known_extent(g),
    })
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
    [
        (c1 - c0 + 1) as f64 * g.resolution,
        (r1 - r0 + 1) as f64 * g.resolution,
    ]
}

/// Field value at grid point (u, v) in cell units (cell centres at half-integers).
fn bilinear(f: &[f32], w: usize, h: usize, u: f64, v: f64) -> f64 {
    let x = (u - 0.5).clamp(0.0, (w - 1) as f64);
    let y = (v - 0.5).clamp(0.0, (h - 1) as f64);
    let (c0, v0) = (x.floor() as usize, y.floor() as usize);
    let (c1, v1) = ((c0 + 1).min(w - 1), (v0 + 1).min(h - 1));
    let (tx, ty) = (x - c0 as f64, y - v0 as f64);
    let at = |c: usize, vv: usize| f[(h - 1 - vv) * w + c] as f64;
    let a = at(c0, v0) * (1.0 - tx) + at(c1, v0) * tx;
    let b = at(c0, v1) * (1.0 - tx) + at(c1, v1) * tx;
    a * (1.0 - ty) + b * ty
}

/// Marching squares on cell centres: the longest closed zero-crossing loop of `f`, as
/// (u, v) grid coordinates (cell units from the lower-left corner, v up).
fn longest_zero_loop(f: &[f32], w: usize, h: usize) -> Option<Vec<[f64; 2]>> {
    // Sample (c, vv) with vv counted from the bottom.
    let at = |c: usize, vv: usize| f[(h - 1 - vv) * w + c];
    // A crossing lives on a lattice edge: key = (c, vv, dir) with dir 0 = +c, 1 = +vv.
    let key = |c: usize, vv: usize, dir: usize| (vv * w + c) * 2 + dir;
    let mut point: HashMap<usize, [f64; 2]> = HashMap::new();
    let mut adj: HashMap<usize, Vec<usize>> = HashMap::new();
    let crossing = |c: usize, vv: usize, dir: usize| -> [f64; 2] {
        let (a, (c2, v2)) = (at(c, vv), if dir == 0 { (c + 1, vv) } else { (c, vv + 1) });
        let b = at(c2, v2);
        let t = (a / (a - b)) as f64;
        let (x0, y0) = (c as f64 + 0.5, vv as f64 + 0.5);
        if dir == 0 {
            [x0 + t, y0]
        } else {
            [x0, y0 + t]
        }
    };
    for vv in 0..h.saturating_sub(1) {
        for c in 0..w.saturating_sub(1) {
            let v = [at(c, vv), at(c + 1, vv), at(c + 1, vv + 1), at(c, vv + 1)];
            let idx = (v[0] >= 0.0) as u8
                | ((v[1] >= 0.0) as u8) << 1
                | ((v[2] >= 0.0) as u8) << 2
                | ((v[3] >= 0.0) as u8) << 3;
            if idx == 0 || idx == 15 {
                continue;
            }
            // Square edges: 0 bottom, 1 right, 2 top, 3 left.
            let e = [
                key(c, vv, 0),
                key(c + 1, vv, 1),
                key(c, vv + 1, 0),
                key(c, vv, 1),
            ];
            let pos = [(c, vv, 0), (c + 1, vv, 1), (c, vv + 1, 0), (c, vv, 1)];
            let centre_pos = (v.iter().sum::<f32>()) >= 0.0;
            let pairs: &[(usize, usize)] = match idx {
                1 | 14 => &[(3, 0)],
                2 | 13 => &[(0, 1)],
                3 | 12 => &[(3, 1)],
                4 | 11 => &[(1, 2)],
                6 | 9 => &[(0, 2)],
                7 | 8 => &[(3, 2)],
                5 => {
                    if centre_pos {
                        &[(3, 2), (0, 1)]
                    } else {
                        &[(3, 0), (1, 2)]
                    }
                }
                10 => {
                    if centre_pos {
                        &[(3, 0), (1, 2)]
                    } else {
                        &[(3, 2), (0, 1)]
                    }
                }
                _ => &[],
            };
            for &(a, b) in pairs {
                for k in [a, b] {
                    point
                        .entry(e[k])
                        .or_insert_with(|| crossing(pos[k].0, pos[k].1, pos[k].2));
                }
                adj.entry(e[a]).or_default().push(e[b]);
                adj.entry(e[b]).or_default().push(e[a]);
            }
        }
    }
    // Walk loops; keep the longest closed one.
    let mut seen: HashMap<usize, bool> = HashMap::new();
    let mut best: Option<Vec<[f64; 2]>> = None;
    let mut best_len = 0.0;
    let mut starts: Vec<usize> = adj.keys().copied().collect();
    starts.sort_unstable();
    for s in starts {
        if seen.contains_key(&s) || adj[&s].len() != 2 {
            continue;
        }
        let mut path = vec![s];
        seen.insert(s, true);
        let (mut prev, mut cur) = (s, adj[&s][0]);
        let mut closed = false;
        loop {
            if cur == s {
                closed = true;
                break;
            }
            if seen.contains_key(&cur) {
                break;
            }
            seen.insert(cur, true);
            path.push(cur);
            let nb = &adj[&cur];
            if nb.len() != 2 {
                break;
            }
            let next = if nb[0] == prev { nb[1] } else { nb[0] };
            prev = cur;
            cur = next;
        }
        if closed && path.len() >= 3 {
            let pts: Vec<[f64; 2]> = path.iter().map(|k| point[k]).collect();
            let len = crate::geometry::polyline_length(&pts, true);
            if len > best_len {
                best_len = len;
                best = Some(pts);
            }
        }
    }
    best
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

    #[test]
    fn open_map_is_a_corridor_error() {
        let g = OccupancyGrid::filled(20, 20, 0.1, [0.0; 3], FREE);
        assert!(matches!(measure_raster(&g), Err(ArenaError::Corridor(_))));
    }
}
