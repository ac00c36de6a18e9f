//! A drivable track: closed wall polylines and a closed centreline in map-frame metres.
//!
//! Built once and shared (`Arc<Track>`) by every world that drives on it:
//! * `wall_shape`: ONE rapier trimesh (the walls extruded by
//!   [`crate::geometry::mesh::extrude_walls`], the very mesh the USD stage gets) whose
//!   `SharedShape` is an `Arc`, so N worlds reference it without copying;
//! * `grid`: a uniform grid over the wall segments for exact 2D lidar casts;
//! * `centreline`: arc-length tables for progress, laps and reset poses.

use rapier3d::prelude::{SharedShape, Vector};

use super::segments::SegmentGrid;
use crate::error::{ArenaError, Result};
use crate::geometry::mesh::extrude_walls;
use crate::geometry::polyline::cumulative_length;

/// Tallest collision wall a track accepts (m): far above any barrier a 1:10 car meets, low
/// enough that a unit mix-up (mm for m) is refused instead of built.
pub const MAX_WALL_HEIGHT_M: f64 = 10.0;

/// Closed polyline with cumulative arc length, for projection and interpolation.
///
/// Or, for an *open map* (a floor plan with walls but no closed corridor), an *anchor*:
/// two distinct points, the default start at the first heading to the second. An anchor
/// has length 0: no progress, no laps; [`Centreline::pose_at`] moves along its heading
/// (behind it for `s < 0`, where a grid of several cars lines up).
#[derive(Debug, Clone)]
pub struct Centreline {
    pts: Vec<[f64; 2]>,
    /// `cum[i]` = arc length at `pts[i]`; `cum[n]` = total length (closing edge included).
    cum: Vec<f64>,
    /// The start pose (x, y, heading) of an open map's anchor.
    anchor: Option<[f64; 3]>,
}

impl Centreline {
    /// A closed centreline (a repeated closing point is dropped), or an open map's
    /// anchor when it has exactly two distinct points.
    pub fn new(points: &[[f64; 2]]) -> Result<Self> {
        let pts = dedupe_closed(points);
        if pts.iter().flatten().any(|v| !v.is_finite()) {
            return Err(ArenaError::invalid("centreline has non-finite coordinates"));
        }
        if pts.len() == 2 {
            let (a, b) = (pts[0], pts[1]);
            let anchor = Some([a[0], a[1], (b[1] - a[1]).atan2(b[0] - a[0])]);
            return Ok(Centreline {
                pts,
                cum: vec![0.0; 3],
                anchor,
            });
        }
        if pts.len() < 3 {
            return Err(ArenaError::invalid(
                "centreline needs at least 3 distinct points (2 for an open map's start anchor)",
            ));
        }
        let cum = cumulative_length(&pts, true);
        Ok(Centreline {
            pts,
            cum,
            anchor: None,
        })
    }

    /// True for an open map's anchor (no lap, no progress).
    pub fn is_anchor(&self) -> bool {
        self.anchor.is_some()
    }

    /// Total (closed) length in metres; 0 for an anchor.
    pub fn length(&self) -> f64 {
        self.cum[self.pts.len()]
    }

    pub fn num_segments(&self) -> usize {
        self.pts.len()
    }

    /// Vertex `i` (of `num_segments()` distinct vertices; the polyline closes).
    pub fn point(&self, i: usize) -> [f64; 2] {
        self.pts[i % self.pts.len()]
    }

    /// Pose `(x, y, heading)` at arc length `s` (wrapped into `[0, length)`).
    pub fn pose_at(&self, s: f64) -> [f64; 3] {
        if let Some([x, y, yaw]) = self.anchor {
            let s = if s.is_finite() { s } else { 0.0 };
            return [x + s * yaw.cos(), y + s * yaw.sin(), yaw];
        }
        let len = self.length();
        let s = if s.is_finite() {
            s.rem_euclid(len)
        } else {
            0.0
        };
        pose_on_ring(&self.pts, &self.cum, s)
    }

