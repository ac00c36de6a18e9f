//! Corridor isolation on synthetic filled and thin-line maps.

use super::*;
use crate::grid::{OCCUPIED, UNKNOWN};

/// n × n grid at 0.1 m, origin (0, 0): cells with radius in [r0, r1] get `ring`,
/// radius in the walls [r0 − t, r0) and (r1, r1 + t] get OCCUPIED, the rest `rest`.
fn ring_map(n: usize, r0: f64, r1: f64, t: f64, ring: u8, rest: u8) -> OccupancyGrid {
    let mut g = OccupancyGrid::filled(n, n, 0.1, [0.0, 0.0, 0.0], rest);
    let c = n as f64 / 2.0;
    for row in 0..n {
        for col in 0..n {
            let r = ((col as f64 + 0.5 - c).powi(2) + (row as f64 + 0.5 - c).powi(2)).sqrt();
            let i = g.index(col, row);
            if r >= r0 && r <= r1 {
                g.data[i] = ring;
            } else if r >= r0 - t && r <= r1 + t {
                g.data[i] = OCCUPIED;
            }
        }
    }
    g
}

fn corridor_err(r: Result<Corridor>) -> String {
    match r {
        Err(ArenaError::Corridor(m)) => m,
        other => panic!(
            "expected a corridor error, got {:?}",
            other.map(|c| c.cells)
        ),
    }
}

#[test]
fn filled_map_ring_is_found() {
    let g = ring_map(60, 12.0, 20.0, 2.0, FREE, UNKNOWN);
    let c = isolate_corridor(&g, None).unwrap();
    let expect = g.data.iter().filter(|&&v| v == FREE).count();
    assert_eq!(c.cells, expect);
    assert_eq!(c.holes, 1);
    assert!(c.infield[g.index(30, 30)] && !c.mask[g.index(30, 30)]);
    assert!(!c.infield[0] && !c.mask[0]);
}

#[test]
fn thin_line_map_drops_exterior_and_infield() {
    // white everywhere, walls as 1.5-cell lines: exterior and infield are free too
    let g = ring_map(70, 14.0, 22.0, 1.5, FREE, FREE);
    let c = isolate_corridor(&g, None).unwrap();
    assert!(c.mask[g.index(35 + 18, 35)], "a ring cell");
    assert!(
        !c.mask[g.index(35, 35)] && c.infield[g.index(35, 35)],
        "infield centre"
    );
    assert!(!c.mask[0] && !c.infield[0], "exterior corner");
    let ring_cells = (0..g.data.len())
        .filter(|&i| {
            let (col, row) = (i % 70, i / 70);
            let r = ((col as f64 + 0.5 - 35.0).powi(2) + (row as f64 + 0.5 - 35.0).powi(2)).sqrt();
            (14.0..=22.0).contains(&r)
        })
        .count();
    assert_eq!(c.cells, ring_cells);
}

#[test]
fn start_pose_seeds_the_ring_and_bad_starts_are_explained() {
    let g = ring_map(70, 14.0, 22.0, 1.5, FREE, FREE);
    let on_ring = g.cell_center(35 + 18, 35);
    assert_eq!(
        isolate_corridor(&g, Some(on_ring)).unwrap().cells,
        isolate_corridor(&g, None).unwrap().cells
    );
    let m = corridor_err(isolate_corridor(&g, Some(g.cell_center(1, 1))));
    assert!(m.contains("leak") && m.contains("border"), "{m}");
    let m = corridor_err(isolate_corridor(&g, Some(g.cell_center(35, 35))));
    assert!(m.contains("encloses no infield"), "{m}");
    let m = corridor_err(isolate_corridor(&g, Some([-5.0, 1.0])));
    assert!(m.contains("outside the map"), "{m}");
    let wall = g.cell_center(35 + 22, 35);
    let m = corridor_err(isolate_corridor(&g, Some(wall)));
    assert!(m.contains("not on a free cell"), "{m}");
}

#[test]
fn leaking_walls_are_reported_with_a_location() {
    let mut g = ring_map(70, 14.0, 22.0, 1.5, FREE, FREE);
    // cut the outer wall on the right: rows 33..37, cols beyond radius 22
    for row in 33..37 {
        for col in 56..62 {
            let i = g.index(col, row);
            g.data[i] = FREE;
        }
    }
    let m = corridor_err(isolate_corridor(&g, None));
    assert!(m.contains("leak") && m.contains(" m)"), "{m}");
}

#[test]
fn blank_and_empty_maps_are_refused() {
    let blank = OccupancyGrid::filled(30, 20, 0.1, [0.0; 3], FREE);
    let m = corridor_err(isolate_corridor(&blank, None));
    assert!(
        m.contains("no closed corridor") && m.contains("blank"),
        "{m}"
    );
    let walls = OccupancyGrid::filled(30, 20, 0.1, [0.0; 3], OCCUPIED);
    assert!(corridor_err(isolate_corridor(&walls, None)).contains("no free cells"));
    let none = OccupancyGrid::filled(0, 0, 0.1, [0.0; 3], FREE);
    assert!(corridor_err(isolate_corridor(&none, None)).contains("empty map"));
    let one = OccupancyGrid::filled(1, 1, 0.1, [0.0; 3], FREE);
    assert!(corridor_err(isolate_corridor(&one, None)).contains("no closed corridor"));
}

#[test]
fn outermost_ring_wins_over_a_ring_in_the_infield() {
    // an outer ring and a smaller ring inside its infield
    let mut g = ring_map(90, 36.0, 40.0, 1.5, FREE, UNKNOWN);
    let inner = ring_map(90, 6.0, 28.0, 1.5, FREE, UNKNOWN); // bigger, but nested
    for i in 0..g.data.len() {
        if inner.data[i] != UNKNOWN {
            g.data[i] = inner.data[i];
        }
    }
    let c = isolate_corridor(&g, None).unwrap();
    assert!(c.mask[g.index(45 + 38, 45)] && !c.mask[g.index(45 + 14, 45)]);
    assert!(c.infield[g.index(45 + 14, 45)]);
}

#[test]
fn a_ring_grazing_the_map_edge_is_closed_by_it_but_a_wide_opening_leaks() {
    // a filled ring with a free channel from the ring up to the top border
    let mut g = ring_map(100, 20.0, 30.0, 2.0, FREE, UNKNOWN);
    let carve = |g: &mut OccupancyGrid, cols: std::ops::Range<usize>| {
        for row in 0..25 {
            for col in cols.clone() {
                let i = g.index(col, row);
                g.data[i] = FREE;
            }
        }
    };
    carve(&mut g, 50..52);
    let c = isolate_corridor(&g, None).unwrap();
    assert_eq!(c.border_contact, 2);
    assert!(c.mask[g.index(50, 0)]);
    carve(&mut g, 40..60); // 20 border cells > 2 % of 396
    let m = corridor_err(isolate_corridor(&g, None));
    assert!(m.contains("leak"), "{m}");
    let m = corridor_err(isolate_corridor(&g, Some(g.cell_center(50, 50 + 25))));
    assert!(
        m.contains("leak") && m.contains("reaches the map border at"),
        "{m}"
    );
}
