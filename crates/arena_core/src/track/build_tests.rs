//! The whole pipeline on synthetic rings (filled and thin-line).

use super::*;
use crate::geometry::polyline_length;
use crate::grid::rasterise::rasterise_constant;
use crate::grid::{FREE, OCCUPIED, UNKNOWN};
use std::f64::consts::PI;

const CX: f64 = 1.0;
const CY: f64 = -2.0;

fn ring(r: f64, w: f64, res: f64) -> OccupancyGrid {
    let c: Vec<[f64; 2]> = (0..2000)
        .map(|i| {
            let a = 2.0 * PI * i as f64 / 2000.0;
            [r * a.cos() + CX, r * a.sin() + CY]
        })
        .collect();
    rasterise_constant(&c, w, res, 0.15, 0.6).unwrap()
}

fn radius(p: [f64; 2]) -> f64 {
    (p[0] - CX).hypot(p[1] - CY)
}

#[test]
fn filled_ring_builds_with_high_iou_and_correct_geometry() {
    let (r, w, res) = (4.0, 1.5, 0.05);
    let g = ring(r, w, res);
    let geo = build_geometry(&g, &BuildParams::default(), None).unwrap();
    assert!(geo.iou >= 0.97, "iou {}", geo.iou);
    assert!(
        geo.max_wall_deviation_cells <= 0.6,
        "deviation {}",
        geo.max_wall_deviation_cells
    );
    assert_eq!(geo.walls.len(), 2);
    let mut areas: Vec<f64> = geo.walls.iter().map(|l| signed_area(l)).collect();
    areas.sort_by(f64::total_cmp);
    assert!(
        areas[0] < 0.0 && areas[1] > 0.0,
        "outer CCW, inner CW: {areas:?}"
    );
    // Eq. 3 frees d ≤ w/2 − Δ/2 at cell centres: the boundary lies ~w/2 from the centreline.
    for l in &geo.walls {
        let mean = l.iter().map(|&p| radius(p)).sum::<f64>() / l.len() as f64;
        let want = if signed_area(l) > 0.0 {
            r + w / 2.0
        } else {
            r - w / 2.0
        };
        assert!((mean - want).abs() < 0.05, "wall radius {mean} vs {want}");
    }
    assert_eq!(geo.ducts.len(), 2);
    for l in &geo.ducts {
        let mean = l.iter().map(|&p| radius(p)).sum::<f64>() / l.len() as f64;
        let want = if signed_area(l) > 0.0 {
            r + w / 2.0 + 0.165
        } else {
            r - w / 2.0 - 0.165
        };
        assert!((mean - want).abs() < 0.05, "duct radius {mean} vs {want}");
    }
    let cl = &geo.centreline;
    assert!(signed_area(cl) > 0.0);
    let len = polyline_length(cl, true);
    assert!(
        (len - 2.0 * PI * r).abs() / (2.0 * PI * r) < 0.01,
        "centreline length {len}"
    );
    assert!(cl.iter().all(|&p| (radius(p) - r).abs() < 0.05));
    assert!((len / cl.len() as f64 - 0.1).abs() < 0.002);
    assert_ne!(cl[0], cl[cl.len() - 1]);
    for m in [&geo.floor, &geo.wall_mesh, &geo.duct_mesh, &geo.ring_mesh] {
        assert!(!m.triangles.is_empty());
        assert!(m
            .triangles
            .iter()
            .flatten()
            .all(|&i| (i as usize) < m.vertices.len()));
    }
    assert!(geo
        .wall_mesh
        .vertices
        .iter()
        .all(|v| v[2] == 0.0 || v[2] == 0.5));
    assert_eq!(geo.timings.last().unwrap().0, "total");
    assert_eq!(geo.params.simplify_tolerance_m, 0.025);
}

#[test]
fn wall_offset_moves_walls_into_the_wall_cells() {
    let g = ring(4.0, 1.5, 0.05);
    let p = BuildParams {
        wall_offset_m: 0.1,
        ..BuildParams::default()
    };
    let geo = build_geometry(&g, &p, None).unwrap();
    let outer = geo.walls.iter().find(|l| signed_area(l) > 0.0).unwrap();
    let mean = outer.iter().map(|&q| radius(q)).sum::<f64>() / outer.len() as f64;
    assert!((mean - (4.0 + 0.75 + 0.1)).abs() < 0.05, "{mean}");
    assert!(
        geo.iou < 0.97 && geo.iou > 0.8,
        "walls moved out: IoU drops to {}",
        geo.iou
    );
}

#[test]
fn thin_line_ring_and_start_seed() {
    // thin-line style: everything free except the two wall lines
    let mut g = ring(3.0, 1.2, 0.04);
    for v in g.data.iter_mut() {
        if *v == UNKNOWN {
            *v = FREE;
        }
    }
    let geo = build_geometry(&g, &BuildParams::default(), None).unwrap();
    assert!(geo.iou >= 0.97, "iou {}", geo.iou);
    assert_eq!(geo.walls.len(), 2);
    let seeded = build_geometry(&g, &BuildParams::default(), Some([CX + 3.0, CY])).unwrap();
    assert_eq!(seeded.corridor.cells, geo.corridor.cells);
    let err = build_geometry(&g, &BuildParams::default(), Some([CX, CY])).unwrap_err();
    assert!(matches!(err, ArenaError::Corridor(_)), "{err}");
}

