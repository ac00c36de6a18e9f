//! Bindings for `arena_core::generate` (requirements → track): the screen, the derived
//! geometry and the lattice/ring/polygon constructors with their deadline. The
//! rasteriser is in `grid.rs`, the raster validator in `track.rs`. The constructors run
//! through `boundary::call_with_deadline` (worker thread, Ctrl-C, deadline), the rest
//! through `boundary::call`.

use pyo3::prelude::*;

use crate::boundary;
use crate::convert::from_py;
use crate::mirror::FromCore;
use crate::nearest::NearestFound;
use crate::outcome::{Construction, LatticeOutcome};
use crate::reports::{Derived, ScreenResult};
use arena_core::generate::construct;
use arena_core::generate::deadline::Failure;
use arena_core::generate::nearest::{self, NearestReport};
use arena_core::generate::spec::{ConstructorConfig, Spec};
use arena_core::ArenaError;

/// The spec (``TrackSpec``, or its ``model_dump()``) and the constructor config
/// (``ConstructorConfig`` or its dump; None = defaults) as the core's types, each checked
/// with the schema's ranges (``SpecError`` / ``ConfigError`` naming the field).
pub(crate) fn parse(
    py: Python<'_>,
    spec: &Bound<'_, PyAny>,
    config: Option<&Bound<'_, PyAny>>,
) -> PyResult<(Spec, ConstructorConfig)> {
    let spec: Spec = from_py(py, Some(spec), "spec", ArenaError::Spec)?;
    let cfg: ConstructorConfig = from_py(py, config, "constructor config", ArenaError::config)?;
    boundary::call(py, "spec/config", move || Ok((spec.check()?, cfg.check()?)))
}

/// The admissibility screen (Eqs. 1–2): passed, violations and every quantity, a
/// [`ScreenResult`].
#[pyfunction]
#[pyo3(signature = (spec, config=None))]
fn screen(
    py: Python<'_>,
    spec: &Bound<'_, PyAny>,
    config: Option<&Bound<'_, PyAny>>,
) -> PyResult<ScreenResult> {
    let (spec, cfg) = parse(py, spec, config)?;
    let out = boundary::call_ok(py, "screen", move || {
        arena_core::generate::screen::screen(&spec, &cfg)
    })?;
    ScreenResult::from_core(py, out)
}

/// Derived geometry (r_min, pitch, L_max, s_min, corner radius), a [`Derived`].
#[pyfunction]
#[pyo3(signature = (spec, config=None))]
fn derived_geometry(
    py: Python<'_>,
    spec: &Bound<'_, PyAny>,
    config: Option<&Bound<'_, PyAny>>,
) -> PyResult<Derived> {
    let (spec, cfg) = parse(py, spec, config)?;
    let d = boundary::call_ok(py, "derived_geometry", move || {
        arena_core::generate::spec::derive(&spec, &cfg)
    })?;
    Derived::from_core(py, d)
}

/// Algorithm 1 (lattice and ring constructors), screen included (once, in the core):
/// a [`LatticeOutcome`] ("accepted", "rejected" or "failed"). ``timeout`` (seconds, None
/// = unbounded) bounds the loop; a failure it cut short has ``stopped == "timeout"``.
/// Ctrl-C stops the loop between candidates and raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (spec, config, seed, timeout=None))]
fn generate_lattice(
    py: Python<'_>,
    spec: &Bound<'_, PyAny>,
    config: Option<&Bound<'_, PyAny>>,
    seed: u64,
    timeout: Option<f64>,
) -> PyResult<LatticeOutcome> {
    let (spec, cfg) = parse(py, spec, config)?;
    match boundary::call_with_deadline(py, "generate_lattice", timeout, move |b| {
        construct::generate(&spec, &cfg, seed, b)
    })? {
        Some(out) => LatticeOutcome::from_core(py, out),
        None => Ok(LatticeOutcome::failed(Failure::abandoned())),
    }
}

/// The constructor without the raster validator in its loop (the paper's
/// constructor-comparison protocol): a [`Construction`] with the first candidate that
/// passed the constructor's checks, or why none did.
#[pyfunction]
#[pyo3(signature = (spec, config, seed, timeout=None))]
fn construct_lattice(
    py: Python<'_>,
    spec: &Bound<'_, PyAny>,
    config: Option<&Bound<'_, PyAny>>,
    seed: u64,
    timeout: Option<f64>,
) -> PyResult<Construction> {
    let (spec, cfg) = parse(py, spec, config)?;
    let out = boundary::call_with_deadline(py, "construct_lattice", timeout, move |b| {
        Ok(construct::first_candidate(&spec, &cfg, seed, b))
    })?;
    Ok(Construction::from_core(py, out))
}

/// Nearest specs that build after a generation failure (`generate::nearest`), a
/// [`NearestFound`].
/// ``timeout`` (seconds) bounds the search; when it passes inside one probe the search
/// reports what it found so far. Ctrl-C raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (spec, config, seed, timeout))]
fn nearest_specs<'py>(
    py: Python<'py>,
    spec: &Bound<'py, PyAny>,
    config: Option<&Bound<'py, PyAny>>,
    seed: u64,
    timeout: f64,
) -> PyResult<NearestFound> {
    let (spec, cfg) = parse(py, spec, config)?;
    let out = boundary::call_with_deadline(py, "nearest_specs", Some(timeout), move |b| {
        Ok(nearest::nearest_specs(&spec, &cfg, seed, b))
    })?;
    NearestFound::from_core(py, out.unwrap_or_else(NearestReport::abandoned))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(nearest_specs, m)?)?;
    m.add_function(wrap_pyfunction!(screen, m)?)?;
    m.add_function(wrap_pyfunction!(derived_geometry, m)?)?;
    m.add_function(wrap_pyfunction!(generate_lattice, m)?)?;
    m.add_class::<LatticeOutcome>()?;
    m.add_class::<Construction>()?;
    m.add_class::<NearestFound>()?;
    m.add_class::<crate::nearest::NearestSuggestion>()?;
    m.add_function(wrap_pyfunction!(construct_lattice, m)?)?;
    Ok(())
}
