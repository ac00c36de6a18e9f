//! Visual barrier meshes: air-duct tubes swept along closed centre lines, with evenly
//! spaced rings (short, slightly larger bands), and a flat floor quad.

use super::mesh::TriMesh;
use super::{dist, Polyline};

/// Sweep an n-gon cross-section of `radius` along a closed planar path, the tube axis
/// at height `z`. Outward-facing triangles; `segments` vertices per cross-section.
/// At corners the section is widened by 1/cos(half turn) so the tube keeps its radius.
pub fn closed_tube_mesh(path: &[[f64; 2]], radius: f64, z: f64, segments: usize) -> TriMesh {
    let n = path.len();
    let s = segments.max(3);
    let mut m = TriMesh::default();
    if n < 3 {
        return m;
    }
    m.vertices.reserve(n * s);
    for i in 0..n {
        let (a, b, c) = (path[(i + n - 1) % n], path[i], path[(i + 1) % n]);
        let t_in = unit([b[0] - a[0], b[1] - a[1]]);
        let t_out = unit([c[0] - b[0], c[1] - b[1]]);
        let t = unit([t_in[0] + t_out[0], t_in[1] + t_out[1]]);
        let t = if t == [0.0, 0.0] { t_out } else { t };
        let mitre = (t[0] * t_out[0] + t[1] * t_out[1]).max(0.5);
        let lat = [-t[1] / mitre, t[0] / mitre];
        push_section(&mut m, b, lat, radius, z, s);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        stitch(&mut m, (i * s) as u32, (j * s) as u32, s as u32);
    }
    m
}

/// Texture coordinates of [`closed_tube_mesh`]'s triangles, face-varying: `(st, indices)`
/// with one index per triangle corner, in the tube's triangle order. `u` is the arc
/// length along the path in metres, `v` runs 0..1 around the tube. The grid of values has
/// a seam row (the loop's closure at `u` = its length) and a seam column (`v` = 1), so
/// a texture repeats continuously along and around the tube.
pub fn closed_tube_st(path: &[[f64; 2]], segments: usize) -> (Vec<[f32; 2]>, Vec<u32>) {
    let n = path.len();
    let s = segments.max(3);
    if n < 3 {
        return (Vec::new(), Vec::new());
    }
    let cols = s + 1; // seam column
    let mut st = Vec::with_capacity((n + 1) * cols);
    for u in super::polyline::cumulative_length(path, true) {
        st.extend((0..cols).map(|k| [u as f32, k as f32 / s as f32])); // n + 1 rows: seam
    }
    let mut idx = Vec::with_capacity(6 * n * s);
    for i in 0..n {
        for k in 0..s {
            let at = |r: usize, c: usize| (r * cols + c) as u32;
            let (p, q, r, t) = (at(i, k), at(i, k + 1), at(i + 1, k), at(i + 1, k + 1));
            idx.extend([p, t, r, p, q, t]); // the corner order of `stitch`
        }
    }
    (st, idx)
}

/// Rings every `spacing` metres of arc length along a closed path: open bands of
/// length `width` and radius `radius`, each two cross-sections joined by quads.
pub fn rings_along(
    path: &[[f64; 2]],
    spacing: f64,
    width: f64,
    radius: f64,
    z: f64,
    segments: usize,
) -> TriMesh {
    let mut m = TriMesh::default();
    let n = path.len();
    if n < 2 || spacing <= 0.0 || width <= 0.0 {
        return m;
    }
    let s = segments.max(3);
    let total: f64 = (0..n).map(|i| dist(path[i], path[(i + 1) % n])).sum();
    let count = (total / spacing).floor() as usize;
    if count == 0 {
        return m;
    }
    let step = total / count as f64;
    let (mut seg, mut acc) = (0usize, 0.0);
    for k in 0..count {
        let target = k as f64 * step;
        while seg < n && acc + dist(path[seg], path[(seg + 1) % n]) < target {
            acc += dist(path[seg], path[(seg + 1) % n]);
            seg += 1;
        }
        let (a, b) = (path[seg % n], path[(seg + 1) % n]);
        let len = dist(a, b).max(1e-12);
        let t = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
        let f = (target - acc) / len;
        let p = [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])];
        let lat = [-t[1], t[0]];
        let base = m.vertices.len() as u32;
        for sign in [-0.5, 0.5] {
            let c = [p[0] + sign * width * t[0], p[1] + sign * width * t[1]];
            push_section(&mut m, c, lat, radius, z, s);
        }
        stitch(&mut m, base, base + s as u32, s as u32);
    }
    m
}

/// A flat rectangle at z = 0 covering `[x0, x1] × [y0, y1]`, facing +z.
pub fn floor_quad(x0: f64, y0: f64, x1: f64, y1: f64) -> TriMesh {
    let v = |x: f64, y: f64| [x as f32, y as f32, 0.0];
    TriMesh {
        vertices: vec![v(x0, y0), v(x1, y0), v(x1, y1), v(x0, y1)],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    }
}

