//! Lattice boundary → smooth centreline: scale, cut sweeper corners, fillet every vertex.
//!
//! Radii are absolute (not scaled with the pitch), so the curve length is
//! `s · E − Σ savings` exactly and the pitch `s` that gives lap length `L` follows in
//! closed form. Ordinary corners get radius `r_c`; a sweeper corner is cut by a 45°
//! chamfer `a = 1.5 r_c` from the corner on both legs and its two 45° vertices get
//! radius `2 r_c` (two larger-radius 45° turns replacing one 90° corner).

use super::lattice::Corner;
use std::f64::consts::PI;

/// Chamfer leg of a sweeper corner and radius of its two 45° turns, in units of r_c.
pub const SWEEPER_CHAMFER: f64 = 1.5;
pub const SWEEPER_RADIUS: f64 = 2.0;

/// A polygon vertex with its fillet radius.
#[derive(Debug, Clone, Copy)]
struct Vertex {
    p: [f64; 2],
    radius: f64,
}

/// Length removed from the polygon by one ordinary corner and by one sweeper corner.
pub fn savings(rc: f64) -> (f64, f64) {
    let ordinary = 2.0 * rc - rc * PI / 2.0;
    let a = SWEEPER_CHAMFER * rc;
    let r = SWEEPER_RADIUS * rc;
    let t = r * (PI / 8.0).tan();
    let sweeper = (2.0 * a - a * 2f64.sqrt()) + 2.0 * (2.0 * t - r * PI / 4.0);
    (ordinary, sweeper)
}

/// Lattice pitch `s` that makes the rounded loop exactly `lap` long.
pub fn pitch_for_length(
    lap: f64,
    perimeter_edges: u32,
    corners: usize,
    sweepers: usize,
    rc: f64,
) -> f64 {
    let (o, s) = savings(rc);
    (lap + (corners - sweepers) as f64 * o + sweepers as f64 * s) / perimeter_edges as f64
}

/// Build the rounded centreline (counter-clockwise, lattice origin at 0) with points at
/// most `step` apart along arcs. `None` if some fillets would overlap on an edge.
pub fn rounded_centreline(
    corners: &[Corner],
    is_sweeper: &[bool],
    s: f64,
    rc: f64,
    step: f64,
) -> Option<Vec<[f64; 2]>> {
    let pts: Vec<[f64; 2]> = corners
        .iter()
        .map(|c| [c.at.0 as f64 * s, c.at.1 as f64 * s])
        .collect();
    round_polygon(&pts, is_sweeper, rc, step)
}

/// Round a rectilinear polygon (metres): ordinary vertices get radius `rc`, a sweeper
/// vertex is cut by the 45° chamfer and its two vertices get `SWEEPER_RADIUS · rc`.
/// `None` if some fillets would overlap on an edge.
pub fn round_polygon(
    pts: &[[f64; 2]],
    is_sweeper: &[bool],
    rc: f64,
    step: f64,
) -> Option<Vec<[f64; 2]>> {
    let m = pts.len();
    let mut verts: Vec<Vertex> = Vec::with_capacity(m + 4);
    for i in 0..m {
        let p = pts[i];
        if is_sweeper[i] {
            let a = SWEEPER_CHAMFER * rc;
            let din = norm(sub(p, pts[(i + m - 1) % m]));
            let dout = norm(sub(pts[(i + 1) % m], p));
            let r = SWEEPER_RADIUS * rc;
            verts.push(Vertex {
                p: [p[0] - din[0] * a, p[1] - din[1] * a],
                radius: r,
            });
            verts.push(Vertex {
                p: [p[0] + dout[0] * a, p[1] + dout[1] * a],
                radius: r,
            });
        } else {
            verts.push(Vertex { p, radius: rc });
        }
    }
    fillet(&verts, step)
}

/// Round a polygon (metres) with one fillet radius per vertex. `None` if some fillets
/// would overlap on an edge.
pub fn round_polygon_radii(pts: &[[f64; 2]], radii: &[f64], step: f64) -> Option<Vec<[f64; 2]>> {
    let verts: Vec<Vertex> = pts
        .iter()
        .zip(radii)
        .map(|(&p, &radius)| Vertex { p, radius })
        .collect();
    fillet(&verts, step)
}

