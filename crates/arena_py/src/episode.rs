//! Bindings for `arena_core::sim::episode`: the episode parameters (`EpisodeConfig`) and
//! the numpy buffers the simulator's step writes the episode results into
//! (`EpisodeBuffers`). The arithmetic is the core's.

use arena_core::sim::{
    EpisodeOut, EpisodeParams, EVENT_FAULT, EVENT_LAP, EVENT_VEHICLE, EVENT_WALL,
};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadwriteArray1};
use pyo3::prelude::*;

use crate::boundary;
use crate::errors::to_py;

/// Reward weights and episode ends of `Simulator.set_episode` (the core checks them);
/// its fields are read-only attributes (the core's `EpisodeParams`, field for field).
#[pyclass(
    module = "roboracer_arena._core",
    name = "EpisodeConfig",
    frozen,
    eq,
    get_all
)]
#[derive(Clone, Copy, PartialEq)]
pub struct EpisodeConfig {
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
}

impl EpisodeConfig {
    /// The core's parameters (every field named: a field one side lacks does not compile).
    pub(crate) fn params(&self) -> EpisodeParams {
        let EpisodeConfig {
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
        } = *self;
        EpisodeParams {
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
        }
    }
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
        let config = EpisodeConfig {
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
        let params = config.params();
        boundary::call(py, "EpisodeConfig", move || params.validate())?;
        Ok(config)
    }

    fn __repr__(&self) -> String {
        format!("EpisodeConfig({:?})", self.params())
    }
}

/// The episode results of `E` envs x `V` vehicles, as numpy arrays the simulator writes
/// in place (`Simulator.step(..., episode=)`, `Simulator.observe(..., episode=)`). The
/// arrays are contiguous views of four blocks (float64, bool, int8, int64), so a step
/// borrows four arrays, not eight.
#[pyclass(module = "roboracer_arena._core", name = "EpisodeBuffers", frozen)]
pub struct EpisodeBuffers {
    /// (E,) float64: each env's reward (the sum over its vehicles).
    #[pyo3(get)]
    reward: Py<PyArray1<f64>>,
    /// (E,) bool: any vehicle's episode ended.
    #[pyo3(get)]
    terminated: Py<PyArray1<bool>>,
    /// (E,) bool: the step limit was reached (and the env did not terminate).
    #[pyo3(get)]
    truncated: Py<PyArray1<bool>>,
    /// (E,) int64: steps since the env's reset.
    #[pyo3(get)]
    elapsed: Py<PyArray1<i64>>,
    /// (E, V) float64: each vehicle's reward.
    #[pyo3(get)]
    vehicle_reward: Py<PyArray2<f64>>,
    /// (E, V) bool: each vehicle's end.
    #[pyo3(get)]
    vehicle_terminated: Py<PyArray2<bool>>,
    /// (E, V) float64: metres along the centreline since reset.
    #[pyo3(get)]
    progress: Py<PyArray2<f64>>,
    /// (E, V) int8: 0, +1 nose first, -1 reversing.
    #[pyo3(get)]
    wrong_way: Py<PyArray2<i8>>,
    blocks: Blocks,
}

/// The four blocks the views above share: [reward E | vehicle_reward E·V | progress E·V],
/// [terminated E | truncated E | vehicle_terminated E·V], wrong_way E·V, elapsed E.
struct Blocks {
    values: Py<PyArray1<f64>>,
    flags: Py<PyArray1<bool>>,
    wrong_way: Py<PyArray1<i8>>,
    elapsed: Py<PyArray1<i64>>,
    envs: usize,
}

/// The blocks borrowed for writing (held while the core writes).
pub(crate) struct Borrowed<'py> {
    values: PyReadwriteArray1<'py, f64>,
    flags: PyReadwriteArray1<'py, bool>,
    wrong_way: PyReadwriteArray1<'py, i8>,
    elapsed: PyReadwriteArray1<'py, i64>,
    envs: usize,
}

fn slice<'a, T: numpy::Element>(
    a: &'a mut PyReadwriteArray1<'_, T>,
    name: &str,
) -> PyResult<&'a mut [T]> {
    a.as_slice_mut().map_err(|e| {
        to_py(arena_core::ArenaError::invalid(format!(
            "episode {name} must be C-contiguous: {e}"
        )))
    })
}

