//! Maps `arena_core::ArenaError` variants onto Python exception classes. The classes
//! live in `roboracer_arena._core` (their `__module__`, so they pickle across process
//! pools) and are re-exported by `roboracer_arena.errors`.

use arena_core::ArenaError as CoreError;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

pyo3::create_exception!(
    roboracer_arena._core,
    ArenaError,
    PyException,
    "Base class of every RoboRacer Arena error."
);
pyo3::create_exception!(
    roboracer_arena._core,
    MapIOError,
    ArenaError,
    "A map or output file could not be read or written."
);
pyo3::create_exception!(
    roboracer_arena._core,
    MapFormatError,
    ArenaError,
    "A map YAML or image is malformed."
);
pyo3::create_exception!(
    roboracer_arena._core,
    CorridorError,
    ArenaError,
    "The map has no usable closed corridor."
);
pyo3::create_exception!(
    roboracer_arena._core,
    InvalidArgumentError,
    ArenaError,
    "An argument is outside its domain."
);
pyo3::create_exception!(
    roboracer_arena._core,
    ConfigError,
    ArenaError,
    "A configuration file or value (BuildConfig, SimConfig, ...) is invalid."
);
pyo3::create_exception!(
    roboracer_arena._core,
    SpecError,
    ArenaError,
    "A track specification is malformed."
);
pyo3::create_exception!(
    roboracer_arena._core,
    SimulationError,
    ArenaError,
    "The simulator refused a track, config or call."
);

pyo3::create_exception!(
    roboracer_arena._core,
    InternalError,
    ArenaError,
    "The core failed on an input it should have refused (a caught panic); please report it."
);

/// Converts a core error into the matching Python exception.
pub fn to_py(err: CoreError) -> PyErr {
    let msg = err.to_string();
    match err {
        CoreError::Io { .. } => MapIOError::new_err(msg),
        CoreError::MapFormat { .. } => MapFormatError::new_err(msg),
        CoreError::Corridor(_) => CorridorError::new_err(msg),
        CoreError::InvalidArgument(_) => InvalidArgumentError::new_err(msg),
        CoreError::Config(_) => ConfigError::new_err(msg),
        CoreError::Spec(_) => SpecError::new_err(msg),
        CoreError::Simulation(_) => SimulationError::new_err(msg),
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ArenaError", py.get_type::<ArenaError>())?;
    m.add("MapIOError", py.get_type::<MapIOError>())?;
    m.add("MapFormatError", py.get_type::<MapFormatError>())?;
    m.add("CorridorError", py.get_type::<CorridorError>())?;
    m.add(
        "InvalidArgumentError",
        py.get_type::<InvalidArgumentError>(),
    )?;
    m.add("ConfigError", py.get_type::<ConfigError>())?;
    m.add("SpecError", py.get_type::<SpecError>())?;
    m.add("SimulationError", py.get_type::<SimulationError>())?;
    m.add("InternalError", py.get_type::<InternalError>())?;
    Ok(())
}