#[test]
fn open_map_is_refused() {
    let g = OccupancyGrid::filled(40, 30, 0.05, [0.0; 3], OCCUPIED);
    assert!(matches!(
        build_geometry(&g, &BuildParams::default(), None),
        Err(ArenaError::Corridor(_))
    ));
}

#[test]
fn corridor_wider_than_the_first_distance_cap_is_exact() {
    // 14 m wide at 5 cm: inscribed radius 140 cells > the first cap of 128
    let (r, w) = (9.0, 14.0);
    let g = ring(r, w, 0.05);
    let geo = build_geometry(&g, &BuildParams::default(), None).unwrap();
    assert!(geo.iou >= 0.97, "iou {}", geo.iou);
    assert!(geo.centreline.iter().all(|&p| (radius(p) - r).abs() < 0.05));
    let outer = geo.walls.iter().find(|l| signed_area(l) > 0.0).unwrap();
    let mean = outer.iter().map(|&q| radius(q)).sum::<f64>() / outer.len() as f64;
    assert!((mean - (r + w / 2.0)).abs() < 0.05, "{mean}");
}

#[test]
fn origin_yaw_rotates_every_output() {
    let mut g = ring(4.0, 1.5, 0.05);
    let [u, v] = g.world_to_grid(CX, CY); // ring centre in grid units
    g.origin = [2.0, -1.0, 0.7];
    let centre = g.grid_to_world(u, v);
    let geo = build_geometry(&g, &BuildParams::default(), None).unwrap();
    let rad = |p: [f64; 2]| (p[0] - centre[0]).hypot(p[1] - centre[1]);
    assert!(geo.centreline.iter().all(|&p| (rad(p) - 4.0).abs() < 0.05));
    assert!(signed_area(&geo.centreline) > 0.0);
    for l in &geo.walls {
        let want = if signed_area(l) > 0.0 { 4.75 } else { 3.25 };
        assert!(l.iter().all(|&p| (rad(p) - want).abs() < 0.06));
    }
    assert!(geo.iou >= 0.97);
}

/// Even–odd point-in-region test over all wall loops: inside = drivable.
fn drivable(walls: &[Polyline], p: [f64; 2]) -> bool {
    let mut inside = false;
    for l in walls {
        for i in 0..l.len() {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            if (a[1] > p[1]) != (b[1] > p[1])
                && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
            {
                inside = !inside;
            }
        }
    }
    inside
}

/// Unnormalised normal of a triangle (right-hand rule) and its centroid.
fn normal_and_centroid(m: &TriMesh, t: &[u32; 3]) -> ([f64; 3], [f64; 3]) {
    let p = |i: u32| m.vertices[i as usize].map(|v| v as f64);
    let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
    let (u, v) = (
        [0, 1, 2].map(|k| b[k] - a[k]),
        [0, 1, 2].map(|k| c[k] - a[k]),
    );
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    (n, [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0))
}

/// Every wall triangle faces the drivable side and the floor faces up: PhysX meshes are
/// single-sided, so a wall facing away lets rays and bodies through (issue #23).
fn assert_faces_the_corridor(geo: &Geometry) {
    const STEP: f64 = 1e-3;
    for t in &geo.wall_mesh.triangles {
        let (n, c) = normal_and_centroid(&geo.wall_mesh, t);
        let len = n[0].hypot(n[1]);
        assert!(
            len > 0.0 && n[2].abs() < 1e-6 * len,
            "wall {t:?} not vertical: {n:?}"
        );
        let (dx, dy) = (STEP * n[0] / len, STEP * n[1] / len);
        assert!(
            drivable(&geo.walls, [c[0] + dx, c[1] + dy]),
            "wall triangle {t:?} at {c:?} faces away from the corridor"
        );
        assert!(!drivable(&geo.walls, [c[0] - dx, c[1] - dy]));
    }
    for t in &geo.floor.triangles {
        let (n, _) = normal_and_centroid(&geo.floor, t);
        assert!(
            n[2] > 0.0 && n[0] == 0.0 && n[1] == 0.0,
            "floor {t:?} faces {n:?}"
        );
    }
}

#[test]
fn wall_faces_point_into_the_corridor_and_the_floor_up() {
    assert_faces_the_corridor(
        &build_geometry(&ring(4.0, 1.5, 0.05), &BuildParams::default(), None).unwrap(),
    );
    // A non-convex ring (three lobes): concave and convex stretches on both walls.
    let c: Vec<[f64; 2]> = (0..2000)
        .map(|i| {
            let a = 2.0 * PI * i as f64 / 2000.0;
            let r = 4.0 + 1.2 * (3.0 * a).sin();
            [r * a.cos() + CX, r * a.sin() + CY]
        })
        .collect();
    let g = rasterise_constant(&c, 1.2, 0.04, 0.15, 0.6).unwrap();
    let geo = build_geometry(&g, &BuildParams::default(), None).unwrap();
    assert_eq!(geo.walls.len(), 2);
    assert_faces_the_corridor(&geo);
}
