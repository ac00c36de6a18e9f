//! Conversions between numpy arrays and the core's plain types, shared by the binding
//! files (no logic: shapes in, shapes out).

use numpy::{PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

pub(crate) type MapTuple<'py> = (Bound<'py, PyArray2<u8>>, (f64, f64, f64));

pub(crate) fn grid_to_py<'py>(
    py: Python<'py>,
    g: arena_core::grid::OccupancyGrid,
) -> MapTuple<'py> {
    let o = g.origin;
    let arr =
        numpy::ndarray::Array2::from_shape_vec((g.height, g.width), g.data).expect("shape matches");
    (PyArray2::from_owned_array(py, arr), (o[0], o[1], o[2]))
}

pub(crate) fn points_from_py(
    xy: &PyReadonlyArray2<'_, f64>,
    what: &str,
) -> PyResult<Vec<[f64; 2]>> {
    if xy.shape()[1] != 2 {
        return Err(crate::errors::InvalidArgumentError::new_err(format!(
            "{what} must have shape (N, 2), got {:?}",
            xy.shape()
        )));
    }
    Ok(xy
        .as_array()
        .rows()
        .into_iter()
        .map(|r| [r[0], r[1]])
        .collect())
}

pub(crate) fn line_to_py<'py>(py: Python<'py>, line: &[[f64; 2]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = line.iter().flat_map(|p| [p[0], p[1]]).collect();
    let arr = numpy::ndarray::Array2::from_shape_vec((line.len(), 2), flat).expect("shape matches");
    PyArray2::from_owned_array(py, arr)
}

pub(crate) fn to_json<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_string(v).expect("plain data serialises")
}
