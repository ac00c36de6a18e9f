//! Read-only Python mirrors of the core's report structs, built field for field.
//!
//! [`mirror!`] declares a frozen pyclass with `get_all` and converts each core struct it
//! mirrors by an exhaustive destructuring: a field the core adds, drops or renames is a
//! compile error here, never a silent drift. [`FromCore`] converts one field: plain
//! values as they are, nested structs into their own mirrors, closed domains (the core's
//! enums) into their names, which the stub types as `Literal`.

use arena_core::grid::image::MapMode;
use arena_core::grid::mapfile::ImageFormat;
use arena_core::track::features::FeatureKind;
use pyo3::prelude::*;

/// A core value as its Python-side mirror.
pub(crate) trait FromCore<C>: Sized {
    fn from_core(py: Python<'_>, core: C) -> PyResult<Self>;
}

/// Plain values cross as they are.
macro_rules! as_is {
    ($($t:ty),+) => {
        $(impl FromCore<$t> for $t {
            fn from_core(_: Python<'_>, core: $t) -> PyResult<Self> {
                Ok(core)
            }
        })+
    };
}
as_is!(bool, u8, usize, f64, String);

impl FromCore<[f64; 2]> for (f64, f64) {
    fn from_core(_: Python<'_>, [a, b]: [f64; 2]) -> PyResult<Self> {
        Ok((a, b))
    }
}

impl<C, T: FromCore<C>> FromCore<Vec<C>> for Vec<T> {
    fn from_core(py: Python<'_>, core: Vec<C>) -> PyResult<Self> {
        core.into_iter().map(|c| T::from_core(py, c)).collect()
    }
}

impl<C, T: FromCore<C>> FromCore<Option<C>> for Option<T> {
    fn from_core(py: Python<'_>, core: Option<C>) -> PyResult<Self> {
        core.map(|c| T::from_core(py, c)).transpose()
    }
}

/// A nested struct: its mirror, as a Python object.
impl<C, T> FromCore<C> for Py<T>
where
    T: FromCore<C> + pyo3::PyClass + Into<pyo3::PyClassInitializer<T>>,
{
    fn from_core(py: Python<'_>, core: C) -> PyResult<Self> {
        Py::new(py, T::from_core(py, core)?)
    }
}

/// A closed domain crosses as its name (the stub's `Literal`); the core owns the names.
macro_rules! by_name {
    ($($t:ty => $name:ident),+) => {
        $(impl FromCore<$t> for String {
            fn from_core(_: Python<'_>, core: $t) -> PyResult<Self> {
                Ok(core.$name().to_owned())
            }
        })+
    };
}
by_name!(FeatureKind => name, ImageFormat => name, MapMode => as_str);

/// `mirror!(Doc Name { field: Type, .. } from CoreA, CoreB)`: the pyclass `Name` (frozen,
/// `get_all`, a `__repr__` naming every field) and `FromCore<CoreX>` for each core struct
/// listed, each of which must have exactly these fields. `Name { .. } from Core = pattern`
/// takes a core struct of another shape through a pattern that binds every field (and
/// names every field it drops with `_`), so it stays exhaustive too.
macro_rules! mirror {
    ($(#[$doc:meta])* $name:ident $fields:tt from $($core:ident),+) => {
        mirror!(@class $(#[$doc])* $name $fields);
        $(mirror!(@from $core $name $fields);)+
    };
    ($(#[$doc:meta])* $name:ident $fields:tt from $core:ty = $pat:pat) => {
        mirror!(@class $(#[$doc])* $name $fields);
        mirror!(@build $core, $pat, $name $fields);
    };
    (@class $(#[$doc:meta])* $name:ident { $($(#[$fdoc:meta])* $field:ident: $ty:ty),+ $(,)? }) => {
        $(#[$doc])*
        #[pyclass(frozen, get_all, module = "roboracer_arena._core")]
        pub struct $name {
            $($(#[$fdoc])* $field: $ty),+
        }

        #[pymethods]
        impl $name {
            fn __repr__(slf: &Bound<'_, Self>) -> PyResult<String> {
                let fields: Vec<String> = [$(stringify!($field)),+]
                    .iter()
                    .map(|f| Ok(format!("{f}={}", slf.getattr(*f)?.repr()?)))
                    .collect::<PyResult<_>>()?;
                Ok(format!("{}({})", stringify!($name), fields.join(", ")))
            }

            /// Pickling (a map's meta rides along to worker processes): the fields, in
            /// order, back through `_unpickle`; Python code has no other constructor.
            fn __reduce__<'py>(
                slf: &Bound<'py, Self>,
            ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
                let fields = [$(slf.getattr(stringify!($field))?),+];
                Ok((
                    slf.get_type().getattr("_unpickle")?,
                    pyo3::types::PyTuple::new(slf.py(), fields)?,
                ))
            }

            #[staticmethod]
            #[allow(clippy::too_many_arguments)] // one per field, as `__reduce__` lists them
            fn _unpickle($($field: $ty),+) -> Self {
                $name { $($field),+ }
            }
        }
    };
    // Exhaustive on purpose (no `..`): see the module doc.
    (@from $core:ident $name:ident { $($(#[$fdoc:meta])* $field:ident: $ty:ty),+ $(,)? }) => {
        mirror!(@build $core, $core { $($field),+ }, $name { $($field: $ty),+ });
    };
    (@build $core:ty, $pat:pat, $name:ident { $($(#[$fdoc:meta])* $field:ident: $ty:ty),+ $(,)? }) => {
        impl $crate::mirror::FromCore<$core> for $name {
            fn from_core(py: Python<'_>, core: $core) -> PyResult<Self> {
                let $pat = core;
                Ok($name {
                    $($field: $crate::mirror::FromCore::from_core(py, $field)?),+
                })
            }
        }
    };
}
pub(crate) use mirror;
