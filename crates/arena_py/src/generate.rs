//! Bindings for requirement-driven generation: the rasteriser (Eq. 3), the screen, the
//! lattice constructor and the raster validator. Thin wrappers; GIL released for heavy work.

use numpy::{PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::errors::IntoPyResult;

type MapTuple<'py> = (Bound<'py, PyArray2<u8>>, (f64, f64, f64));

fn grid_to_py<'py>(py: Python<'py>, g: arena_core::grid::OccupancyGrid) -> MapTuple<'py> {
    let o = g.origin;
    let arr = numpy::ndarray::Array2::from_shape_vec((g.height, g.width), g.data).expect("shape matches");
    (PyArray2::from_owned_array(py, arr), (o[0], o[1], o[2]))
}

pub(crate) fn points_from_py(xy: &PyReadonlyArray2<'_, f64>, what: &str) -> PyResult<Vec<[f64; 2]>> {
    if xy.shape()[1] != 2 {
        return Err(crate::errors::InvalidArgumentError::new_err(format!(
            "{what} must have shape (N, 2), got {:?}",
            xy.shape()
        )));
    }
    Ok(xy.as_array().rows().into_iter().map(|r| [r[0], r[1]]).collect())
}

/// Rasterise a closed centreline with per-vertex full corridor widths (Eq. 3).
/// Returns ``(data uint8 (H, W), origin (x, y, yaw))``, row 0 = top image row.
#[pyfunction]
#[pyo3(signature = (xy, widths, resolution=0.05, wall_thickness=0.15, margin=0.5))]
fn rasterise_centreline<'py>(
    py: Python<'py>,
    xy: PyReadonlyArray2<'py, f64>,
    widths: PyReadonlyArray1<'py, f64>,
    resolution: f64,
    wall_thickness: f64,
    margin: f64,
) -> PyResult<MapTuple<'py>> {
    let pts = points_from_py(&xy, "xy")?;
    let w: Vec<f64> = widths.as_array().iter().copied().collect();
    let g = py
        .detach(move || arena_core::grid::rasterise::rasterise_centreline(&pts, &w, resolution, wall_thickness, margin))
        .py()?;
    Ok(grid_to_py(py, g))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(rasterise_centreline, m)?)?;
    Ok(())
}
