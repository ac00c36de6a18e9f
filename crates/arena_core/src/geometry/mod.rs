//! Planar polylines and the triangle meshes built from them. One set of meshes serves
//! both the USD stage and the rapier worlds, so they live here, not in either consumer.

pub mod contour;
pub mod fill;
pub mod mesh;
pub mod smooth;
pub mod tube;

/// A polyline of map-frame points (m). A *closed* polyline does not repeat its first
/// point at the end; closure is implied by the caller's context.
pub type Polyline = Vec<[f64; 2]>;

/// Length of a polyline, counting the closing edge when `closed`.
pub fn polyline_length(p: &[[f64; 2]], closed: bool) -> f64 {
    let n = p.len();
    if n < 2 {
        return 0.0;
    }
    let edges = if closed { n } else { n - 1 };
    (0..edges).map(|i| dist(p[i], p[(i + 1) % n])).sum()
}

/// Signed area (m²) of a closed polyline: positive when counter-clockwise.
pub fn signed_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    0.5 * (0..n)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
}

#[inline]
pub fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// A regular `n`-gon of radius `r` about the origin, counter-clockwise (shared by tests).
#[cfg(test)]
pub(crate) fn test_circle(n: usize, r: f64) -> Vec<[f64; 2]> {
    (0..n)
        .map(|i| {
            let a = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_length_and_orientation() {
        let sq = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(polyline_length(&sq, true), 4.0);
        assert_eq!(polyline_length(&sq, false), 3.0);
        assert_eq!(signed_area(&sq), 1.0);
        let cw: Vec<_> = sq.iter().rev().copied().collect();
        assert_eq!(signed_area(&cw), -1.0);
    }
}
