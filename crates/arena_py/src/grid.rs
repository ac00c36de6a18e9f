//! Bindings for `arena_core::grid`: thin wrappers, GIL released for heavy work.

use numpy::{PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

/// Exact Euclidean distance (in cells) from every cell to the nearest True cell.
#[pyfunction]
fn distance_transform<'py>(
    py: Python<'py>,
    feature: PyReadonlyArray2<'py, bool>,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let (h, w) = (feature.shape()[0], feature.shape()[1]);
    crate::boundary::call(py, "distance_transform", || {
        arena_core::limits::check_cells(w, h, "distance_transform feature array")
    })?;
    let mask: Vec<bool> = feature.as_array().iter().copied().collect();
    let d = crate::boundary::call_ok(py, "distance_transform", move || {
        arena_core::grid::edt::edt(&mask, w, h)
    })?;
    let arr = numpy::ndarray::Array2::from_shape_vec((h, w), d).expect("shape matches");
    Ok(PyArray2::from_owned_array(py, arr))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(distance_transform, m)?)?;
    Ok(())
}
