//! Bindings for `arena_core::sim`: the batched `Simulator`. Inputs are checked here
//! (shapes, dtypes, contiguity → `InvalidArgumentError`), the GIL is released for
//! stepping, and outputs are written in place into the caller's numpy buffers.

use std::sync::Arc;

use arena_core::sim::{
    ResetGiven, ResetOut, SimParams, Simulator as CoreSim, Track, STATE_FIELDS, STATE_SIZE,
};
use arena_core::track::params::DEFAULT_WALL_HEIGHT_M;
use arena_core::ArenaError as CoreError;
use numpy::{
    PyArray1, PyArray2, PyArray3, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods,
    PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat, PyTuple};

use crate::boundary;
use crate::episode::{EpisodeBuffers, EpisodeConfig};
use crate::errors::to_py;
use crate::start_grid::StartSpec;

/// (vertices (V, 3) float32, triangles (T, 3) uint32) of a mesh.
type MeshArrays<'py> = (Bound<'py, PyArray2<f32>>, Bound<'py, PyArray2<u32>>);

pub(crate) fn invalid(msg: impl Into<String>) -> PyErr {
    to_py(CoreError::invalid(msg))
}

/// A closed polyline from an (N, 2) float64 array or any sequence of (x, y) pairs.
fn points(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[f64; 2]>> {
    if let Ok(a) = obj.extract::<PyReadonlyArray2<'_, f64>>() {
        if a.shape()[1] != 2 {
            return Err(invalid(format!(
                "{what} must have shape (N, 2), got {:?}",
                a.shape()
            )));
        }
        let v = a.as_array();
        return Ok(v.rows().into_iter().map(|r| [r[0], r[1]]).collect());
    }
    obj.extract::<Vec<[f64; 2]>>().map_err(|_| {
        invalid(format!(
            "{what} must be an (N, 2) float64 array or a sequence of (x, y) pairs"
        ))
    })
}

pub(crate) fn check_shape(name: &str, got: &[usize], want: &[usize]) -> PyResult<()> {
    if got == want {
        Ok(())
    } else {
        Err(invalid(format!(
            "{name} must have shape {want:?}, got {got:?}"
        )))
    }
}

/// Copy a float64 array of exactly `shape` out of Python (any memory layout).
fn read_f64<const N: usize>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    shape: [usize; N],
) -> PyResult<Vec<f64>> {
    let arr = obj.cast::<PyArrayDyn<f64>>().map_err(|_| {
        invalid(format!(
            "{name} must be a numpy float64 array of shape {shape:?}"
        ))
    })?;
    check_shape(name, arr.shape(), &shape)?;
    let view = arr.try_readonly().map_err(|e| invalid(e.to_string()))?;
    Ok(view.as_array().iter().copied().collect())
}

/// A numpy bool array of shape (num_envs,) as a Vec.
pub(crate) fn read_mask(obj: &Bound<'_, PyAny>, num_envs: usize) -> PyResult<Vec<bool>> {
    let mask = obj.cast::<PyArray1<bool>>().map_err(|_| {
        invalid(format!(
            "env_mask must be a numpy bool array of shape ({num_envs},)"
        ))
    })?;
    check_shape("env_mask", mask.shape(), &[num_envs])?;
    Ok(mask
        .try_readonly()
        .map_err(|e| invalid(e.to_string()))?
        .as_array()
        .iter()
        .copied()
        .collect())
}

