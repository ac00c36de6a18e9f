//! Open maps: a floor plan with walls but no closed corridor (a hallway with open
//! doorways, a room, a SLAM map that leaks), simulated the way F1TENTH Gym does — the
//! car drives wherever the map is free and collides with every occupied region.
//!
//! The drivable region is every free cell (and, with `unknown_free`, every unknown
//! cell); everything else, and everything beyond the map edge, is wall. The builder
//! ([`super::build::build_around`]) then derives walls, ducts and meshes from it as for
//! a track, but no centreline: there is no lap. The default start pose is the free
//! cell farthest from any wall, heading along the longest free line of sight.

use super::build::{build_around, Geometry};
use super::corridor::Corridor;
use super::params::BuildParams;
use crate::error::{ArenaError, Result};
use crate::grid::edt::edt_within;
use crate::grid::{OccupancyGrid, FREE, UNKNOWN};

/// How an open map reads its cells.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct OpenOptions {
    /// Unknown cells (205) are drivable floor (F1TENTH Gym's 128 threshold reads them so)
    /// instead of walls (nav2's planners with `allow_unknown: false`).
    pub unknown_free: bool,
}

/// An open map's geometry and its default start pose (x, y, yaw; map metres, radians).
#[derive(Debug, Clone)]
pub struct OpenGeometry {
    pub geometry: Geometry,
    pub start: [f64; 3],
    /// Clearance (m) from the default start to the nearest wall cell or map edge (NaN
    /// for a given start).
    pub start_clearance_m: f64,
}

/// The drivable cells of an open map as a [`Corridor`] without an infield.
pub fn open_floor(g: &OccupancyGrid, opts: OpenOptions) -> Result<Corridor> {
    let (w, h) = (g.width, g.height);
    let mask: Vec<bool> = g
        .data
        .iter()
        .map(|&v| v == FREE || (opts.unknown_free && v == UNKNOWN))
        .collect();
    let cells = mask.iter().filter(|&&m| m).count();
    if w == 0 || h == 0 || cells == 0 {
        return Err(ArenaError::Corridor(
            "empty map: no free cells (value 254), nothing to drive on".into(),
        ));
    }
    let (mut c0, mut r0, mut c1, mut r1) = (usize::MAX, usize::MAX, 0, 0);
    let mut border_contact = 0;
    for r in 0..h {
        for c in 0..w {
            if mask[r * w + c] {
                (c0, r0, c1, r1) = (c0.min(c), r0.min(r), c1.max(c), r1.max(r));
                if r == 0 || c == 0 || r + 1 == h || c + 1 == w {
                    border_contact += 1;
                }
            }
        }
    }
    Ok(Corridor {
        infield: vec![false; mask.len()],
        mask,
        cells,
        holes: 0,
        bbox: (c0, r0, c1, r1),
        border_contact,
    })
}

/// Walls, ducts and meshes of an open map, and its start pose: `start` (x, y, yaw) when
/// given — it must lie on a drivable cell — else [`default_start`].
pub fn build_open_geometry(
    g: &OccupancyGrid,
    params: &BuildParams,
    opts: OpenOptions,
    start: Option<[f64; 3]>,
) -> Result<OpenGeometry> {
    let geometry = build_around(g, params, |g| open_floor(g, opts))?;
    let mask = &geometry.corridor.mask;
    let (start, clearance) = match start {
        None => default_start(g, mask),
        Some([x, y, yaw]) => {
            let at = format!("({x:.2}, {y:.2}) m");
            let (c, r) = g
                .world_to_cell(x, y)
                .ok_or_else(|| ArenaError::Corridor(format!("start {at} is outside the map")))?;
            if !mask[r * g.width + c] {
                return Err(ArenaError::Corridor(format!(
                    "start {at} is not on a drivable cell (value {})",
                    g.get(c, r)
                )));
            }
            ([x, y, yaw], f64::NAN)
        }
    };
    Ok(OpenGeometry {
        geometry,
        start,
        start_clearance_m: clearance,
    })
}

/// Headings tried for the default start's line of sight.
const HEADINGS: usize = 72;

