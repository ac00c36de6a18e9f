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
/// per edge, double-sided by construction of the collision query, not duplicated).
/// This is the collision-wall mesh shared by the USD stage and every physics world.
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
            mesh.triangles.push([a0, b0, b1]);
            mesh.triangles.push([a0, b1, a1]);
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
        assert_eq!(both.triangles[8], [8, 10, 11]);
    }
}
