//! The core's own reading of every configuration schema the Python layer also models
//! (pydantic): its defaults, and its verdict on a document. The parity tests
//! (`tests/test_config_parity.py`) hold the two sides to the same defaults and limits.
//! Documents cross as Python mappings (or the pydantic models), never as JSON text.

use arena_core::generate::spec::{ConstructorConfig, Spec};
use arena_core::sim::SimParams;
use arena_core::track::params::BuildParams;
use arena_core::ArenaError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::boundary;
use crate::convert::{from_py, to_dict};
use crate::domain::{ConfigKind, Wrap};

fn config_error(message: String) -> ArenaError {
    ArenaError::config(message)
}

/// The core's defaults for one schema, as a dict (``"spec"`` has no defaults of its own:
/// the schema's defaults live in ``TrackSpec``).
#[pyfunction]
fn config_defaults<'py>(py: Python<'py>, kind: Wrap<ConfigKind>) -> PyResult<Bound<'py, PyDict>> {
    match kind.0 {
        ConfigKind::Sim => to_dict(py, &SimParams::default()),
        ConfigKind::Build => to_dict(py, &BuildParams::default()),
        ConfigKind::Constructor => to_dict(py, &ConstructorConfig::default()),
        ConfigKind::Spec => Err(crate::errors::to_py(ArenaError::invalid(format!(
            "config kind {:?} has no core defaults: expected 'sim', 'build' or 'constructor' (TrackSpec holds the spec's)",
            ConfigKind::Spec.name()
        )))),
    }
}

/// Read and validate ``config`` (a mapping or the pydantic model) as the core does;
/// returns it normalised (defaults filled in). ``ConfigError`` (``SpecError`` for a spec)
/// naming the field when the core refuses it.
#[pyfunction]
fn check_config<'py>(
    py: Python<'py>,
    kind: Wrap<ConfigKind>,
    config: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let c = Some(config);
    match kind.0 {
        ConfigKind::Sim => {
            let p: SimParams = from_py(py, c, "simulator config", config_error)?;
            let p = boundary::call(py, "check_config", move || p.validate().map(|_| p))?;
            to_dict(py, &p)
        }
        ConfigKind::Build => {
            let p: BuildParams = from_py(py, c, "build params", config_error)?;
            let p = boundary::call(py, "check_config", move || p.validate().map(|_| p))?;
            to_dict(py, &p)
        }
        ConfigKind::Constructor => {
            let p: ConstructorConfig = from_py(py, c, "constructor config", config_error)?;
            to_dict(py, &boundary::call(py, "check_config", move || p.check())?)
        }
        ConfigKind::Spec => {
            let s: Spec = from_py(py, c, "spec", ArenaError::Spec)?;
            to_dict(py, &boundary::call(py, "check_config", move || s.check())?)
        }
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(config_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(check_config, m)?)?;
    Ok(())
}
