//! `nearest_specs`'s result as typed, read-only objects: the suggestions that build and
//! how far the search got.

use arena_core::generate::nearest::NearestReport;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::to_dict;

/// One changed spec that builds: which ``field`` changed, the whole ``spec`` (a
/// ``TrackSpec`` document) and the ``seed`` / ``candidate_index`` that accept it.
#[pyclass(frozen, get_all, module = "roboracer_arena._core")]
pub struct NearestSuggestion {
    field: &'static str,
    spec: Py<PyDict>,
    seed: u64,
    candidate_index: u32,
}

/// What ``nearest_specs`` found: ``suggestions``, ``probes`` run and whether the search
/// was ``exhausted`` (the deadline cut it short).
#[pyclass(frozen, get_all, module = "roboracer_arena._core")]
pub struct NearestFound {
    suggestions: Vec<Py<NearestSuggestion>>,
    probes: u32,
    exhausted: bool,
}

impl NearestFound {
    /// The core's report as the Python object.
    pub fn from_core(py: Python<'_>, report: NearestReport) -> PyResult<NearestFound> {
        let suggestions = report
            .suggestions
            .iter()
            .map(|s| {
                let one = NearestSuggestion {
                    field: s.field,
                    spec: to_dict(py, &s.spec)?.unbind(),
                    seed: s.seed,
                    candidate_index: s.candidate_index,
                };
                Py::new(py, one)
            })
            .collect::<PyResult<_>>()?;
        Ok(NearestFound {
            suggestions,
            probes: report.probes,
            exhausted: report.exhausted,
        })
    }
}
