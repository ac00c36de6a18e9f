//! The core's own reading of every configuration schema the Python layer also models
//! (pydantic): its defaults, and its verdict on a JSON document. The parity tests
//! (`tests/test_config_parity.py`) hold the two sides to the same defaults and limits.

use arena_core::generate::spec::ConstructorConfig;
use arena_core::sim::SimParams;
use arena_core::track::params::BuildParams;
use arena_core::ArenaError;
use pyo3::prelude::*;

use crate::boundary;

const KINDS: &str = "'sim', 'build' or 'constructor'";

fn normalised(kind: &str, json: &str) -> arena_core::Result<String> {
    let text = match kind {
        "sim" => serde_json::to_string(&SimParams::from_json(json)?),
        "build" => Ok(BuildParams::from_json(json)?.to_json()),
        "constructor" => serde_json::to_string(&ConstructorConfig::from_json(json)?),
        _ => {
            return Err(ArenaError::invalid(format!(
                "config kind {kind:?}: expected {KINDS}"
            )))
        }
    };
    Ok(text.expect("plain data serialises"))
}

/// The core's defaults for one schema, as JSON.
#[pyfunction]
fn config_defaults(py: Python<'_>, kind: &str) -> PyResult<String> {
    boundary::call(py, "config_defaults", || {
        let text = match kind {
            "sim" => serde_json::to_string(&SimParams::default()),
            "build" => Ok(BuildParams::default().to_json()),
            "constructor" => serde_json::to_string(&ConstructorConfig::default()),
            _ => {
                return Err(ArenaError::invalid(format!(
                    "config kind {kind:?}: expected {KINDS}"
                )))
            }
        };
        Ok(text.expect("plain data serialises"))
    })
}

/// Parse and validate `json` as the core does; returns it normalised (defaults filled in).
#[pyfunction]
fn check_config(py: Python<'_>, kind: &str, json: &str) -> PyResult<String> {
    boundary::call(py, "check_config", || normalised(kind, json))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(config_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(check_config, m)?)?;
    Ok(())
}
