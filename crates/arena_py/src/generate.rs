//! Bindings for requirement-driven generation: the rasteriser (Eq. 3), the screen, the
//! lattice constructor and the raster validator. Thin wrappers; GIL released for heavy work.

use numpy::{PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::boundary;
use arena_core::generate::budget::{Budget, Stop};
use arena_core::generate::construct::{self, Outcome};
use arena_core::generate::spec::{ConstructorConfig, Spec};
use arena_core::track::{features, validate};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

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

/// How often the waiting binding thread looks for Ctrl-C (Python signal handlers only
/// run on the main thread, so the core runs on a worker while this thread polls).
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Grace (s) past the deadline before the binding stops waiting for a worker that is
/// inside one long candidate (rasterising or validating a very large map).
const DEADLINE_GRACE_S: f64 = 1.0;

/// Run `work` on a worker thread with a [`Budget`] of `timeout` seconds, polling Python
/// signals meanwhile. On KeyboardInterrupt the cancellation flag is set and the signal's
/// exception is raised at once; once the deadline (plus a short grace) has passed,
/// `Ok(None)` is returned at once. Either way the worker is left to stop at its next
/// check, its result discarded, so one long candidate cannot hold the caller.
fn run_budgeted<T: Send + 'static>(
    py: Python<'_>,
    timeout: Option<f64>,
    work: impl FnOnce(&Budget) -> T + Send + 'static,
) -> PyResult<Option<T>> {
    if let Some(t) = timeout {
        if !(t.is_finite() && t > 0.0) {
            return Err(crate::errors::InvalidArgumentError::new_err(format!(
                "timeout: must be a positive finite number of seconds (got {t})"
            )));
        }
    }
    let flag = Arc::new(AtomicBool::new(false));
    let budget = Budget::new(timeout, Some(flag.clone()));
    let hard_stop = Budget::new(timeout.map(|t| t + DEADLINE_GRACE_S), None);
    // The worker's result slot: None while running, Some(Err) if the worker panicked.
    type Slot<T> = Option<std::thread::Result<T>>;
    let slot: Arc<(Mutex<Slot<T>>, Condvar)> = Arc::new((Mutex::new(None), Condvar::new()));
    let worker_slot = slot.clone();
    std::thread::spawn(move || {
        let out = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| work(&budget)));
        let (lock, cv) = &*worker_slot;
        *lock.lock().unwrap_or_else(|e| e.into_inner()) = Some(out);
        cv.notify_all();
    });
    // Wait up to `SIGNAL_POLL` (GIL released) for the worker; `None` = still running.
    let wait = |poll: Option<Duration>| {
        let s = slot.clone();
        py.detach(move || {
            let (lock, cv) = &*s;
            let mut g = lock.lock().unwrap_or_else(|e| e.into_inner());
            while g.is_none() {
                match poll {
                    Some(d) => {
                        g = cv.wait_timeout(g, d).unwrap_or_else(|e| e.into_inner()).0;
                        break;
                    }
                    None => g = cv.wait(g).unwrap_or_else(|e| e.into_inner()),
                }
            }
            g.take()
        })
    };
    loop {
        match wait(Some(SIGNAL_POLL)) {
            Some(Ok(v)) => return Ok(Some(v)),
            Some(Err(_)) => return Err(crate::errors::InternalError::new_err(
                "generate: internal error on this input (a bug; please report it with the spec)",
            )),
            None => {
                if let Err(e) = py.check_signals() {
                    flag.store(true, Ordering::Relaxed);
                    return Err(e);
                }
                if hard_stop.stopped().is_some() {
                    flag.store(true, Ordering::Relaxed);
                    return Ok(None);
                }
            }
        }
    }
}

/// Failure info when the deadline passed inside one candidate (its count is unknown).
fn abandoned_info() -> String {
    serde_json::json!({
        "tried": 0,
        "reasons": {"time budget ran out inside one candidate (rasterising or validating)": 1},
        "stopped": "timeout",
    })
    .to_string()
}

fn stop_name(s: Option<Stop>) -> Option<&'static str> {
    s.map(|s| match s {
        Stop::Timeout => "timeout",
        Stop::Cancelled => "cancelled",
    })
}

/// Algorithm 1 (lattice and ring constructors). Returns ``(kind, info_json, data,
/// origin, centreline)`` with kind ``"accepted" | "rejected" | "failed"``; the last three
/// are None unless accepted. ``timeout`` (seconds, None = unbounded) bounds the loop; a
/// failure it cut short has ``"stopped": "timeout"`` in its info. Ctrl-C stops the loop
/// between candidates and raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (spec_json, config_json, seed, timeout=None))]
#[allow(clippy::type_complexity)]
fn generate_lattice<'py>(
    py: Python<'py>,
    spec_json: &str,
    config_json: &str,
    seed: u64,
    timeout: Option<f64>,
) -> PyResult<(
    &'static str,
    String,
    Option<MapTuple<'py>>,
    Option<Bound<'py, PyArray2<f64>>>,
)> {
    let (spec, cfg) = parse(py, spec_json, config_json)?;
    let Some(out) = run_budgeted(py, timeout, move |b| {
        construct::generate(&spec, &cfg, seed, b)
    })?
    else {
        return Ok(("failed", abandoned_info(), None, None));
    };
    Ok(match out.map_err(crate::errors::to_py)? {
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
        Outcome::Failed {
            tried,
            reasons,
            stopped,
        } => (
            "failed",
            serde_json::json!({"tried": tried, "reasons": reasons, "stopped": stop_name(stopped)})
                .to_string(),
            None,
            None,
        ),
    })
}

/// The constructor without the raster validator in its loop (the paper's
/// constructor-comparison protocol). Returns ``(info_json, centreline | None)``; info has
/// ``tried`` and, when no candidate passed the constructor's checks, ``reasons``.
#[pyfunction]
#[pyo3(signature = (spec_json, config_json, seed, timeout=None))]
fn construct_lattice<'py>(
    py: Python<'py>,
    spec_json: &str,
    config_json: &str,
    seed: u64,
    timeout: Option<f64>,
) -> PyResult<(String, Option<Bound<'py, PyArray2<f64>>>)> {
    let (spec, cfg) = parse(py, spec_json, config_json)?;
    let Some(out) = run_budgeted(py, timeout, move |b| {
        construct::first_candidate(&spec, &cfg, seed, b)
    })?
    else {
        return Ok((abandoned_info(), None));
    };
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
    boundary::call(py, "validate_map", || {
        validate::check_frame(resolution, [origin.0, origin.1, origin.2])
    })?;
    let grid = crate::grid::grid_from_py(py, &data, resolution, origin)?;
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