/// An integer index (a Python int or numpy integer; bools and floats such as 0.7 are
/// refused, never truncated).
fn index_arg(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<i64> {
    if obj.is_instance_of::<PyBool>() || obj.is_instance_of::<PyFloat>() {
        return Err(invalid(format!("{name} must be an integer, got {obj}")));
    }
    if let Ok(a) = obj.cast::<numpy::PyUntypedArray>() {
        let kind = a.dtype().kind();
        if kind != b'i' && kind != b'u' {
            return Err(invalid(format!("{name} must be an integer, got {obj}")));
        }
    }
    obj.extract::<i64>()
        .map_err(|_| invalid(format!("{name} must be an integer, got {obj}")))
}

/// A non-negative integer argument at most `max` (a Python or numpy integer; bools,
/// floats and negative or larger values refused with a message naming `name`).
fn uint_arg(obj: &Bound<'_, PyAny>, name: &str, max: u64) -> PyResult<u64> {
    let bad = || {
        invalid(format!(
            "{name} must be an integer in [0, {max}], got {obj}"
        ))
    };
    if obj.is_instance_of::<PyBool>() || obj.is_instance_of::<PyFloat>() {
        return Err(bad());
    }
    match obj.extract::<u64>() {
        Ok(v) if v <= max => Ok(v),
        _ => Err(bad()),
    }
}

/// Integer ids from a 1-D numpy integer array or a sequence of Python ints (bools and
/// floats refused), checked to hold `n` of them.
fn read_ids(obj: &Bound<'_, PyAny>, name: &str, n: usize) -> PyResult<Vec<i64>> {
    let ids: Vec<i64> = if let Ok(a) = obj.cast::<numpy::PyUntypedArray>() {
        let kind = a.dtype().kind();
        if kind != b'i' && kind != b'u' {
            return Err(invalid(format!(
                "{name} must hold integers, got a numpy {} array",
                a.dtype()
            )));
        }
        obj.call_method1("astype", ("int64",))?
            .extract::<Vec<i64>>()
            .map_err(|_| invalid(format!("{name} must be a 1-D integer array")))?
    } else {
        let mut out = Vec::new();
        for (i, item) in obj
            .try_iter()
            .map_err(|_| invalid(format!("{name} must be a sequence of int")))?
            .enumerate()
        {
            out.push(index_arg(&item?, &format!("{name}[{i}]"))?);
        }
        out
    };
    if ids.len() != n {
        return Err(invalid(format!(
            "{name} must have {n} entries, got {}",
            ids.len()
        )));
    }
    Ok(ids)
}

/// Borrow `obj` as a writable C-contiguous array of element type T and the given shape.
macro_rules! out_array {
    ($obj:expr, $ty:ty, $arr:ident, $name:expr, $shape:expr, $dtype:expr) => {{
        let a = $obj.cast::<$arr<$ty>>().map_err(|_| {
            invalid(format!(
                "{} must be a numpy {} array of shape {:?}",
                $name, $dtype, $shape
            ))
        })?;
        check_shape($name, a.shape(), &$shape)?;
        let rw = a
            .try_readwrite()
            .map_err(|e| invalid(format!("{} cannot be written: {e}", $name)))?;
        if !rw.is_c_contiguous() {
            return Err(invalid(format!("{} must be C-contiguous", $name)));
        }
        rw
    }};
}

/// Batched simulation of `num_envs` rapier worlds with `vehicles_per_env` cars each.
#[pyclass(module = "roboracer_arena._core")]
pub struct Simulator {
    inner: CoreSim,
}

/// One track's free space as the simulator holds it (`Simulator.free_space`): immutable
/// and shared, so a caller checks points while another thread steps the simulator.
#[pyclass(module = "roboracer_arena._core", frozen)]
pub struct FreeSpace {
    track: Arc<Track>,
}

#[pymethods]
impl FreeSpace {
    /// True when (x, y) lies in the track's free space: enclosed by the same closed walls
    /// as the start of its centreline (not inside a wall, an infield or beyond the outer
    /// wall). Non-finite points are not free.
    fn contains(&self, py: Python<'_>, x: f64, y: f64) -> PyResult<bool> {
        let track = self.track.clone();
        boundary::call_ok(py, "FreeSpace.contains", move || track.is_free([x, y]))
    }
}

#[pymethods]
impl Simulator {
    #[new]
    #[pyo3(signature = (tracks, num_envs, vehicles_per_env, config = None, seed = None, env_index_offset = None))]
    fn new(
        py: Python<'_>,
        tracks: &Bound<'_, PyAny>,
        num_envs: &Bound<'_, PyAny>,
        vehicles_per_env: &Bound<'_, PyAny>,
        config: Option<&Bound<'_, PyAny>>,
        seed: Option<&Bound<'_, PyAny>>,
        env_index_offset: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let env_offset = match env_index_offset {
            Some(o) if !o.is_none() => uint_arg(o, "env_index_offset", u32::MAX as u64)? as usize,
            _ => 0,
        };
        // (The core bounds the counts; these only refuse what is not a non-negative int.)
        let num_envs = uint_arg(num_envs, "num_envs", u32::MAX as u64)? as usize;
        let vehicles_per_env =
            uint_arg(vehicles_per_env, "vehicles_per_env", u32::MAX as u64)? as usize;
        let seed = match seed {
            Some(s) if !s.is_none() => uint_arg(s, "seed", u64::MAX)?,
            _ => 0,
        };
        let params: SimParams =
            crate::convert::from_py(py, config, "simulator config", CoreError::config)?;
        let params = boundary::call(py, "Simulator", move || params.validate().map(|_| params))?;
        let mut raw = Vec::new();
        for (i, item) in tracks.try_iter()?.enumerate() {
            let item = item?;
            let bad = || {
                invalid(format!(
                    "tracks[{i}] must be (walls, centreline) or (walls, centreline, wall_height)"
                ))
            };
            let (walls, centre, height) =
                match item.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>() {
                    Ok((w, c)) => (w, c, DEFAULT_WALL_HEIGHT_M),
                    Err(_) => {
                        let (w, c, h): (Bound<'_, PyAny>, Bound<'_, PyAny>, Bound<'_, PyAny>) =
                            item.extract().map_err(|_| bad())?;
                        let h = match h.extract::<f64>() {
                            Ok(v) if !h.is_instance_of::<PyBool>() => v,
                            _ => {
                                return Err(invalid(format!(
                                    "tracks[{i}] wall_height must be a number"
                                )))
                            }
                        };
                        (w, c, h)
                    }
                };
            let mut ws = Vec::new();
            for (j, w) in walls.try_iter()?.enumerate() {
                ws.push(points(&w?, &format!("tracks[{i}] wall {j}"))?);
            }
            raw.push((
                ws,
                points(&centre, &format!("tracks[{i}] centreline"))?,
                height,
            ));
        }
        let inner = boundary::call(py, "Simulator", move || {
            let built: arena_core::Result<Vec<Arc<Track>>> = raw
                .iter()
                .enumerate()
                .map(|(i, (w, c, h))| {
                    Track::new(w, c, *h)
                        .map(Arc::new)
                        .map_err(|e| CoreError::invalid(format!("tracks[{i}]: {e}")))
                })
                .collect();
            CoreSim::with_env_offset(built?, num_envs, vehicles_per_env, params, seed, env_offset)
        })?;
        Ok(Simulator { inner })
    }

    #[getter]
    fn num_envs(&self) -> usize {
        self.inner.num_envs()
    }
    #[getter]
    fn vehicles_per_env(&self) -> usize {
        self.inner.vehicles_per_env()
    }
    #[getter]
    fn num_beams(&self) -> usize {
        self.inner.num_beams()
    }
    #[getter]
    fn num_tracks(&self) -> usize {
        self.inner.tracks().len()
    }
    #[getter]
    fn state_fields<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, STATE_FIELDS)
    }
    #[getter]
    fn dt(&self) -> f64 {
        self.inner.params().physics.dt
    }
    /// The validated configuration actually in use (a dict of ``SimConfig`` fields).
    #[getter]
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        crate::convert::to_dict(py, self.inner.params())
    }

    /// (world steps through the rapier pipeline, contact-free shortcut steps) so far,
    /// summed over envs.
    fn step_counts(&self) -> (u64, u64) {
        let c = self.inner.step_counts();
        (c[0], c[1])
    }

    /// Track id of every env.
    fn track_ids<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let ids: Vec<i64> = (0..self.inner.num_envs())
            .map(|e| self.inner.track_of(e) as i64)
            .collect();
        PyArray1::from_vec(py, ids)
    }

    fn set_tracks(&mut self, py: Python<'_>, track_ids: &Bound<'_, PyAny>) -> PyResult<()> {
        let ids = read_ids(track_ids, "track_ids", self.inner.num_envs())?;
        let inner = &mut self.inner;
        boundary::call(py, "set_tracks", move || inner.set_tracks(&ids))
    }

    /// Configure `reset_drawn` (a `StartSpec`; the core checks it against the tracks).
    fn set_start_spec(&mut self, py: Python<'_>, spec: PyRef<'_, StartSpec>) -> PyResult<()> {
        let spec = spec.inner.clone();
        let inner = &mut self.inner;
        boundary::call(py, "set_start_spec", move || inner.set_start_spec(spec))
    }

    /// Reset the envs where `env_mask` is True with natively drawn tracks, poses, speeds
    /// and lidar randomisation (each env from its own stream), except what `track_ids`
    /// (E,), `poses` (E, V, 3) or `speeds` (E, V) fix; writes what each reset env got into
    /// `out_track_ids` (E,) int64, `out_poses` (E, V, 3) float64, `out_speeds` (E, V) float64.
    #[pyo3(signature = (env_mask, out_track_ids, out_poses, out_speeds, track_ids = None, poses = None, speeds = None))]
    #[allow(clippy::too_many_arguments)]
    fn reset_drawn(
        &mut self,
        py: Python<'_>,
        env_mask: &Bound<'_, PyAny>,
        out_track_ids: &Bound<'_, PyAny>,
        out_poses: &Bound<'_, PyAny>,
        out_speeds: &Bound<'_, PyAny>,
        track_ids: Option<&Bound<'_, PyAny>>,
        poses: Option<&Bound<'_, PyAny>>,
        speeds: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let (e, v) = (self.inner.num_envs(), self.inner.vehicles_per_env());
        let mask = read_mask(env_mask, e)?;
        let given_tracks = match track_ids {
            Some(t) if !t.is_none() => Some(read_ids(t, "track_ids", e)?),
            _ => None,
        };
        let given_poses = match poses {
            Some(p) if !p.is_none() => Some(read_f64(p, "poses", [e, v, 3])?),
            _ => None,
        };
        let given_speeds = match speeds {
            Some(s) if !s.is_none() => Some(read_f64(s, "speeds", [e, v])?),
            _ => None,
        };
        let mut ot = out_array!(out_track_ids, i64, PyArray1, "out_track_ids", [e], "int64");
        let mut op = out_array!(out_poses, f64, PyArray3, "out_poses", [e, v, 3], "float64");
        let mut os = out_array!(out_speeds, f64, PyArray2, "out_speeds", [e, v], "float64");
        let out = ResetOut {
            tracks: ot.as_slice_mut().map_err(|e| invalid(e.to_string()))?,
            poses: op.as_slice_mut().map_err(|e| invalid(e.to_string()))?,
            speeds: os.as_slice_mut().map_err(|e| invalid(e.to_string()))?,
        };
        let inner = &mut self.inner;
        boundary::call(py, "reset_drawn", move || {
            let given = ResetGiven {
                tracks: given_tracks.as_deref(),
                poses: given_poses.as_deref(),
                speeds: given_speeds.as_deref(),
            };
            inner.reset_drawn(&mask, given, out)
        })
    }

    fn reset(
        &mut self,
        py: Python<'_>,
        env_mask: &Bound<'_, PyAny>,
        poses: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let (e, v) = (self.inner.num_envs(), self.inner.vehicles_per_env());
        let mask = read_mask(env_mask, e)?;
        let poses = read_f64(poses, "poses", [e, v, 3])?;
        let inner = &mut self.inner;
        boundary::call(py, "reset", move || inner.reset(&mask, &poses))
    }

    /// Rolling start: forward speeds (E, V) m/s for the envs where `env_mask` is True,
    /// right after `reset`.
    fn set_speeds(
        &mut self,
        py: Python<'_>,
        env_mask: &Bound<'_, PyAny>,
        speeds: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let (e, v) = (self.inner.num_envs(), self.inner.vehicles_per_env());
        let mask = read_mask(env_mask, e)?;
        let speeds = read_f64(speeds, "speeds", [e, v])?;
        let inner = &mut self.inner;
        boundary::call(py, "set_speeds", move || inner.set_speeds(&mask, &speeds))
    }

    /// Per-episode vehicle parameters (domain randomisation) for the envs where
    /// `env_mask` is True: friction, mass (kg), steering and throttle lags (s), each a
    /// float64 array of shape (E,). They hold until set again.
    fn set_vehicle_params(
        &mut self,
        py: Python<'_>,
        env_mask: &Bound<'_, PyAny>,
        friction: &Bound<'_, PyAny>,
        mass: &Bound<'_, PyAny>,
        steer_lag: &Bound<'_, PyAny>,
        throttle_lag: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let e = self.inner.num_envs();
        let mask = read_mask(env_mask, e)?;
        let (f, m) = (
            read_f64(friction, "friction", [e])?,
            read_f64(mass, "mass", [e])?,
        );
        let (s, t) = (
            read_f64(steer_lag, "steer_lag", [e])?,
            read_f64(throttle_lag, "throttle_lag", [e])?,
        );
        let inner = &mut self.inner;
        boundary::call(py, "set_vehicle_params", move || {
            inner.set_vehicle_params(&mask, &f, &m, &s, &t)
        })
    }

    /// Run the episode step (progress, reward, wrong-way, termination, truncation) in
    /// every step from now on, and restart an env's episode with its reset; a later call
    /// changes the parameters and keeps the episodes.
    fn set_episode(&mut self, py: Python<'_>, config: PyRef<'_, EpisodeConfig>) -> PyResult<()> {
        let params = config.params();
        let inner = &mut self.inner;
        boundary::call(py, "set_episode", move || inner.set_episode(params))
    }

    /// Apply the action rule in place to `actions` ((E, V, 2) float64, C-contiguous):
    /// NaN becomes 0, every other value (±inf included) is clipped to ±max_steer and
    /// [min_speed, max_speed], as `step` applies it to what it is given.
    fn sanitise_actions(&self, actions: &Bound<'_, PyAny>) -> PyResult<()> {
        let (e, v) = (self.inner.num_envs(), self.inner.vehicles_per_env());
        let mut a = out_array!(actions, f64, PyArray3, "actions", [e, v, 2], "float64");
        let a = a.as_slice_mut().map_err(|e| invalid(e.to_string()))?;
        self.inner.sanitise_actions(a).map_err(to_py)
    }

    #[pyo3(signature = (actions, substeps, scans, state, events, episode = None))]
    #[allow(clippy::too_many_arguments)]
    fn step(
        &mut self,
        py: Python<'_>,
        actions: &Bound<'_, PyAny>,
        substeps: &Bound<'_, PyAny>,
        scans: &Bound<'_, PyAny>,
        state: &Bound<'_, PyAny>,
        events: &Bound<'_, PyAny>,
        episode: Option<PyRef<'_, EpisodeBuffers>>,
    ) -> PyResult<()> {
        let (e, v) = (self.inner.num_envs(), self.inner.vehicles_per_env());
        let acts = read_f64(actions, "actions", [e, v, 2])?;
        let substeps = uint_arg(substeps, "substeps", 100_000)? as usize;
        self.run(
            py,
            Advance::Step {
                actions: acts,
                substeps,
            },
            scans,
            state,
            events,
            episode,
        )
    }

    /// Write state, events and (unless `scans` is None) scans without stepping: of every
    /// env, or only of those where `env_mask` is True (the other rows are left alone);
    /// with `episode`, the same envs' episode results too.
    #[pyo3(signature = (scans, state, events, env_mask = None, episode = None))]
    fn observe(
        &mut self,
        py: Python<'_>,
        scans: &Bound<'_, PyAny>,
        state: &Bound<'_, PyAny>,
        events: &Bound<'_, PyAny>,
        env_mask: Option<&Bound<'_, PyAny>>,
        episode: Option<PyRef<'_, EpisodeBuffers>>,
    ) -> PyResult<()> {
        let mask = match env_mask {
            Some(m) if !m.is_none() => Some(read_mask(m, self.inner.num_envs())?),
            _ => None,
        };
        self.run(
            py,
            Advance::Observe { env_mask: mask },
            scans,
            state,
            events,
            episode,
        )
    }

    /// Pose (x, y, heading) on track `track_id`'s centreline at arc length `s` (wrapped).
    fn centreline_pose(
        &self,
        py: Python<'_>,
        track_id: &Bound<'_, PyAny>,
        s: f64,
    ) -> PyResult<(f64, f64, f64)> {
        if !s.is_finite() {
            return Err(invalid(format!("s must be finite, got {s}")));
        }
        let track = self.track_arg(track_id)?;
        let p = boundary::call_ok(py, "centreline_pose", move || track.centreline.pose_at(s))?;
        Ok((p[0], p[1], p[2]))
    }

    /// The free space of track `track_id` (a [`FreeSpace`] sharing the track, usable from
    /// any thread while the simulator steps).
    fn free_space(&self, track_id: &Bound<'_, PyAny>) -> PyResult<FreeSpace> {
        Ok(FreeSpace {
            track: self.track_arg(track_id)?.clone(),
        })
    }

    fn centreline_length(&self, py: Python<'_>, track_id: &Bound<'_, PyAny>) -> PyResult<f64> {
        let track = self.track_arg(track_id)?;
        boundary::call_ok(py, "centreline_length", move || track.centreline.length())
    }

    /// The (closed) centreline points of a track, (M, 2) float64.
    fn centreline<'py>(
        &self,
        py: Python<'py>,
        track_id: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let c = &self.track_arg(track_id)?.centreline;
        let rows: Vec<Vec<f64>> = boundary::call_ok(py, "centreline", move || {
            (0..c.num_segments()).map(|i| c.point(i).to_vec()).collect()
        })?;
        PyArray2::from_vec2(py, &rows).map_err(|e| invalid(e.to_string()))
    }

    /// The collision wall mesh of a track as the physics engine holds it (shared by all
    /// envs on that track): (vertices (V, 3) float32, triangles (T, 3) uint32).
    fn wall_mesh<'py>(
        &self,
        py: Python<'py>,
        track_id: &Bound<'_, PyAny>,
    ) -> PyResult<MeshArrays<'py>> {
        let track = self.track_arg(track_id)?;
        let (v, t) = boundary::call_ok(py, "wall_mesh", move || {
            let (v, t) = track.wall_mesh();
            let v: Vec<Vec<f32>> = v.iter().map(|p| p.to_vec()).collect();
            let t: Vec<Vec<u32>> = t.iter().map(|p| p.to_vec()).collect();
            (v, t)
        })?;
        Ok((
            PyArray2::from_vec2(py, &v).map_err(|e| invalid(e.to_string()))?,
            PyArray2::from_vec2(py, &t).map_err(|e| invalid(e.to_string()))?,
        ))
    }

    fn __repr__(&self) -> String {
        format!(
            "Simulator(num_envs={}, vehicles_per_env={}, num_beams={}, tracks={}, dt={})",
            self.inner.num_envs(),
            self.inner.vehicles_per_env(),
            self.inner.num_beams(),
            self.inner.tracks().len(),
            self.inner.params().physics.dt
        )
    }
}

