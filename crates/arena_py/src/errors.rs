//! Maps `arena_core::ArenaError` variants onto Python exception classes. The classes
//! live in `roboracer_arena._core` (their `__module__`, so they pickle across process
//! pools) and are re-exported by `roboracer_arena.errors`.
//!
//! The bad-value errors (a malformed map file, argument, config or spec) are also
//! `ValueError`s, as pydantic's `ValidationError` is: code that catches `ValueError`
//! keeps working when a check moves into the core. `create_exception!` takes one base,
//! so [`value_exception!`] creates those types with the two bases `(ArenaError, ValueError)`.

use arena_core::ArenaError as CoreError;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyTuple, PyType};

/// A new exception type `roboracer_arena._core.<name>` deriving from both `ArenaError`
/// and `ValueError` (CPython's `PyErr_NewExceptionWithDoc` takes a tuple of bases).
fn new_value_error_type(py: Python<'_>, name: &std::ffi::CStr, doc: &std::ffi::CStr) -> Py<PyType> {
    let bases = PyTuple::new(
        py,
        [py.get_type::<ArenaError>(), py.get_type::<PyValueError>()],
    )
    .expect("a tuple of two types");
    // SAFETY: valid NUL-terminated name and doc, a tuple of exception classes as the
    // base, no dict; the result is a new reference to an exception type or NULL.
    unsafe {
        let ty = pyo3::ffi::PyErr_NewExceptionWithDoc(
            name.as_ptr(),
            doc.as_ptr(),
            bases.as_ptr(),
            std::ptr::null_mut(),
        );
        Bound::from_owned_ptr_or_err(py, ty)
            .expect("Failed to initialize new exception type.")
            .cast_into_unchecked::<PyType>()
            .unbind()
    }
}

/// `create_exception!` for a bad-value error: a subclass of `ArenaError` and `ValueError`,
/// raised from Rust with `Name::new_err(msg)` like the others.
macro_rules! value_exception {
    ($name:ident, $doc:literal) => {
        #[doc = $doc]
        #[repr(transparent)]
        pub struct $name(pyo3::PyAny);

        impl $name {
            /// Creates a new [`PyErr`] of this type.
            pub fn new_err<A>(args: A) -> PyErr
            where
                A: pyo3::PyErrArguments + Send + Sync + 'static,
            {
                PyErr::new::<$name, A>(args)
            }
        }

        // SAFETY: the type object is created once (per interpreter) and kept alive by
        // the lock, as `create_exception!` does it.
        unsafe impl pyo3::type_object::PyTypeInfo for $name {
            fn type_object_raw(py: Python<'_>) -> *mut pyo3::ffi::PyTypeObject {
                static TYPE_OBJECT: pyo3::sync::PyOnceLock<Py<PyType>> =
                    pyo3::sync::PyOnceLock::new();
                TYPE_OBJECT
                    .get_or_init(py, || {
                        new_value_error_type(
                            py,
                            pyo3::ffi::c_str!(concat!("roboracer_arena._core.", stringify!($name))),
                            pyo3::ffi::c_str!($doc),
                        )
                    })
                    .as_ptr()
                    .cast()
            }
        }
    };
}

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
value_exception!(MapFormatError, "A map YAML or image is malformed.");
pyo3::create_exception!(
    roboracer_arena._core,
    CorridorError,
    ArenaError,
    "The map has no usable closed corridor."
);
value_exception!(InvalidArgumentError, "An argument is outside its domain.");
value_exception!(
    ConfigError,
    "A configuration file or value (BuildConfig, SimConfig, ...) is invalid."
);
value_exception!(SpecError, "A track specification is malformed.");
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
