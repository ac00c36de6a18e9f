//! Bindings for `arena_core::generate` (requirements → track): the screen, the derived
//! geometry and the lattice/ring/polygon constructors with their time budget. The
//! rasteriser is in `grid.rs`, the raster validator in `track.rs`. The constructors run
//! through `boundary::call_budgeted` (worker thread, Ctrl-C, deadline), the rest through
//! `boundary::call`.

use numpy::PyArray2;
use pyo3::prelude::*;

use crate::boundary;
use crate::convert::{grid_to_py, line_to_py, to_json, MapTuple};
use arena_core::generate::budget::Failure;
use arena_core::generate::construct::{self, Outcome};
use arena_core::generate::nearest::{self, NearestReport};
use arena_core::generate::spec::{ConstructorConfig, Spec};

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
    let Some(out) = boundary::call_budgeted(py, "generate_lattice", timeout, move |b| {
        construct::generate(&spec, &cfg, seed, b)
    })?
    else {
        return Ok(("failed", to_json(&Failure::abandoned()), None, None));
    };
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
        Outcome::Failed {
            tried,
            reasons,
            stopped,
        } => (
            "failed",
            to_json(&Failure {
                tried,
                reasons,
                stopped,
            }),
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
    let Some(out) = boundary::call_budgeted(py, "construct_lattice", timeout, move |b| {
        Ok(construct::first_candidate(&spec, &cfg, seed, b))
    })?
    else {
        return Ok((to_json(&Failure::abandoned()), None));
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
    let out = boundary::call_budgeted(py, "nearest_specs", Some(timeout), move |b| {
        Ok(nearest::nearest_specs(&spec, &cfg, seed, b))
    })?;
    Ok(to_json(&out.unwrap_or_else(NearestReport::abandoned)))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(nearest_specs, m)?)?;
    m.add_function(wrap_pyfunction!(screen, m)?)?;
    m.add_function(wrap_pyfunction!(derived_geometry, m)?)?;
    m.add_function(wrap_pyfunction!(generate_lattice, m)?)?;
    m.add_function(wrap_pyfunction!(construct_lattice, m)?)?;
    Ok(())
}
