//! Bindings for `arena_core::sim::episode`: the episode parameters (`EpisodeConfig`) and
//! the numpy buffers the simulator's step writes the episode results into
//! (`EpisodeBuffers`). The arithmetic is the core's.

use arena_core::sim::{
    EpisodeOut, EpisodeParams, EVENT_FAULT, EVENT_LAP, EVENT_VEHICLE, EVENT_WALL,
};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadwriteArray1, PyReadwriteArray2};
use pyo3::prelude::*;

use crate::boundary;
use crate::errors::to_py;

/// Reward weights and episode ends of `Simulator.set_episode` (the core checks them).
#[pyclass(module = "roboracer_arena._core", name = "EpisodeConfig", frozen, eq)]
#[derive(PartialEq)]
pub struct EpisodeConfig {
    pub(crate) inner: EpisodeParams,
}

#[pymethods]
impl EpisodeConfig {
    #[new]
    #[pyo3(signature = (*, progress, collision_penalty, stall_penalty, stall_speed, time_penalty,
        wrong_way_penalty, wrong_way_distance, dt, collision_ends_episode, wrong_way_ends_episode,
        max_steps = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        progress: f64,
        collision_penalty: f64,
        stall_penalty: f64,
        stall_speed: f64,
        time_penalty: f64,
        wrong_way_penalty: f64,
        wrong_way_distance: f64,
        dt: f64,
        collision_ends_episode: bool,
        wrong_way_ends_episode: bool,
        max_steps: Option<u64>,
    ) -> PyResult<Self> {
        let inner = EpisodeParams {
            progress,
            collision_penalty,
            stall_penalty,
            stall_speed,
            time_penalty,
            wrong_way_penalty,
            wrong_way_distance,
            dt,
            collision_ends_episode,
            wrong_way_ends_episode,
            max_steps,
        };
        let inner = boundary::call(py, "EpisodeConfig", move || {
            inner.validate().map(|()| inner)
        })?;
        Ok(EpisodeConfig { inner })
    }

    #[getter]
    fn max_steps(&self) -> Option<u64> {
        self.inner.max_steps
    }

    fn __repr__(&self) -> String {
        format!("EpisodeConfig({:?})", self.inner)
    }
}

/// The episode results of `E` envs x `V` vehicles, as numpy arrays the simulator writes
/// in place (`Simulator.step(..., episode=)`, `Simulator.observe(..., episode=)`).
#[pyclass(
    module = "roboracer_arena._core",
    name = "EpisodeBuffers",
    frozen,
    get_all
)]
pub struct EpisodeBuffers {
    /// (E,) float64: each env's reward (the sum over its vehicles).
    reward: Py<PyArray1<f64>>,
    /// (E,) bool: any vehicle's episode ended.
    terminated: Py<PyArray1<bool>>,
    /// (E,) bool: the step limit was reached (and the env did not terminate).
    truncated: Py<PyArray1<bool>>,
    /// (E,) int64: steps since the env's reset.
    elapsed: Py<PyArray1<i64>>,
    /// (E, V) float64: each vehicle's reward.
    vehicle_reward: Py<PyArray2<f64>>,
    /// (E, V) bool: each vehicle's end.
    vehicle_terminated: Py<PyArray2<bool>>,
    /// (E, V) float64: metres along the centreline since reset.
    progress: Py<PyArray2<f64>>,
    /// (E, V) int8: 0, +1 nose first, -1 reversing.
    wrong_way: Py<PyArray2<i8>>,
}

/// The buffers borrowed for writing (held while the core writes).
pub(crate) struct Borrowed<'py> {
    reward: PyReadwriteArray1<'py, f64>,
    terminated: PyReadwriteArray1<'py, bool>,
    truncated: PyReadwriteArray1<'py, bool>,
    elapsed: PyReadwriteArray1<'py, i64>,
    vehicle_reward: PyReadwriteArray2<'py, f64>,
    vehicle_terminated: PyReadwriteArray2<'py, bool>,
    progress: PyReadwriteArray2<'py, f64>,
    wrong_way: PyReadwriteArray2<'py, i8>,
}

