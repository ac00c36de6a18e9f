//! Bindings for `arena_core::generate` (requirements → track): the screen, the derived
//! geometry and the lattice/ring/polygon constructors with their time budget. The
//! rasteriser is in `grid.rs`, the raster validator in `track.rs`. GIL released for the work.

use numpy::PyArray2;
use pyo3::prelude::*;

use crate::boundary;
use crate::convert::{grid_to_py, line_to_py, to_json, MapTuple};
use arena_core::generate::budget::{Budget, Stop};
use arena_core::generate::construct::{self, Outcome};
use arena_core::generate::spec::{ConstructorConfig, Spec};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

pub(crate) fn parse(
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

/// Nearest specs that build after a generation failure (`generate::nearest`), as JSON
/// ``{"suggestions": [{field, spec, seed, candidate_index}], "probes", "exhausted"}``.
/// ``timeout`` (seconds) bounds the search; when it passes inside one probe the search
/// reports what it found so far. Ctrl-C raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (spec_json, config_json, seed, timeout))]
fn nearest_specs(
    py: Python<'_>,
    spec_json: &str,
    config_json: &str,
    seed: u64,
    timeout: f64,
) -> PyResult<String> {
    let (spec, cfg) = parse(py, spec_json, config_json)?;
    let out = run_budgeted(py, Some(timeout), move |b| {
        to_json(&arena_core::generate::nearest::nearest_specs(
            &spec, &cfg, seed, b,
        ))
    })?;
    Ok(out.unwrap_or_else(|| {
        serde_json::json!({"suggestions": [], "probes": 0, "exhausted": true}).to_string()
    }))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(nearest_specs, m)?)?;
    m.add_function(wrap_pyfunction!(screen, m)?)?;
    m.add_function(wrap_pyfunction!(derived_geometry, m)?)?;
    m.add_function(wrap_pyfunction!(generate_lattice, m)?)?;
    m.add_function(wrap_pyfunction!(construct_lattice, m)?)?;
    Ok(())
}
