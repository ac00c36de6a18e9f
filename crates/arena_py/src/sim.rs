//! Bindings for `arena_core::sim`: the batched `Simulator`. Inputs are checked here
//! (shapes, dtypes, contiguity → `InvalidArgumentError`), the GIL is released for
//! stepping, and outputs are written in place into the caller's numpy buffers.

use std::sync::Arc;

use arena_core::sim::{SimParams, Simulator as CoreSim, Track, STATE_FIELDS, STATE_SIZE};
use arena_core::ArenaError as CoreError;
use numpy::{
    PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::errors::{to_py, IntoPyResult};

/// (vertices (V, 3) float32, triangles (T, 3) uint32) of a mesh.
type MeshArrays<'py> = (Bound<'py, PyArray2<f32>>, Bound<'py, PyArray2<u32>>);

fn invalid(msg: impl Into<String>) -> PyErr {
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

fn check_shape(name: &str, got: &[usize], want: &[usize]) -> PyResult<()> {
    if got == want {
        Ok(())
    } else {
        Err(invalid(format!(
            "{name} must have shape {want:?}, got {got:?}"
        )))
    }
}

/// Copy a float64 array of exactly `shape` out of Python (any memory layout).
fn read_f64_3d(obj: &Bound<'_, PyAny>, name: &str, shape: [usize; 3]) -> PyResult<Vec<f64>> {
    let arr = obj.cast::<PyArray3<f64>>().map_err(|_| {
        invalid(format!(
            "{name} must be a numpy float64 array of shape {shape:?}"
        ))
    })?;
    check_shape(name, arr.shape(), &shape)?;
    let view = arr.try_readonly().map_err(|e| invalid(e.to_string()))?;
    Ok(view.as_array().iter().copied().collect())
}

/// A numpy bool array of shape (num_envs,) as a Vec.
fn read_mask(obj: &Bound<'_, PyAny>, num_envs: usize) -> PyResult<Vec<bool>> {
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

#[pymethods]
impl Simulator {
    #[new]
    #[pyo3(signature = (tracks, num_envs, vehicles_per_env, config_json = "{}", seed = 0))]
    fn new(
        py: Python<'_>,
        tracks: &Bound<'_, PyAny>,
        num_envs: usize,
        vehicles_per_env: usize,
        config_json: &str,
        seed: u64,
    ) -> PyResult<Self> {
        let params = SimParams::from_json(config_json).py()?;
        let mut raw = Vec::new();
        for (i, item) in tracks.try_iter()?.enumerate() {
            let item = item?;
            let (walls, centre): (Bound<'_, PyAny>, Bound<'_, PyAny>) = item
                .extract()
                .map_err(|_| invalid(format!("tracks[{i}] must be a (walls, centreline) pair")))?;
            let mut ws = Vec::new();
            for (j, w) in walls.try_iter()?.enumerate() {
                ws.push(points(&w?, &format!("tracks[{i}] wall {j}"))?);
            }
            raw.push((ws, points(&centre, &format!("tracks[{i}] centreline"))?));
        }
        let h = params.physics.wall_height;
        let inner = py
            .detach(move || {
                let built: arena_core::Result<Vec<Arc<Track>>> = raw
                    .iter()
                    .enumerate()
                    .map(|(i, (w, c))| {
                        Track::new(w, c, h)
                            .map(Arc::new)
                            .map_err(|e| CoreError::invalid(format!("tracks[{i}]: {e}")))
                    })
                    .collect();
                CoreSim::new(built?, num_envs, vehicles_per_env, params, seed)
            })
            .py()?;
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
    /// The validated configuration actually in use, as JSON.
    #[getter]
    fn config_json(&self) -> String {
        serde_json::to_string(self.inner.params()).unwrap_or_default()
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

    fn set_tracks(&mut self, track_ids: &Bound<'_, PyAny>) -> PyResult<()> {
        let ids: Vec<i64> = track_ids
            .extract()
            .map_err(|_| invalid("track_ids must be a sequence of int"))?;
        self.inner.set_tracks(&ids).py()
    }

    fn reset(
        &mut self,
        py: Python<'_>,
        env_mask: &Bound<'_, PyAny>,
        poses: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let (e, v) = (self.inner.num_envs(), self.inner.vehicles_per_env());
        let mask = read_mask(env_mask, e)?;
        let poses = read_f64_3d(poses, "poses", [e, v, 3])?;
        let inner = &mut self.inner;
        py.detach(move || inner.reset(&mask, &poses)).py()
    }

    /// Rolling start: forward speeds (E, V) m/s for the envs where `env_mask` is True,
    /// right after `reset`.
    fn set_speeds(
        &mut self,
        env_mask: &Bound<'_, PyAny>,
        speeds: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let (e, v) = (self.inner.num_envs(), self.inner.vehicles_per_env());
        let mask = read_mask(env_mask, e)?;
        let arr = speeds.cast::<PyArray2<f64>>().map_err(|_| {
            invalid(format!(
                "speeds must be a numpy float64 array of shape [{e}, {v}]"
            ))
        })?;
        check_shape("speeds", arr.shape(), &[e, v])?;
        let speeds: Vec<f64> = arr
            .try_readonly()
            .map_err(|e| invalid(e.to_string()))?
            .as_array()
            .iter()
            .copied()
            .collect();
        self.inner.set_speeds(&mask, &speeds).py()
    }

    /// Per-episode vehicle parameters (domain randomisation) for the envs where
    /// `env_mask` is True: friction, mass (kg), steering and throttle lags (s), each a
    /// float64 array of shape (E,). They hold until set again.
    fn set_vehicle_params(
        &mut self,
        env_mask: &Bound<'_, PyAny>,
        friction: &Bound<'_, PyAny>,
        mass: &Bound<'_, PyAny>,
        steer_lag: &Bound<'_, PyAny>,
        throttle_lag: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let e = self.inner.num_envs();
        let mask = read_mask(env_mask, e)?;
        let read = |obj: &Bound<'_, PyAny>, name: &str| -> PyResult<Vec<f64>> {
            let arr = obj.cast::<PyArray1<f64>>().map_err(|_| {
                invalid(format!(
                    "{name} must be a numpy float64 array of shape ({e},)"
                ))
            })?;
            check_shape(name, arr.shape(), &[e])?;
            Ok(arr
                .try_readonly()
                .map_err(|err| invalid(err.to_string()))?
                .as_array()
                .iter()
                .copied()
                .collect())
        };
        let (f, m) = (read(friction, "friction")?, read(mass, "mass")?);
        let (s, t) = (
            read(steer_lag, "steer_lag")?,
            read(throttle_lag, "throttle_lag")?,
        );
        self.inner.set_vehicle_params(&mask, &f, &m, &s, &t).py()
    }

    #[pyo3(signature = (actions, substeps, scans, state, events))]
    fn step(
        &mut self,
        py: Python<'_>,
        actions: &Bound<'_, PyAny>,
        substeps: usize,
        scans: &Bound<'_, PyAny>,
        state: &Bound<'_, PyAny>,
        events: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let (e, v) = (self.inner.num_envs(), self.inner.vehicles_per_env());
        let acts = read_f64_3d(actions, "actions", [e, v, 2])?;
        self.run(py, Some((acts, substeps)), scans, state, events)
    }

    fn observe(
        &mut self,
        py: Python<'_>,
        scans: &Bound<'_, PyAny>,
        state: &Bound<'_, PyAny>,
        events: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        self.run(py, None, scans, state, events)
    }

    /// Pose (x, y, heading) on track `track_id`'s centreline at arc length `s` (wrapped).
    fn centreline_pose(&self, track_id: usize, s: f64) -> PyResult<(f64, f64, f64)> {
        let p = self.inner.track(track_id).py()?.centreline.pose_at(s);
        Ok((p[0], p[1], p[2]))
    }

    fn centreline_length(&self, track_id: usize) -> PyResult<f64> {
        Ok(self.inner.track(track_id).py()?.centreline.length())
    }

    /// The (closed) centreline points of a track, (M, 2) float64.
    fn centreline<'py>(
        &self,
        py: Python<'py>,
        track_id: usize,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let c = &self.inner.track(track_id).py()?.centreline;
        let n = c.num_segments();
        let rows: Vec<Vec<f64>> = (0..n).map(|i| c.point(i).to_vec()).collect();
        PyArray2::from_vec2(py, &rows).map_err(|e| invalid(e.to_string()))
    }

    /// The collision wall mesh of a track as the physics engine holds it (shared by all
    /// envs on that track): (vertices (V, 3) float32, triangles (T, 3) uint32).
    fn wall_mesh<'py>(&self, py: Python<'py>, track_id: usize) -> PyResult<MeshArrays<'py>> {
        let (v, t) = self.inner.track(track_id).py()?.wall_mesh();
        let v: Vec<Vec<f32>> = v.iter().map(|p| p.to_vec()).collect();
        let t: Vec<Vec<u32>> = t.iter().map(|p| p.to_vec()).collect();
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

impl Simulator {
    fn run(
        &mut self,
        py: Python<'_>,
        step: Option<(Vec<f64>, usize)>,
        scans: &Bound<'_, PyAny>,
        state: &Bound<'_, PyAny>,
        events: &Bound<'_, PyAny>,
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
        let inner = &mut self.inner;
        py.detach(move || match step {
            Some((acts, substeps)) => inner.step(&acts, substeps, sc, st, ev),
            None => inner.observe(sc, st, ev),
        })
        .py()
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
    let ok = |x: f64| x.is_finite() && x > 0.0;
    if !(ok(radius) && ok(width) && straight.is_finite() && straight >= 0.0 && width < 2.0 * radius)
    {
        return Err(invalid(
            "stadium_track needs straight >= 0, radius > 0 and 0 < width < 2 radius",
        ));
    }
    let (walls, centre) = arena_core::sim::shapes::stadium_track(straight, radius, width);
    let arr = |pts: &[[f64; 2]]| {
        PyArray2::from_vec2(py, &pts.iter().map(|p| p.to_vec()).collect::<Vec<_>>())
            .map_err(|e| invalid(e.to_string()))
    };
    Ok((
        walls.iter().map(|w| arr(w)).collect::<PyResult<_>>()?,
        arr(&centre)?,
    ))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Simulator>()?;
    m.add_function(wrap_pyfunction!(stadium_track, m)?)?;
    m.add("STATE_FIELDS", PyTuple::new(m.py(), STATE_FIELDS)?)?;
    Ok(())
}
