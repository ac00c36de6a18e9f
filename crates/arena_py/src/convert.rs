//! Conversions between Python objects and the core's plain types, shared by the binding
//! files (no logic: shapes in, shapes out). Arrays go through numpy; the core's serde
//! types (specs, configs) cross as Python objects through `pythonize`, never as JSON
//! text. Reports cross as typed mirrors (`mirror.rs`, `reports.rs`).

use arena_core::ArenaError;
use numpy::{PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat, PyList, PyTuple};
use serde::de::DeserializeOwned;
use serde::Serialize;

use crate::errors::InternalError;

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

/// A core result as plain Python objects: structs become dicts, sequences lists,
/// `None` options None, unit enums their serde name.
pub(crate) fn to_py<'py, T: Serialize + ?Sized>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    pythonize::pythonize(py, value)
        .map_err(|e| InternalError::new_err(format!("result conversion: {e}")))
}

/// [`to_py`] for a result known to be a struct (a dict on the Python side).
pub(crate) fn to_dict<'py, T: Serialize + ?Sized>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyDict>> {
    Ok(to_py(py, value)?.cast_into::<PyDict>()?)
}

/// A Python object as the core's serde type `T`: a mapping (``model.model_dump()``) or a
/// pydantic model (dumped here), None meaning an empty mapping (every default). A shape
/// the type refuses (unknown field, wrong type, a bool for a number, a float for a count,
/// a non-finite number) is the core error `kind` with the message prefixed by `what`; the
/// caller runs the core's own range check afterwards.
///
/// The object is read into a `serde_json::Value` tree first (in memory, no text), so the
/// typing is exactly as strict as reading a JSON document: pythonize's typed extraction
/// would read `True` as 1.0 and any truthy value as a bool.
pub(crate) fn from_py<T: DeserializeOwned>(
    py: Python<'_>,
    obj: Option<&Bound<'_, PyAny>>,
    what: &str,
    kind: fn(String) -> ArenaError,
) -> PyResult<T> {
    let obj: Bound<'_, PyAny> = match obj {
        None => PyDict::new(py).into_any(),
        Some(o) if o.is_none() => PyDict::new(py).into_any(),
        Some(o) if o.hasattr("model_dump")? => o.call_method0("model_dump")?,
        Some(o) => o.clone(),
    };
    let fail = |e: String| crate::errors::to_py(kind(format!("{what}: {e}")));
    if let Some(at) = non_finite(&obj, String::new())? {
        return Err(fail(format!("{at}: must be a finite number")));
    }
    let tree: serde_json::Value = pythonize::depythonize(&obj).map_err(|e| fail(e.to_string()))?;
    serde_json::from_value(tree).map_err(|e| fail(e.to_string()))
}

/// Where (a dotted path, "(value)" at the top) `obj` holds a NaN or infinite float, if
/// anywhere: a JSON tree has no such numbers, and the core refuses them.
fn non_finite(obj: &Bound<'_, PyAny>, at: String) -> PyResult<Option<String>> {
    let here = |k: &str| {
        if at.is_empty() {
            k.to_string()
        } else {
            format!("{at}.{k}")
        }
    };
    if let Ok(f) = obj.cast::<PyFloat>() {
        let v = f.value();
        return Ok((!v.is_finite()).then(|| {
            if at.is_empty() {
                "(value)".into()
            } else {
                at.clone()
            }
        }));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        for (k, v) in d.iter() {
            if let Some(p) = non_finite(&v, here(&k.str()?.to_cow()?))? {
                return Ok(Some(p));
            }
        }
    } else if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        for (i, v) in obj.try_iter()?.enumerate() {
            if let Some(p) = non_finite(&v?, here(&i.to_string()))? {
                return Ok(Some(p));
            }
        }
    }
    Ok(None)
}