    /// Project `p` on segment `i`: (squared distance, arc length).
    #[inline]
    fn project_segment(&self, p: [f64; 2], i: usize) -> (f64, f64) {
        let (a, b) = (self.pts[i], self.pts[(i + 1) % self.pts.len()]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let l2 = dx * dx + dy * dy;
        let t = if l2 > 0.0 {
            (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (qx, qy) = (a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
        (
            qx * qx + qy * qy,
            self.cum[i] + t * (self.cum[i + 1] - self.cum[i]),
        )
    }

    /// Nearest point over all segments: (segment index, arc length); (0, 0) on an anchor.
    pub fn project_global(&self, p: [f64; 2]) -> (usize, f64) {
        if self.is_anchor() {
            return (0, 0.0);
        }
        let mut best = (f64::INFINITY, 0usize, 0.0);
        for i in 0..self.pts.len() {
            let (d2, s) = self.project_segment(p, i);
            if d2 < best.0 {
                best = (d2, i, s);
            }
        }
        (best.1, best.2)
    }

    /// Nearest point among segments within `window` metres of arc length around segment
    /// `hint` (the previous projection), so a car never jumps to a neighbouring pass of
    /// the track. Returns (segment index, arc length).
    pub fn project_local(&self, p: [f64; 2], hint: usize, window: f64) -> (usize, f64) {
        if self.is_anchor() {
            return (0, 0.0);
        }
        let n = self.pts.len();
        let hint = hint % n;
        let mut best = {
            let (d2, s) = self.project_segment(p, hint);
            (d2, hint, s)
        };
        for dir in [1isize, -1] {
            let mut walked = 0.0;
            let mut i = hint;
            for _ in 1..n {
                i = (i as isize + dir).rem_euclid(n as isize) as usize;
                let (d2, s) = self.project_segment(p, i);
                if d2 < best.0 {
                    best = (d2, i, s);
                }
                walked += self.cum[i + 1] - self.cum[i];
                if walked > window {
                    break;
                }
            }
        }
        (best.1, best.2)
    }
}

/// Pose `(x, y, heading)` at arc length `s` (already wrapped into `[0, length]`) on the
/// closed ring `pts` with cumulative lengths `cum` (one more than `pts`): on the last
/// segment that starts at or before `s` (numpy's `searchsorted(cum, s, "right") - 1`).
pub(crate) fn pose_on_ring(pts: &[[f64; 2]], cum: &[f64], s: f64) -> [f64; 3] {
    let n = pts.len();
    let i = cum
        .partition_point(|&c| c <= s)
        .saturating_sub(1)
        .min(n - 1);
    let (a, b) = (pts[i], pts[(i + 1) % n]);
    let seg = cum[i + 1] - cum[i];
    let t = if seg > 0.0 { (s - cum[i]) / seg } else { 0.0 };
    [
        a[0] + t * (b[0] - a[0]),
        a[1] + t * (b[1] - a[1]),
        (b[1] - a[1]).atan2(b[0] - a[0]),
    ]
}

/// Drop consecutive duplicates and a closing point equal to the first.
fn dedupe_closed(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(points.len());
    for &p in points {
        if out
            .last()
            .is_none_or(|q| (q[0] - p[0]).hypot(q[1] - p[1]) > 1e-9)
        {
            out.push(p);
        }
    }
    while out.len() > 1 {
        let (f, l) = (out[0], out[out.len() - 1]);
        if (f[0] - l[0]).hypot(f[1] - l[1]) > 1e-9 {
            break;
        }
        out.pop();
    }
    out
}

/// Everything the simulator needs about one track (immutable, shared by `Arc`).
pub struct Track {
    pub walls: Vec<Vec<[f64; 2]>>,
    pub wall_shape: SharedShape,
    pub grid: SegmentGrid,
    pub centreline: Centreline,
}

impl std::fmt::Debug for Track {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Track")
            .field("walls", &self.walls.len())
            .field("segments", &self.grid.num_segments())
            .field("centreline_length", &self.centreline.length())
            .finish()
    }
}

impl Track {
    /// The collision mesh as the physics engine holds it: (vertices, triangles).
    pub fn wall_mesh(&self) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        match self.wall_shape.as_trimesh() {
            Some(m) => (
                m.vertices().iter().map(|v| [v.x, v.y, v.z]).collect(),
                m.indices().to_vec(),
            ),
            None => (Vec::new(), Vec::new()),
        }
    }

    /// Build from closed wall polylines and a closed centreline; walls are extruded from
    /// z = 0 to `wall_height` for the collision mesh.
    pub fn new(walls: &[Vec<[f64; 2]>], centreline: &[[f64; 2]], wall_height: f64) -> Result<Self> {
        let walls: Vec<Vec<[f64; 2]>> = walls
            .iter()
            .map(|w| dedupe_closed(w))
            .filter(|w| w.len() >= 2)
            .collect();
        if walls.is_empty() {
            return Err(ArenaError::invalid(
                "track has no wall polyline with at least 2 distinct points",
            ));
        }
        if walls.iter().flatten().flatten().any(|v| !v.is_finite()) {
            return Err(ArenaError::invalid(
                "track walls have non-finite coordinates",
            ));
        }
        if !(wall_height.is_finite() && wall_height > 0.0 && wall_height <= MAX_WALL_HEIGHT_M) {
            return Err(ArenaError::invalid(format!(
                "wall_height must be in (0, {MAX_WALL_HEIGHT_M}] m, got {}",
                crate::limits::show(wall_height)
            )));
        }
        let centreline = Centreline::new(centreline)?;
        let mesh = extrude_walls(&walls, 0.0, wall_height);
        let vertices = mesh
            .vertices
            .iter()
            .map(|v| Vector::new(v[0], v[1], v[2]))
            .collect();
        let wall_shape = SharedShape::trimesh(vertices, mesh.triangles).map_err(|e| {
            ArenaError::Simulation(format!("wall mesh rejected by the physics engine: {e}"))
        })?;
        let grid = SegmentGrid::new(&walls);
        Ok(Track {
            walls,
            wall_shape,
            grid,
            centreline,
        })
    }

    /// True when `p` lies in the free region of the track's start: enclosed by exactly
    /// the closed walls (rings of 3+ points) that enclose the centreline's first point.
    /// Inside a wall block, in a track's infield, beyond its outer wall or in a pocket
    /// cut off by walls is false. The walls are the map's occupancy boundaries as the
    /// simulator holds them, so this is the map's free space for any track source
    /// (a map, walls from Python, a bare simulator's tracks). O(wall vertices).
    pub fn is_free(&self, p: [f64; 2]) -> bool {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return false;
        }
        let start = self.centreline.point(0);
        self.walls
            .iter()
            .filter(|w| w.len() >= 3)
            .all(|w| ring_contains(w, p) == ring_contains(w, start))
    }
}

/// Even-odd point-in-polygon test of the closed ring `w` (half-open in y, so a ray
/// through a vertex counts once).
fn ring_contains(w: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut inside = false;
    for (i, &a) in w.iter().enumerate() {
        let b = w[(i + 1) % w.len()];
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if p[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle(r: f64, n: usize) -> Vec<[f64; 2]> {
        crate::geometry::test_circle(n, r)
    }

    #[test]
    fn centreline_length_pose_and_projection() {
        let sq = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0], [0.0, 0.0]];
        let c = Centreline::new(&sq).unwrap();
        assert_eq!(c.num_segments(), 4);
        assert!((c.length() - 6.0).abs() < 1e-12);
        let p = c.pose_at(2.5);
        assert!((p[0] - 2.0).abs() < 1e-12 && (p[1] - 0.5).abs() < 1e-12);
        assert!((p[2] - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert_eq!(c.pose_at(-1.0), c.pose_at(5.0));
        let (i, s) = c.project_global([1.0, -0.3]);
        assert_eq!((i, s), (0, 1.0));
        let (_, s) = c.project_local([0.1, 0.8], 3, 1.0);
        assert!((s - 5.2).abs() < 1e-12);
    }

    #[test]
    fn track_builds_a_shared_mesh() {
        let t = Track::new(&[circle(3.0, 64), circle(1.5, 64)], &circle(2.25, 64), 0.5).unwrap();
        assert_eq!(t.grid.num_segments(), 128);
        assert!(Track::new(&[], &circle(2.0, 8), 0.5).is_err());
        assert!(Track::new(&[circle(3.0, 8)], &[[0.0, 0.0], [0.0, 0.0]], 0.5).is_err());
    }

    #[test]
    fn an_anchor_has_no_length_and_poses_along_its_heading() {
        let c = Centreline::new(&[[1.0, 2.0], [1.0, 3.0]]).unwrap();
        assert!(c.is_anchor());
        assert_eq!(c.length(), 0.0);
        let p = c.pose_at(-1.0);
        assert!((p[0] - 1.0).abs() < 1e-12 && (p[1] - 1.0).abs() < 1e-12);
        assert!((p[2] - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert_eq!(c.pose_at(f64::NAN)[1], 2.0);
        assert_eq!(c.project_global([5.0, 5.0]), (0, 0.0));
        let mut pr = super::super::progress::Progress::reset(&c, [1.0, 2.0]);
        assert!(!pr.update(&c, [4.0, 2.0], 0.1, 3.0));
        assert_eq!((pr.travel, pr.laps), (0.0, 0));
        assert!((pr.lap_time - 0.1).abs() < 1e-12);
    }

    #[test]
    fn free_space_is_the_region_of_the_start() {
        // A ring track (outer r 3, inner r 1.5) with a 0.3 m square block on the track,
        // a quarter lap from the start (2.25, 0).
        let block = vec![[-0.15, 2.1], [0.15, 2.1], [0.15, 2.4], [-0.15, 2.4]];
        let t = Track::new(
            &[circle(3.0, 64), circle(1.5, 64), block],
            &circle(2.25, 64),
            0.5,
        )
        .unwrap();
        for p in [
            [-2.25, 0.0],
            [0.0, -2.0],
            [0.0, -2.8],
            [2.0, 0.0],
            [0.0, 2.6],
        ] {
            assert!(t.is_free(p), "{p:?} is on the track");
        }
        // In the infield, beyond the outer wall, inside the block, non-finite.
        for p in [
            [0.0, 0.0],
            [0.5, 0.5],
            [3.5, 0.0],
            [0.0, -40.0],
            [0.0, 2.25],
            [f64::NAN, 2.0],
        ] {
            assert!(!t.is_free(p), "{p:?} is not free");
        }
    }

    #[test]
    fn wall_height_is_checked_by_the_core() {
        let (w, c) = ([circle(3.0, 32), circle(1.5, 32)], circle(2.25, 32));
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, MAX_WALL_HEIGHT_M * 1.01] {
            let e = Track::new(&w, &c, bad).unwrap_err().to_string();
            assert!(e.contains("wall_height must be in (0, 10] m"), "{e}");
        }
        assert!(Track::new(&w, &c, MAX_WALL_HEIGHT_M).is_ok());
    }
}