/// The drivable cell farthest from any non-drivable cell or the map edge (ties: the
/// first in row-major order), heading along its longest free line of sight (ties: the
/// smallest angle from +x). Returns ((x, y, yaw), clearance m).
pub fn default_start(g: &OccupancyGrid, mask: &[bool]) -> ([f64; 3], f64) {
    let (w, h) = (g.width, g.height);
    // Padded by one wall cell on every side: the map edge is a wall.
    let (pw, ph) = (w + 2, h + 2);
    let mut wall = vec![true; pw * ph];
    for r in 0..h {
        for c in 0..w {
            wall[(r + 1) * pw + c + 1] = !mask[r * w + c];
        }
    }
    let d = edt_within(&wall, pw, ph, (pw + ph) as f64);
    let (mut best, mut at) = (f32::MIN, (0usize, 0usize));
    for r in 0..h {
        for c in 0..w {
            let v = d[(r + 1) * pw + c + 1];
            if mask[r * w + c] && v > best {
                (best, at) = (v, (c, r));
            }
        }
    }
    let (c, r) = at;
    let free = |cc: f64, rr: f64| -> bool {
        let (ci, ri) = (cc.floor(), rr.floor());
        ci >= 0.0
            && ri >= 0.0
            && (ci as usize) < w
            && (ri as usize) < h
            && mask[ri as usize * w + ci as usize]
    };
    let (mut yaw, mut longest) = (0.0, -1.0);
    for k in 0..HEADINGS {
        let a = k as f64 / HEADINGS as f64 * std::f64::consts::TAU;
        // Rows grow downwards in the image: +y in the map is −row.
        let (dc, dr) = (a.cos() * 0.5, -a.sin() * 0.5);
        let (mut cc, mut rr, mut n) = (c as f64 + 0.5, r as f64 + 0.5, 0usize);
        while free(cc + dc, rr + dr) {
            (cc, rr, n) = (cc + dc, rr + dr, n + 1);
        }
        if n as f64 > longest {
            (yaw, longest) = (a, n as f64);
        }
    }
    // Normalise to (−π, π] like the rest of the simulator's yaws.
    if yaw > std::f64::consts::PI {
        yaw -= std::f64::consts::TAU;
    }
    let [x, y] = g.cell_center(c, r);
    ([x, y, yaw], best as f64 * g.resolution)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 60 × 40 room (walls one cell thick) with a 20-cell opening in its right wall, so
    /// the floor reaches the map border: no closed corridor, an open map.
    fn room_with_a_door() -> OccupancyGrid {
        let (w, h) = (60, 40);
        let mut data = vec![FREE; w * h];
        for r in 0..h {
            for c in 0..w {
                let edge = r == 2 || r == h - 3 || c == 2 || c == w - 3;
                let door = c == w - 3 && (10..30).contains(&r);
                if edge && !door {
                    data[r * w + c] = 0;
                }
                if r < 2 || r > h - 3 || c < 2 {
                    data[r * w + c] = UNKNOWN;
                }
            }
        }
        let mut g = OccupancyGrid::filled(w, h, 0.05, [0.0, 0.0, 0.0], FREE);
        g.data = data;
        g
    }

    #[test]
    fn an_open_room_builds_walls_but_no_centreline() {
        let g = room_with_a_door();
        assert!(super::super::build::build_geometry(&g, &BuildParams::default(), None).is_err());
        let o =
            build_open_geometry(&g, &BuildParams::default(), OpenOptions::default(), None).unwrap();
        assert!(o.geometry.centreline.is_empty());
        assert!(!o.geometry.walls.is_empty() && !o.geometry.wall_mesh.triangles.is_empty());
        assert!(o.geometry.iou > 0.95, "iou {}", o.geometry.iou);
        // The start is inside the room, about half its height (36 cells) from the walls.
        let [x, y, _] = o.start;
        assert!(
            (0.2..2.9).contains(&x) && (0.2..1.9).contains(&y),
            "{x} {y}"
        );
        assert!(o.start_clearance_m > 0.6, "{}", o.start_clearance_m);
        let p = BuildParams::default();
        let given = build_open_geometry(&g, &p, OpenOptions::default(), Some([0.5, 0.5, 1.0]));
        assert_eq!(given.unwrap().start, [0.5, 0.5, 1.0]);
        // (0.05, 0.05) is in the unknown margin; (9, 9) is off the map.
        for bad in [[0.05, 0.05, 0.0], [9.0, 9.0, 0.0]] {
            assert!(build_open_geometry(&g, &p, OpenOptions::default(), Some(bad)).is_err());
        }
        // Unknown as floor: the unknown margin joins the drivable region.
        let f = open_floor(&g, OpenOptions { unknown_free: true }).unwrap();
        assert!(f.cells > open_floor(&g, OpenOptions::default()).unwrap().cells);
    }

    #[test]
    fn a_map_without_free_cells_is_refused() {
        let g = OccupancyGrid::filled(8, 8, 0.05, [0.0, 0.0, 0.0], 0);
        assert!(open_floor(&g, OpenOptions::default()).is_err());
    }
}
