//! Indexed triangle meshes (f32, as USD and rapier store them) and wall extrusion.

/// An indexed triangle mesh in map-frame metres, Z up.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    pub vertices: Vec<[f32; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// Append another mesh, re-indexing its triangles.
    pub fn append(&mut self, other: &TriMesh) {
        let base = self.vertices.len() as u32;
        self.vertices.extend_from_slice(&other.vertices);
        self.triangles.extend(
            other
                .triangles
                .iter()
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
    }
}

/// Extrude closed wall polylines into vertical quads from `z0` to `z1` (two triangles
/// per edge). Every triangle is wound so that its normal points to the polyline's left,
/// the free side of a wall loop: PhysX treats triangle meshes as single-sided (raycasts
/// and contacts see the front face only), so the front must face the drivable corridor.
/// Rapier's queries are double-sided and do not care. This is the collision-wall mesh
/// shared by the USD stage and every physics world.
pub fn extrude_walls(walls: &[Vec<[f64; 2]>], z0: f64, z1: f64) -> TriMesh {
    let mut mesh = TriMesh::default();
    for wall in walls.iter().filter(|w| w.len() >= 2) {
        let base = mesh.vertices.len() as u32;
        let n = wall.len() as u32;
        for p in wall {
            mesh.vertices.push([p[0] as f32, p[1] as f32, z0 as f32]);
            mesh.vertices.push([p[0] as f32, p[1] as f32, z1 as f32]);
        }
        for i in 0..n {
            let j = (i + 1) % n;
            let (a0, a1, b0, b1) = (
                base + 2 * i,
                base + 2 * i + 1,
                base + 2 * j,
                base + 2 * j + 1,
            );
            // (b1 − a0) × (b0 − a0) = h·(z × d): the left normal of edge d = b − a.
            mesh.triangles.push([a0, b1, b0]);
            mesh.triangles.push([a0, a1, b1]);
        }
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_wall_has_eight_triangles() {
        let sq = vec![vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]];
        let m = extrude_walls(&sq, 0.0, 0.5);
        assert_eq!(m.vertices.len(), 8);
        assert_eq!(m.triangles.len(), 8);
        assert!(m
            .triangles
            .iter()
            .flatten()
            .all(|&i| (i as usize) < m.vertices.len()));
        let mut both = m.clone();
        both.append(&m);
        assert_eq!(both.triangles[8], [8, 11, 10]);
    }

    fn normal(m: &TriMesh, t: &[u32; 3]) -> [f64; 3] {
        let p = |i: u32| m.vertices[i as usize].map(|v| v as f64);
        let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
        let (u, v) = (
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
        );
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    }

    #[test]
    fn wall_normals_point_to_the_left_of_each_edge() {
        // A counter-clockwise square: its left (free) side is the inside.
        let sq = vec![vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]];
        let m = extrude_walls(&sq, 0.0, 0.5);
        for t in &m.triangles {
            let n = normal(&m, t);
            let c: [f64; 2] = [0, 1].map(|k| {
                t.iter()
                    .map(|&i| m.vertices[i as usize][k] as f64)
                    .sum::<f64>()
                    / 3.0
            });
            // Towards the square's centre (0.5, 0.5), horizontal.
            let inward = n[0] * (0.5 - c[0]) + n[1] * (0.5 - c[1]);
            assert!(
                inward > 0.0 && n[2].abs() < 1e-9,
                "triangle {t:?} normal {n:?}"
            );
        }
    }
}
