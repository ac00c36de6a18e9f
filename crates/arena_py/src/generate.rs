//! Bindings for requirement-driven generation: the rasteriser (Eq. 3), the screen, the
//! lattice constructor and the raster validator. Thin wrappers; GIL released for heavy work.

use numpy::{PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::boundary;
use arena_core::generate::construct::{self, Outcome};
use arena_core::generate::spec::{ConstructorConfig, Spec};
use arena_core::track::{features, validate};

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
    let g = boundary::call(py, "rasterise_centreline", move || {
        arena_core::grid::rasterise::rasterise_centreline(
            &pts,
            &w,
            resolution,
            wall_thickness,
            margin,
        )
    })?;
    Ok(grid_to_py(py, g))
}

fn parse(
    py: Python<'_>,
    spec_json: &str,
    config_json: &str,
) -> PyResult<(Spec, ConstructorConfig)> {
    boundary::call(py, "spec/config", || {
        Ok((
            Spec::from_json(spec_json)?,
            ConstructorConfig::from_json(config_json)?,
        ))
    })
}

fn to_json<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_string(v).expect("plain data serialises")
}

pub(crate) fn line_to_py<'py>(py: Python<'py>, line: &[[f64; 2]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = line.iter().flat_map(|p| [p[0], p[1]]).collect();
    let arr = numpy::ndarray::Array2::from_shape_vec((line.len(), 2), flat).expect("shape matches");
    PyArray2::from_owned_array(py, arr)
}

/// The admissibility screen (Eqs. 1–2) as JSON: passed, violations and every quantity.
#[pyfunction]
fn screen(py: Python<'_>, spec_json: &str, config_json: &str) -> PyResult<String> {
    let (spec, cfg) = parse(py, spec_json, config_json)?;
    boundary::call_ok(py, "screen", move || {
        to_json(&arena_core::generate::screen::screen(&spec, &cfg))
    })
}

/// Derived geometry (r_min, pitch, L_max, s_min, corner radius) as JSON.
#[pyfunction]
fn derived_geometry(py: Python<'_>, spec_json: &str, config_json: &str) -> PyResult<String> {
    let (spec, cfg) = parse(py, spec_json, config_json)?;
    boundary::call_ok(py, "derived_geometry", move || {
        to_json(&arena_core::generate::spec::derive(&spec, &cfg))
    })
}

/// Algorithm 1 with the lattice constructor. Returns ``(kind, info_json, data, origin,
/// centreline)`` with kind ``"accepted" | "rejected" | "failed"``; the last three are
/// None unless accepted.
#[pyfunction]
#[allow(clippy::type_complexity)]
fn generate_lattice<'py>(
    py: Python<'py>,
    spec_json: &str,
    config_json: &str,
    seed: u64,
) -> PyResult<(
    &'static str,
    String,
    Option<MapTuple<'py>>,
    Option<Bound<'py, PyArray2<f64>>>,
)> {
    let (spec, cfg) = parse(py, spec_json, config_json)?;
    let out = boundary::call_ok(py, "generate_lattice", move || {
        construct::generate(&spec, &cfg, seed)
    })?;
    Ok(match out {
        Outcome::Accepted {
            grid,
            candidate,
            report,
            candidate_index,
            tried,
        } => {
            let info = serde_json::json!({
                "report": report, "candidate_index": candidate_index, "tried": tried, "pitch_m": candidate.pitch_m,
            });
            let line = line_to_py(py, &candidate.centreline);
            (
                "accepted",
                info.to_string(),
                Some(grid_to_py(py, grid)),
                Some(line),
            )
        }
        Outcome::Rejected(sr) => ("rejected", to_json(&sr), None, None),
        Outcome::Failed { tried, reasons } => (
            "failed",
            serde_json::json!({"tried": tried, "reasons": reasons}).to_string(),
            None,
            None,
        ),
    })
}

/// The lattice constructor without the raster validator in its loop (the paper's
/// constructor-comparison protocol). Returns ``(info_json, centreline | None)``; info has
/// ``tried`` and, when no candidate passed the constructor's checks, ``reasons``.
#[pyfunction]
fn construct_lattice<'py>(
    py: Python<'py>,
    spec_json: &str,
    config_json: &str,
    seed: u64,
) -> PyResult<(String, Option<Bound<'py, PyArray2<f64>>>)> {
    let (spec, cfg) = parse(py, spec_json, config_json)?;
    let out = boundary::call_ok(py, "construct_lattice", move || {
        construct::first_candidate(&spec, &cfg, seed)
    })?;
    Ok(match out {
        Ok((c, tried)) => (
            serde_json::json!({"tried": tried, "pitch_m": c.pitch_m}).to_string(),
            Some(line_to_py(py, &c.centreline)),
        ),
        Err((tried, reasons)) => (
            serde_json::json!({"tried": tried, "reasons": reasons}).to_string(),
            None,
        ),
    })
}

/// Validate an occupancy grid against a spec, measuring the raster only. Returns
/// ``(report_json, measured centreline (N, 2) in the driving direction)``.
#[pyfunction]
fn validate_map<'py>(
    py: Python<'py>,
    data: PyReadonlyArray2<'py, u8>,
    resolution: f64,
    origin: (f64, f64, f64),
    spec_json: &str,
    config_json: &str,
) -> PyResult<(String, Bound<'py, PyArray2<f64>>)> {
    let (spec, cfg) = parse(py, spec_json, config_json)?;
    let grid = crate::maps::grid_from_py(py, &data, resolution, origin)?;
    let report = boundary::call_ok(py, "validate_map", move || {
        validate::validate_map(&grid, &spec, &cfg)
    })?;
    Ok((to_json(&report), line_to_py(py, &report.centreline)))
}

/// Curvature analysis of a closed curve (driving direction): turns, features, minimum
/// radius, longest straight, total turn; plus its self-clearance outside `exclude_m`.
#[pyfunction]
#[pyo3(signature = (xy, corner_radius, exclude_m))]
fn analyse_curve(
    py: Python<'_>,
    xy: PyReadonlyArray2<'_, f64>,
    corner_radius: f64,
    exclude_m: f64,
) -> PyResult<String> {
    let pts = points_from_py(&xy, "xy")?;
    boundary::call(py, "analyse_curve", move || {
        features::check_curve_args(&pts, corner_radius, exclude_m)?;
        let a = features::analyse_closed_curve(&pts, corner_radius);
        let c = features::self_clearance(&pts, exclude_m, 0.1);
        let mut v = serde_json::to_value(&a).expect("plain data");
        v["self_clearance_m"] = serde_json::json!(if c.is_finite() { c } else { -1.0 });
        Ok(v.to_string())
    })
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(rasterise_centreline, m)?)?;
    m.add_function(wrap_pyfunction!(screen, m)?)?;
    m.add_function(wrap_pyfunction!(derived_geometry, m)?)?;
    m.add_function(wrap_pyfunction!(generate_lattice, m)?)?;
    m.add_function(wrap_pyfunction!(construct_lattice, m)?)?;
    m.add_function(wrap_pyfunction!(validate_map, m)?)?;
    m.add_function(wrap_pyfunction!(analyse_curve, m)?)?;
    Ok(())
}