/// What [`Simulator::run`] does before writing the outputs.
enum Advance {
    /// `substeps` physics steps with `actions` (E x V x 2, flat).
    Step { actions: Vec<f64>, substeps: usize },
    /// No stepping: observe every env, or only those where `env_mask` is true.
    Observe { env_mask: Option<Vec<bool>> },
}

impl Simulator {
    /// The track named by a `track_id` argument (an integer in range).
    fn track_arg(&self, obj: &Bound<'_, PyAny>) -> PyResult<&Arc<Track>> {
        let id = index_arg(obj, "track_id")?;
        let n = self.inner.tracks().len();
        if !(0..n as i64).contains(&id) {
            return Err(invalid(format!(
                "track_id {id} out of range (have {n} tracks)"
            )));
        }
        self.inner.track(id as usize).map_err(to_py)
    }

    fn run(
        &mut self,
        py: Python<'_>,
        advance: Advance,
        scans: &Bound<'_, PyAny>,
        state: &Bound<'_, PyAny>,
        events: &Bound<'_, PyAny>,
        episode: Option<PyRef<'_, EpisodeBuffers>>,
    ) -> PyResult<()> {
        let (e, v, b) = (
            self.inner.num_envs(),
            self.inner.vehicles_per_env(),
            self.inner.num_beams(),
        );
        let mut st = out_array!(state, f64, PyArray3, "state", [e, v, STATE_SIZE], "float64");
        let mut ev = out_array!(events, u8, PyArray2, "events", [e, v], "uint8");
        let mut sc = if scans.is_none() {
            None
        } else {
            Some(out_array!(
                scans,
                f32,
                PyArray3,
                "scans",
                [e, v, b],
                "float32"
            ))
        };
        let st = st.as_slice_mut().map_err(|e| invalid(e.to_string()))?;
        let ev = ev.as_slice_mut().map_err(|e| invalid(e.to_string()))?;
        let sc = match sc.as_mut() {
            Some(s) => Some(s.as_slice_mut().map_err(|e| invalid(e.to_string()))?),
            None => None,
        };
        let mut borrowed = match episode.as_ref() {
            Some(b) => Some(b.borrow(py)?),
            None => None,
        };
        let out = match borrowed.as_mut() {
            Some(b) => Some(b.out()?),
            None => None,
        };
        let inner = &mut self.inner;
        boundary::call(py, "step", move || match (advance, out) {
            (Advance::Step { actions, substeps }, None) => {
                inner.step(&actions, substeps, sc, st, ev)
            }
            (Advance::Step { actions, substeps }, Some(out)) => {
                inner.step_episode(&actions, substeps, sc, st, ev, out)
            }
            (Advance::Observe { env_mask }, None) => {
                inner.observe_masked(env_mask.as_deref(), sc, st, ev)
            }
            (Advance::Observe { env_mask }, Some(out)) => {
                inner.observe_episode(env_mask.as_deref(), sc, st, ev, out)
            }
        })
    }
}

