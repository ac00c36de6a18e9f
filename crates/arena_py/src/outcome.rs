//! The lattice generator's result as one typed, read-only object (`generate_lattice`):
//! which of the three outcomes it is, and the fields each carries (None elsewhere).
//! The core screens once, inside `construct::generate`; a rejection carries that screen.
//! `construct_lattice`'s result, the constructor alone, is a [`Construction`].

use std::collections::BTreeMap;

use arena_core::generate::construct::{Candidate, Outcome};
use arena_core::generate::deadline::{Failure, Stop};
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::convert::{grid_to_py, line_to_py};
use crate::mirror::FromCore;
use crate::reports::{ScreenResult, ValidationReport};

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
    report: Option<Py<ValidationReport>>,
    candidate_index: Option<u32>,
    pitch_m: Option<f64>,
    screen: Option<Py<ScreenResult>>,
    reasons: BTreeMap<String, u32>,
    stopped: Option<&'static str>,
}

#[pymethods]
impl LatticeOutcome {
    fn __repr__(&self) -> String {
        format!("LatticeOutcome(kind={:?}, tried={})", self.kind, self.tried)
    }
}

/// The name of what stopped a search early.
fn stop_name(stop: Stop) -> &'static str {
    match stop {
        Stop::Timeout => "timeout",
        Stop::Cancelled => "cancelled",
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
            stopped: f.stopped.map(stop_name),
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
                    report: Some(FromCore::from_core(py, *report)?),
                    candidate_index: Some(candidate_index),
                    pitch_m: Some(candidate.pitch_m),
                    ..Self::empty("accepted", tried)
                }
            }
            Outcome::Rejected(sr) => LatticeOutcome {
                screen: Some(FromCore::from_core(py, sr)?),
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

/// What ``construct_lattice`` found: the first candidate's ``centreline`` and
/// ``pitch_m``, or (both None) the ``reasons`` no candidate passed the constructor's
/// checks and what ``stopped`` the search early; ``tried`` candidates.
#[pyclass(frozen, get_all, module = "roboracer_arena._core")]
pub struct Construction {
    tried: u32,
    centreline: Option<Py<PyArray2<f64>>>,
    pitch_m: Option<f64>,
    reasons: BTreeMap<String, u32>,
    stopped: Option<&'static str>,
}

#[pymethods]
impl Construction {
    fn __repr__(&self) -> String {
        format!(
            "Construction(tried={}, built={})",
            self.tried,
            self.centreline.is_some()
        )
    }
}

impl Construction {
    /// `first_candidate`'s result (None: the deadline passed inside one candidate).
    #[allow(clippy::type_complexity)]
    pub fn from_core(
        py: Python<'_>,
        out: Option<Result<(Candidate, u32), (u32, BTreeMap<String, u32>)>>,
    ) -> Construction {
        let failed = |f: Failure| Construction {
            tried: f.tried,
            centreline: None,
            pitch_m: None,
            reasons: f.reasons,
            stopped: f.stopped.map(stop_name),
        };
        match out {
            None => failed(Failure::abandoned()),
            Some(Ok((c, tried))) => Construction {
                tried,
                centreline: Some(line_to_py(py, &c.centreline).unbind()),
                pitch_m: Some(c.pitch_m),
                reasons: BTreeMap::new(),
                stopped: None,
            },
            Some(Err((tried, reasons))) => failed(Failure {
                tried,
                reasons,
                stopped: None,
            }),
        }
    }
}
