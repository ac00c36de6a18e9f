//! Planar polylines and the triangle meshes built from them. One set of meshes serves
//! both the USD stage and the rapier worlds, so they live here, not in either consumer.

pub mod contour;
pub mod fill;
pub mod mesh;
pub mod polyline;
pub mod smooth;
pub mod tube;

pub use polyline::{dist, polyline_length, signed_area};

/// A polyline of map-frame points (m). A *closed* polyline does not repeat its first
/// point at the end; closure is implied by the caller's context.
pub type Polyline = Vec<[f64; 2]>;

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