/// Fillet every vertex with its radius, points at most `step` apart along the arcs.
fn fillet(verts: &[Vertex], step: f64) -> Option<Vec<[f64; 2]>> {
    let n = verts.len();
    // Tangent lengths; every edge must hold both neighbours' tangents.
    let mut tan_len = vec![0.0; n];
    let mut geom = vec![([0.0; 2], [0.0; 2], 0.0f64); n]; // (dir in, dir out, signed turn)
    for i in 0..n {
        let (a, b, c) = (verts[(i + n - 1) % n].p, verts[i].p, verts[(i + 1) % n].p);
        let din = norm([b[0] - a[0], b[1] - a[1]]);
        let dout = norm([c[0] - b[0], c[1] - b[1]]);
        let turn = (din[0] * dout[1] - din[1] * dout[0]).atan2(din[0] * dout[0] + din[1] * dout[1]);
        tan_len[i] = verts[i].radius * (turn.abs() / 2.0).tan();
        geom[i] = (din, dout, turn);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        let (a, b) = (verts[i].p, verts[j].p);
        if tan_len[i] + tan_len[j] > crate::geometry::dist(a, b) + 1e-9 {
            return None;
        }
    }
    let mut out = Vec::new();
    for i in 0..n {
        let (din, dout, turn) = geom[i];
        let (p, r, t) = (verts[i].p, verts[i].radius, tan_len[i]);
        let start = [p[0] - din[0] * t, p[1] - din[1] * t];
        // Arc centre is to the left of the incoming direction for a left turn.
        let sgn = turn.signum();
        let centre = [start[0] - sgn * din[1] * r, start[1] + sgn * din[0] * r];
        let a0 = (start[1] - centre[1]).atan2(start[0] - centre[0]);
        let k = ((turn.abs() * r / step).ceil() as usize).max(2);
        for j in 0..=k {
            let a = a0 + turn * j as f64 / k as f64;
            out.push([centre[0] + r * a.cos(), centre[1] + r * a.sin()]);
        }
        let _ = dout;
    }
    Some(out)
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn norm(v: [f64; 2]) -> [f64; 2] {
    let l = v[0].hypot(v[1]);
    [v[0] / l, v[1] / l]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::polyline_length;

    fn square(n: i32) -> Vec<Corner> {
        [(n, 0), (n, n), (0, n), (0, 0)]
            .iter()
            .map(|&at| Corner {
                at,
                sense: 1,
                run_after: n as u32,
            })
            .collect()
    }

    #[test]
    fn length_is_exact_for_ordinary_and_sweeper_corners() {
        let rc = 1.0;
        for sweepers in [0usize, 1, 2] {
            let is_sw: Vec<bool> = (0..4).map(|i| i < sweepers).collect();
            let s = pitch_for_length(40.0, 12, 4, sweepers, rc);
            let c = rounded_centreline(&square(3), &is_sw, s, rc, 0.01).unwrap();
            let l = polyline_length(&c, true);
            assert!((l - 40.0).abs() < 0.01, "sweepers {sweepers}: {l}");
            assert!(crate::geometry::signed_area(&c) > 0.0);
        }
    }

    #[test]
    fn per_vertex_radii_take_their_own_saving() {
        // A 6 m square with radii 1, 1.5, 1, 0.5: each 90° fillet saves (2 − π/2) r.
        let sq = [[0.0, 0.0], [6.0, 0.0], [6.0, 6.0], [0.0, 6.0]];
        let radii = [1.0, 1.5, 1.0, 0.5];
        let c = round_polygon_radii(&sq, &radii, 0.005).unwrap();
        let want = 24.0 - (2.0 - PI / 2.0) * radii.iter().sum::<f64>();
        assert!((polyline_length(&c, true) - want).abs() < 1e-3);
        assert!(round_polygon_radii(&sq, &[3.5, 3.0, 1.0, 1.0], 0.05).is_none());
    }

    #[test]
    fn overlapping_fillets_are_refused() {
        assert!(rounded_centreline(&square(1), &[false; 4], 1.0, 0.6, 0.05).is_none());
    }
}