impl<'py> Borrowed<'py> {
    /// The core's view of the buffers (its lengths are checked by the core).
    pub(crate) fn out(&mut self) -> PyResult<EpisodeOut<'_>> {
        let e = self.envs;
        let values = slice(&mut self.values, "values")?;
        let flags = slice(&mut self.flags, "flags")?;
        if values.len() < e || flags.len() < 2 * e {
            return Err(to_py(arena_core::ArenaError::invalid(
                "episode buffers were resized",
            )));
        }
        let (reward, per_vehicle) = values.split_at_mut(e);
        let (vehicle_reward, progress) = per_vehicle.split_at_mut(per_vehicle.len() / 2);
        let (terminated, rest) = flags.split_at_mut(e);
        let (truncated, vehicle_terminated) = rest.split_at_mut(e);
        Ok(EpisodeOut {
            reward,
            terminated,
            truncated,
            elapsed: slice(&mut self.elapsed, "elapsed")?,
            vehicle_reward,
            vehicle_terminated,
            progress,
            wrong_way: slice(&mut self.wrong_way, "wrong_way")?,
        })
    }
}

impl EpisodeBuffers {
    /// Borrow the blocks for writing (an error when Python holds a conflicting borrow).
    pub(crate) fn borrow<'py>(&self, py: Python<'py>) -> PyResult<Borrowed<'py>> {
        let bad = |e: numpy::BorrowError| {
            to_py(arena_core::ArenaError::invalid(format!(
                "episode buffers cannot be written: {e}"
            )))
        };
        let b = &self.blocks;
        Ok(Borrowed {
            values: b.values.bind(py).try_readwrite().map_err(bad)?,
            flags: b.flags.bind(py).try_readwrite().map_err(bad)?,
            wrong_way: b.wrong_way.bind(py).try_readwrite().map_err(bad)?,
            elapsed: b.elapsed.bind(py).try_readwrite().map_err(bad)?,
            envs: b.envs,
        })
    }
}

/// `block[start..start + len]` reshaped to `shape` (a view sharing the block).
fn view<'py, T: numpy::Element, D: numpy::ndarray::Dimension>(
    block: &Bound<'py, PyArray1<T>>,
    start: usize,
    len: usize,
    shape: &[usize],
) -> PyResult<Py<numpy::PyArray<T, D>>> {
    let part = block.call_method1(
        "__getitem__",
        (pyo3::types::PySlice::new(
            block.py(),
            start as isize,
            (start + len) as isize,
            1,
        ),),
    )?;
    let shaped = part.call_method1("reshape", (shape.to_vec(),))?;
    Ok(shaped.cast_into::<numpy::PyArray<T, D>>()?.unbind())
}

#[pymethods]
impl EpisodeBuffers {
    /// Zeroed buffers for `num_envs` x `vehicles_per_env` (within the simulator's size
    /// budget, checked before allocating).
    #[new]
    fn new(num_envs: usize, vehicles_per_env: usize, py: Python<'_>) -> PyResult<Self> {
        let (e, v) = (num_envs, vehicles_per_env);
        arena_core::sim::check_size(e as u64, v as u64, 0, 0).map_err(to_py)?;
        let n = e * v;
        let values = PyArray1::<f64>::zeros(py, e + 2 * n, false);
        let flags = PyArray1::<bool>::zeros(py, 2 * e + n, false);
        let wrong_way = PyArray1::<i8>::zeros(py, n, false);
        let elapsed = PyArray1::<i64>::zeros(py, e, false);
        Ok(EpisodeBuffers {
            reward: view(&values, 0, e, &[e])?,
            vehicle_reward: view(&values, e, n, &[e, v])?,
            progress: view(&values, e + n, n, &[e, v])?,
            terminated: view(&flags, 0, e, &[e])?,
            truncated: view(&flags, e, e, &[e])?,
            vehicle_terminated: view(&flags, 2 * e, n, &[e, v])?,
            wrong_way: view(&wrong_way, 0, n, &[e, v])?,
            elapsed: elapsed.clone().unbind(),
            blocks: Blocks {
                values: values.unbind(),
                flags: flags.unbind(),
                wrong_way: wrong_way.unbind(),
                elapsed: elapsed.unbind(),
                envs: e,
            },
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