/// Bounding box (min x, min y, max x, max y) of a set of polylines.
pub fn bounds(lines: &[Polyline]) -> Option<[f64; 4]> {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for p in lines.iter().flatten() {
        b = [
            b[0].min(p[0]),
            b[1].min(p[1]),
            b[2].max(p[0]),
            b[3].max(p[1]),
        ];
    }
    b[0].is_finite().then_some(b)
}

fn unit(v: [f64; 2]) -> [f64; 2] {
    let l = v[0].hypot(v[1]);
    if l > 0.0 {
        [v[0] / l, v[1] / l]
    } else {
        [0.0, 0.0]
    }
}

/// Cross-section around `c`: angle θ from the lateral direction towards +z.
fn push_section(m: &mut TriMesh, c: [f64; 2], lat: [f64; 2], r: f64, z: f64, s: usize) {
    for k in 0..s {
        let th = std::f64::consts::TAU * k as f64 / s as f64;
        let (sn, cs) = th.sin_cos();
        m.vertices.push([
            (c[0] + r * cs * lat[0]) as f32,
            (c[1] + r * cs * lat[1]) as f32,
            (z + r * sn) as f32,
        ]);
    }
}

/// Quads between two consecutive sections starting at vertex `a` and `b`, outward.
fn stitch(m: &mut TriMesh, a: u32, b: u32, s: u32) {
    for k in 0..s {
        let k2 = (k + 1) % s;
        let (p, q, r, t) = (a + k, a + k2, b + k, b + k2);
        m.triangles.push([p, t, r]);
        m.triangles.push([p, q, t]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn circle(n: usize, r: f64) -> Vec<[f64; 2]> {
        crate::geometry::test_circle(n, r)
    }

    /// Each triangle corner's texture coordinate belongs to that corner's vertex: quad
    /// (i, k) has corners at rows i, i+1 and columns k, k+1 (`stitch`'s order), `u` is
    /// the row's arc length (row n = the seam, the loop's full length), `v` = column / s.
    #[test]
    fn tube_st_follows_the_triangle_corners() {
        let (n, s) = (12, 6);
        let path = circle(n, 2.0);
        let m = closed_tube_mesh(&path, 0.1, 0.1, s);
        let (st, idx) = closed_tube_st(&path, s);
        assert_eq!(idx.len(), 3 * m.triangles.len());
        let seg = dist(path[0], path[1]);
        let corners = [[(0, 0), (1, 1), (1, 0)], [(0, 0), (0, 1), (1, 1)]];
        for (t, (tri, uv)) in m.triangles.iter().zip(idx.chunks(3)).enumerate() {
            let (i, k) = ((t / 2) / s, (t / 2) % s);
            for (c, &(dr, dc)) in corners[t % 2].iter().enumerate() {
                assert_eq!(tri[c] as usize, ((i + dr) % n) * s + (k + dc) % s);
                let [u, v] = st[uv[c] as usize];
                assert!(
                    (u as f64 - (i + dr) as f64 * seg).abs() < 1e-4,
                    "u {u} at row {}",
                    i + dr
                );
                assert!(
                    (v - (k + dc) as f32 / s as f32).abs() < 1e-6,
                    "v {v} at column {}",
                    k + dc
                );
            }
        }
    }

    /// Signed volume of a closed mesh (positive when triangles face outward).
    fn volume(m: &TriMesh) -> f64 {
        m.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.vertices[i as usize].map(|x| x as f64));
                (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]))
                    / 6.0
            })
            .sum()
    }

    #[test]
    fn torus_tube_is_closed_outward_and_has_the_right_volume() {
        let (big_r, r) = (5.0, 0.165);
        let m = closed_tube_mesh(&circle(200, big_r), r, r, 16);
        assert_eq!(m.vertices.len(), 200 * 16);
        assert_eq!(m.triangles.len(), 2 * 200 * 16);
        let exact = 2.0 * PI * big_r * PI * r * r;
        let v = volume(&m);
        assert!(
            v > 0.0 && (v - exact).abs() / exact < 0.03,
            "{v} vs {exact}"
        );
        assert!(m
            .vertices
            .iter()
            .all(|p| p[2] >= -1e-6 && p[2] <= (2.0 * r) as f32 + 1e-6));
    }

    #[test]
    fn rings_are_evenly_spaced() {
        let m = rings_along(&circle(100, 10.0), 1.0, 0.05, 0.2, 0.2, 8);
        let count = (2.0 * PI * 10.0).floor() as usize;
        assert_eq!(m.vertices.len(), count * 16);
        assert_eq!(m.triangles.len(), count * 16);
        let f = floor_quad(0.0, 0.0, 2.0, 1.0);
        assert_eq!((f.vertices.len(), f.triangles.len()), (4, 2));
    }
}
