//! Closed domains (a config kind, an image format) as enums converted at the signature:
//! a binding takes `Wrap<T>` and gets `T`, never a `&str` to match in its body (the
//! `Wrap<T>` pattern of polars). The wrapper accepts the strings Python callers pass and
//! refuses any other with `InvalidArgumentError` naming the allowed values.

use arena_core::grid::mapfile::ImageFormat;
use arena_core::ArenaError;
use pyo3::prelude::*;

use crate::errors::to_py;

/// A Python value converted to the core's `T` at the signature.
pub(crate) struct Wrap<T>(pub T);

/// The schemas the core reads (`config_defaults`, `check_config`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ConfigKind {
    Sim,
    Build,
    Constructor,
    Spec,
}

impl ConfigKind {
    const NAMES: [(&'static str, ConfigKind); 4] = [
        ("sim", ConfigKind::Sim),
        ("build", ConfigKind::Build),
        ("constructor", ConfigKind::Constructor),
        ("spec", ConfigKind::Spec),
    ];

    pub(crate) fn name(self) -> &'static str {
        Self::NAMES
            .iter()
            .find(|(_, k)| *k == self)
            .map_or("", |(n, _)| n)
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for Wrap<ConfigKind> {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let text: Option<String> = obj.extract().ok();
        ConfigKind::NAMES
            .iter()
            .find(|(n, _)| text.as_deref() == Some(*n))
            .map(|(_, k)| Wrap(*k))
            .ok_or_else(|| {
                to_py(ArenaError::invalid(format!(
                    "config kind {}: expected 'sim', 'build', 'constructor' or 'spec'",
                    shown(obj, text.as_deref())
                )))
            })
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for Wrap<ImageFormat> {
    type Error = PyErr;

    /// "png" or "pgm" in any case (the core's `ImageFormat::parse` owns the names).
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        match obj.extract::<String>() {
            Ok(text) => ImageFormat::parse(&text).map(Wrap).map_err(to_py),
            Err(_) => Err(to_py(ArenaError::invalid(format!(
                "image_format must be 'png' or 'pgm', got {}",
                shown(obj, None)
            )))),
        }
    }
}

/// The refused value as the message shows it: a string quoted, anything else its repr.
fn shown(obj: Borrowed<'_, '_, PyAny>, text: Option<&str>) -> String {
    match text {
        Some(t) => format!("{t:?}"),
        None => obj
            .repr()
            .map(|r| r.to_string())
            .unwrap_or_else(|_| "?".into()),
    }
}