fn slice<'a, T: numpy::Element, D: numpy::ndarray::Dimension>(
    a: &'a mut numpy::PyReadwriteArray<'_, T, D>,
    name: &str,
) -> PyResult<&'a mut [T]> {
    a.as_slice_mut().map_err(|e| {
        to_py(arena_core::ArenaError::invalid(format!(
            "episode {name} must be C-contiguous: {e}"
        )))
    })
}

impl<'py> Borrowed<'py> {
    /// The core's view of the buffers.
    pub(crate) fn out(&mut self) -> PyResult<EpisodeOut<'_>> {
        Ok(EpisodeOut {
            reward: slice(&mut self.reward, "reward")?,
            terminated: slice(&mut self.terminated, "terminated")?,
            truncated: slice(&mut self.truncated, "truncated")?,
            elapsed: slice(&mut self.elapsed, "elapsed")?,
            vehicle_reward: slice(&mut self.vehicle_reward, "vehicle_reward")?,
            vehicle_terminated: slice(&mut self.vehicle_terminated, "vehicle_terminated")?,
            progress: slice(&mut self.progress, "progress")?,
            wrong_way: slice(&mut self.wrong_way, "wrong_way")?,
        })
    }
}

impl EpisodeBuffers {
    /// Borrow every buffer for writing (an error when Python holds a conflicting borrow).
    pub(crate) fn borrow<'py>(&self, py: Python<'py>) -> PyResult<Borrowed<'py>> {
        let bad = |e: numpy::BorrowError| {
            to_py(arena_core::ArenaError::invalid(format!(
                "episode buffers cannot be written: {e}"
            )))
        };
        Ok(Borrowed {
            reward: self.reward.bind(py).try_readwrite().map_err(bad)?,
            terminated: self.terminated.bind(py).try_readwrite().map_err(bad)?,
            truncated: self.truncated.bind(py).try_readwrite().map_err(bad)?,
            elapsed: self.elapsed.bind(py).try_readwrite().map_err(bad)?,
            vehicle_reward: self.vehicle_reward.bind(py).try_readwrite().map_err(bad)?,
            vehicle_terminated: self
                .vehicle_terminated
                .bind(py)
                .try_readwrite()
                .map_err(bad)?,
            progress: self.progress.bind(py).try_readwrite().map_err(bad)?,
            wrong_way: self.wrong_way.bind(py).try_readwrite().map_err(bad)?,
        })
    }
}

#[pymethods]
impl EpisodeBuffers {
    /// Zeroed buffers for `num_envs` x `vehicles_per_env` (within the simulator's size
    /// budget, checked before allocating).
    #[new]
    fn new(num_envs: usize, vehicles_per_env: usize, py: Python<'_>) -> PyResult<Self> {
        let (e, v) = (num_envs, vehicles_per_env);
        arena_core::sim::check_size(e as u64, v as u64, 0, 0).map_err(to_py)?;
        Ok(EpisodeBuffers {
            reward: PyArray1::zeros(py, e, false).unbind(),
            terminated: PyArray1::zeros(py, e, false).unbind(),
            truncated: PyArray1::zeros(py, e, false).unbind(),
            elapsed: PyArray1::zeros(py, e, false).unbind(),
            vehicle_reward: PyArray2::zeros(py, [e, v], false).unbind(),
            vehicle_terminated: PyArray2::zeros(py, [e, v], false).unbind(),
            progress: PyArray2::zeros(py, [e, v], false).unbind(),
            wrong_way: PyArray2::zeros(py, [e, v], false).unbind(),
        })
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<EpisodeConfig>()?;
    m.add_class::<EpisodeBuffers>()?;
    // The event bits of the state's events (per vehicle, per step), declared once (the core's).
    m.add("EVENT_WALL", EVENT_WALL)?;
    m.add("EVENT_VEHICLE", EVENT_VEHICLE)?;
    m.add("EVENT_LAP", EVENT_LAP)?;
    m.add("EVENT_FAULT", EVENT_FAULT)?;
    Ok(())
}
