//! The medial centreline of a corridor: the zero level set of `d_in − d_out`, where
//! `d_in` / `d_out` are the distances to the inner (infield) and outer side. It is the
//! curve midway between the two walls, found with sub-cell accuracy by marching squares.
//! Shared by the validator's raster measurements and the builder.

use crate::geometry::contour::marching_squares;
use crate::geometry::polyline_length;

/// The longest closed zero-crossing loop of `f` (marching squares on cell centres), as
/// (u, v) grid coordinates (cell units from the lower-left corner, v up).
pub fn longest_zero_loop(f: &[f32], w: usize, h: usize) -> Option<Vec<[f64; 2]>> {
    marching_squares(f, w, h, 0.0)
        .into_iter()
        .map(|l| (polyline_length(&l, true), l))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, l)| l)
}

/// The medial loop between the inner and outer walls given their distance fields (cells).
pub fn medial_loop(d_in: &[f32], d_out: &[f32], w: usize, h: usize) -> Option<Vec<[f64; 2]>> {
    let f: Vec<f32> = d_in.iter().zip(d_out).map(|(a, b)| a - b).collect();
    longest_zero_loop(&f, w, h)
}
