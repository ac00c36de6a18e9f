//! Bindings for `arena_core::geometry::polyline`, the one polyline toolbox: numpy in,
//! numbers and arrays out. Every call goes through `boundary::call` (GIL released,
//! panics caught); the core's `check_*` doors refuse bad input as `InvalidArgumentError`.
//! Closed polylines may repeat their first point at the end; it is dropped (lengths keep
//! it: it adds a zero-length edge, and `cumulative_length` returns one value per point).

use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::boundary::call;
use crate::convert::points_from_py;
use arena_core::geometry::polyline as pl;

type Points = Vec<[f64; 2]>;

/// Run `f` in the core on the points of `xy` that pass the door (at least `min`, finite,
/// a repeated closing point dropped when `closed`), through `boundary::call`.
fn on_points<T: Send>(
    py: Python<'_>,
    what: &str,
    xy: &PyReadonlyArray2<'_, f64>,
    min: usize,
    closed: bool,
    f: impl FnOnce(Points) -> arena_core::Result<T> + Send,
) -> PyResult<T> {
    let mut p = points_from_py(xy, "xy")?;
    call(py, what, move || {
        let n = pl::check_points(&p, min, closed, "xy")?;
        p.truncate(n);
        f(p)
    })
}

fn points_to_py<'py>(py: Python<'py>, p: &[[f64; 2]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = p.iter().flat_map(|q| [q[0], q[1]]).collect();
    let arr = numpy::ndarray::Array2::from_shape_vec((p.len(), 2), flat).expect("shape matches");
    PyArray2::from_owned_array(py, arr)
}

/// Length (m) of a polyline (N ≥ 2), counting the closing edge when ``closed``.
#[pyfunction]
#[pyo3(signature = (xy, closed=true))]
fn polyline_length(py: Python<'_>, xy: PyReadonlyArray2<'_, f64>, closed: bool) -> PyResult<f64> {
    // A repeated closing point adds a zero-length edge: nothing to drop.
    on_points(py, "polyline_length", &xy, 2, false, move |p| {
        Ok(pl::polyline_length(&p, closed))
    })
}

/// Arc length (m) at each vertex from point 0: (N,) for an open polyline, (N + 1,) for a
/// closed one (the last value is the lap length). One value per given point: a repeated
/// closing point is kept (its closing edge has length 0).
#[pyfunction]
#[pyo3(signature = (xy, closed=true))]
fn cumulative_length<'py>(
    py: Python<'py>,
    xy: PyReadonlyArray2<'py, f64>,
    closed: bool,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let cum = on_points(py, "cumulative_length", &xy, 2, false, move |p| {
        Ok(pl::cumulative_length(&p, closed))
    })?;
    Ok(PyArray1::from_vec(py, cum))
}

/// Signed area (m²) of a closed polyline (N ≥ 3): positive when counter-clockwise.
#[pyfunction]
fn signed_area(py: Python<'_>, xy: PyReadonlyArray2<'_, f64>) -> PyResult<f64> {
    on_points(py, "signed_area", &xy, 3, true, |p| Ok(pl::signed_area(&p)))
}

/// Points evenly spaced by arc length along a closed polyline (N ≥ 3), about
/// ``spacing`` m apart (at least 3), starting at point 0: (M, 2).
#[pyfunction]
fn resample_closed<'py>(
    py: Python<'py>,
    xy: PyReadonlyArray2<'py, f64>,
    spacing: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let out = on_points(py, "resample_closed", &xy, 3, true, move |p| {
        pl::check_spacing(spacing, pl::polyline_length(&p, true))?;
        Ok(pl::resample_closed(&p, spacing))
    })?;
    Ok(points_to_py(py, &out))
}

/// [`resample_closed`] carrying one finite value per point (e.g. a width) along, each
/// interpolated linearly in arc length: ``(points (M, 2), values (M,))``. One value
/// more than points is the value on returning to point 0 (an unwrapped parameter).
#[pyfunction]
#[allow(clippy::type_complexity)]
fn resample_closed_values<'py>(
    py: Python<'py>,
    xy: PyReadonlyArray2<'py, f64>,
    values: PyReadonlyArray1<'py, f64>,
    spacing: f64,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<f64>>)> {
    let p = points_from_py(&xy, "xy")?;
    let v: Vec<f64> = values.as_array().iter().copied().collect();
    let (pts, vals) = call(py, "resample_closed_values", move || {
        let n = pl::check_points(&p, 3, true, "xy")?;
        pl::check_values(&v, p.len(), n)?;
        let p = &p[..n];
        pl::check_spacing(spacing, pl::polyline_length(p, true))?;
        Ok(pl::resample_closed_values(p, &v, spacing))
    })?;
    Ok((points_to_py(py, &pts), PyArray1::from_vec(py, vals)))
}

/// Signed curvature (1/m, + = left) at each vertex of a closed polyline (N ≥ 3): the
/// circle through the vertex and its neighbours about ``span_m`` of arc either side.
#[pyfunction]
fn curvature<'py>(
    py: Python<'py>,
    xy: PyReadonlyArray2<'py, f64>,
    span_m: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let k = on_points(py, "curvature", &xy, 3, true, move |p| {
        pl::check_span(span_m)?;
        Ok(pl::curvature_closed(&p, span_m))
    })?;
    Ok(PyArray1::from_vec(py, k))
}

/// Smallest three-point circumradius (m) of a closed polyline (N ≥ 3) over chords of
/// about ``span_m``; ``inf`` when it never bends.
#[pyfunction]
fn min_radius(py: Python<'_>, xy: PyReadonlyArray2<'_, f64>, span_m: f64) -> PyResult<f64> {
    on_points(py, "min_radius", &xy, 3, true, move |p| {
        pl::check_span(span_m)?;
        Ok(pl::min_radius_closed(&p, span_m))
    })
}

/// Crossings of a closed polyline (N ≥ 3) with itself: ``(segments (K, 2) int64,
/// points (K, 2))``, row k = segments ``i < j`` (segment i runs from point i to i + 1)
/// crossing at ``points[k]``, sorted by (i, j).
#[pyfunction]
#[allow(clippy::type_complexity)]
fn self_intersections<'py>(
    py: Python<'py>,
    xy: PyReadonlyArray2<'py, f64>,
) -> PyResult<(Bound<'py, PyArray2<i64>>, Bound<'py, PyArray2<f64>>)> {
    let x = on_points(py, "self_intersections", &xy, 3, true, |p| {
        pl::self_intersections_closed(&p)
    })?;
    let flat: Vec<i64> = x.iter().flat_map(|c| [c.i as i64, c.j as i64]).collect();
    let ij = numpy::ndarray::Array2::from_shape_vec((x.len(), 2), flat).expect("shape matches");
    let pts: Points = x.iter().map(|c| c.point).collect();
    Ok((PyArray2::from_owned_array(py, ij), points_to_py(py, &pts)))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(polyline_length, m)?)?;
    m.add_function(wrap_pyfunction!(cumulative_length, m)?)?;
    m.add_function(wrap_pyfunction!(signed_area, m)?)?;
    m.add_function(wrap_pyfunction!(resample_closed, m)?)?;
    m.add_function(wrap_pyfunction!(resample_closed_values, m)?)?;
    m.add_function(wrap_pyfunction!(curvature, m)?)?;
    m.add_function(wrap_pyfunction!(min_radius, m)?)?;
    m.add_function(wrap_pyfunction!(self_intersections, m)?)?;
    Ok(())
}
