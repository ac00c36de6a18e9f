//! Binding for `arena_core::sim::progress`: `ProgressTracker`, the simulator's progress and
//! lap counting along a centreline for a car it does not step (the PhysX drive loop).

use arena_core::sim::ProgressTracker as CoreTracker;
use numpy::PyReadonlyArray2;
use pyo3::prelude::*;

use crate::convert::points_from_py;
use crate::errors::to_py;

/// Progress along a closed centreline from positions fed in (the core's lap rule: a lap
/// is complete when the car travelled one centreline length forwards since the start).
#[pyclass(module = "roboracer_arena._core", name = "ProgressTracker")]
pub struct ProgressTracker {
    inner: CoreTracker,
}

#[pymethods]
impl ProgressTracker {
    #[new]
    fn new(centreline: PyReadonlyArray2<'_, f64>, x: f64, y: f64) -> PyResult<Self> {
        let line = points_from_py(&centreline, "centreline")?;
        let inner = CoreTracker::new(&line, [x, y]).map_err(to_py)?;
        Ok(ProgressTracker { inner })
    }

    /// The car moved to (x, y) in `elapsed` s, at most `max_move` m; True when this
    /// completed a lap.
    fn update(&mut self, x: f64, y: f64, elapsed: f64, max_move: f64) -> PyResult<bool> {
        self.inner.update([x, y], elapsed, max_move).map_err(to_py)
    }

    /// Metres travelled along the centreline since the start (negative backwards).
    #[getter]
    fn travel(&self) -> f64 {
        self.inner.progress().travel
    }

    /// Start line crossings forwards minus backwards.
    #[getter]
    fn laps(&self) -> i32 {
        self.inner.progress().laps
    }

    /// Lap length (m); 0 for an open map.
    #[getter]
    fn length(&self) -> f64 {
        self.inner.length()
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<ProgressTracker>()
}
