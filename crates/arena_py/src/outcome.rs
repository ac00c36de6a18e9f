//! The lattice generator's result as one typed, read-only object (`generate_lattice`):
//! which of the three outcomes it is, and the fields each carries (None elsewhere).
//! The core screens once, inside `construct::generate`; a rejection carries that screen.

use std::collections::BTreeMap;

use arena_core::generate::construct::Outcome;
use arena_core::generate::deadline::{Failure, Stop};
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{grid_to_py, line_to_py, to_dict};

/// A map as ``(data (H, W) uint8, origin (x, y, yaw))``.
type MapObject = (Py<PyArray2<u8>>, (f64, f64, f64));

/// What ``generate_lattice`` found: ``kind`` "accepted" (``map``, ``centreline``,
/// ``report``, ``candidate_index``, ``pitch_m``), "rejected" by the screen (``screen``)
/// or "failed" (``reasons``, ``stopped``); ``tried`` candidates in every kind.
#[pyclass(frozen, get_all, module = "roboracer_arena._core")]
pub struct LatticeOutcome {
    kind: &'static str,
    tried: u32,
    map: Option<MapObject>,
    centreline: Option<Py<PyArray2<f64>>>,
    report: Option<Py<PyDict>>,
    candidate_index: Option<u32>,
    pitch_m: Option<f64>,
    screen: Option<Py<PyDict>>,
    reasons: BTreeMap<String, u32>,
    stopped: Option<&'static str>,
}

#[pymethods]
impl LatticeOutcome {
    fn __repr__(&self) -> String {
        format!("LatticeOutcome(kind={:?}, tried={})", self.kind, self.tried)
    }
}

impl LatticeOutcome {
    fn empty(kind: &'static str, tried: u32) -> LatticeOutcome {
        LatticeOutcome {
            kind,
            tried,
            map: None,
            centreline: None,
            report: None,
            candidate_index: None,
            pitch_m: None,
            screen: None,
            reasons: BTreeMap::new(),
            stopped: None,
        }
    }

    /// A search that ended without a track.
    pub fn failed(f: Failure) -> LatticeOutcome {
        LatticeOutcome {
            reasons: f.reasons,
            stopped: f.stopped.map(|s| match s {
                Stop::Timeout => "timeout",
                Stop::Cancelled => "cancelled",
            }),
            ..Self::empty("failed", f.tried)
        }
    }

    /// The core's outcome as the Python object.
    pub fn from_core(py: Python<'_>, out: Outcome) -> PyResult<LatticeOutcome> {
        Ok(match out {
            Outcome::Accepted {
                grid,
                candidate,
                report,
                candidate_index,
                tried,
            } => {
                let (data, origin) = grid_to_py(py, grid);
                LatticeOutcome {
                    map: Some((data.unbind(), origin)),
                    centreline: Some(line_to_py(py, &candidate.centreline).unbind()),
                    report: Some(to_dict(py, &*report)?.unbind()),
                    candidate_index: Some(candidate_index),
                    pitch_m: Some(candidate.pitch_m),
                    ..Self::empty("accepted", tried)
                }
            }
            Outcome::Rejected(sr) => LatticeOutcome {
                screen: Some(to_dict(py, &sr)?.unbind()),
                ..Self::empty("rejected", 0)
            },
            Outcome::Failed {
                tried,
                reasons,
                stopped,
            } => Self::failed(Failure {
                tried,
                reasons,
                stopped,
            }),
        })
    }
}
