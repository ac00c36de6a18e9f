//! Bindings for the track library (circuits and catalog): raster measurements of any
//! trinary occupancy grid via `arena_core::track::metrics::measure_raster`. Thin wrapper,
//! GIL released for the heavy work.

use numpy::{PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::boundary;
use arena_core::track::metrics;

/// Measure a trinary grid (254 free / 0 occupied / 205 unknown) as the validator does.
/// Returns ``(info_json, centreline (N, 2), widths (N,))``: the corridor/infield counts,
/// the mean free width and the known extent in ``info_json``; the closed medial
/// centreline (counter-clockwise, map metres) and the local free width at each vertex.
/// Raises ``CorridorError`` when the grid has no closed corridor.
#[pyfunction]
#[allow(clippy::type_complexity)]
fn measure_map<'py>(
    py: Python<'py>,
    data: PyReadonlyArray2<'py, u8>,
    resolution: f64,
    origin: (f64, f64, f64),
) -> PyResult<(String, Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<f64>>)> {
    let grid = crate::maps::grid_from_py(py, &data, resolution, origin)?;
    let t = boundary::call(py, "measure_map", move || metrics::measure_raster(&grid))?;
    let length = arena_core::geometry::polyline_length(&t.centreline, true);
    let info = serde_json::json!({
        "corridor_components": t.corridor_components,
        "infields": t.infields,
        "mean_width_m": t.mean_width_m,
        "extent_m": t.extent_m,
        "centreline_length_m": length,
    });
    let flat: Vec<f64> = t.centreline.iter().flat_map(|p| [p[0], p[1]]).collect();
    let line = numpy::ndarray::Array2::from_shape_vec((t.centreline.len(), 2), flat)
        .expect("shape matches");
    Ok((
        info.to_string(),
        PyArray2::from_owned_array(py, line),
        PyArray1::from_vec(py, t.widths),
    ))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(measure_map, m)?)?;
    Ok(())
}