/// (walls, centreline) as numpy arrays.
type TrackArrays<'py> = (Vec<Bound<'py, PyArray2<f64>>>, Bound<'py, PyArray2<f64>>);

/// Analytic stadium track (walls [outer, inner], centreline), for tests and benchmarks:
/// straights of `straight` m, centreline radius `radius` m, corridor `width` m.
#[pyfunction]
#[pyo3(signature = (straight = 6.0, radius = 3.0, width = 2.0))]
fn stadium_track<'py>(
    py: Python<'py>,
    straight: f64,
    radius: f64,
    width: f64,
) -> PyResult<TrackArrays<'py>> {
    let (walls, centre) = boundary::call(py, "stadium_track", move || {
        arena_core::sim::shapes::check_stadium(straight, radius, width)?;
        Ok(arena_core::sim::shapes::stadium_track(
            straight, radius, width,
        ))
    })?;
    let arr = |pts: &[[f64; 2]]| {
        PyArray2::from_vec2(py, &pts.iter().map(|p| p.to_vec()).collect::<Vec<_>>())
            .map_err(|e| invalid(e.to_string()))
    };
    Ok((
        walls.iter().map(|w| arr(w)).collect::<PyResult<_>>()?,
        arr(&centre)?,
    ))
}

/// check_sim_size(num_envs, vehicles_per_env, beams, frames): the simulator's size budget
/// (`arena_core::sim::budget`), the one rule the Python env applies before allocating:
/// ``ConfigError`` when envs x vehicles or the scan values are over it.
#[pyfunction]
fn check_sim_size(
    num_envs: &Bound<'_, PyAny>,
    vehicles_per_env: &Bound<'_, PyAny>,
    beams: &Bound<'_, PyAny>,
    frames: &Bound<'_, PyAny>,
) -> PyResult<()> {
    arena_core::sim::check_size(
        uint_arg(num_envs, "num_envs", u64::MAX)?,
        uint_arg(vehicles_per_env, "vehicles_per_env", u64::MAX)?,
        uint_arg(beams, "beams", u64::MAX)?,
        uint_arg(frames, "frames", u64::MAX)?,
    )
    .map_err(to_py)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Simulator>()?;
    m.add_class::<FreeSpace>()?;
    m.add_function(wrap_pyfunction!(stadium_track, m)?)?;
    m.add_function(wrap_pyfunction!(check_sim_size, m)?)?;
    m.add("SIM_MAX_VEHICLES", arena_core::sim::MAX_VEHICLES)?;
    m.add("SIM_MAX_SCAN_VALUES", arena_core::sim::MAX_SCAN_VALUES)?;
    m.add("STATE_FIELDS", PyTuple::new(m.py(), STATE_FIELDS)?)?;
    Ok(())
}
