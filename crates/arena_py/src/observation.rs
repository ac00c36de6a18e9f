//! Bindings for `arena_core::sim::observation`: `ObservationNormaliser`, which writes
//! normalised odometry and scans straight into an env's float32 observation buffers
//! (shapes checked here; the arithmetic is the core's).

use arena_core::sim::{
    Frames, ObservationNormaliser as CoreNormaliser, ObservationScales, OdometryField, STATE_SIZE,
};
use numpy::{
    PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyReadwriteArrayDyn, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::boundary;
use crate::domain::Wrap;
use crate::errors::to_py;
use crate::sim::{check_shape, invalid, read_mask};

impl<'a, 'py> FromPyObject<'a, 'py> for Wrap<OdometryField> {
    type Error = PyErr;

    /// A state field's name (the core's `OdometryField::parse` owns the names).
    fn extract(obj: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        match obj.extract::<String>() {
            Ok(name) => OdometryField::parse(&name).map(Wrap).map_err(to_py),
            Err(_) => Err(invalid(format!(
                "an odometry field must be a str, got {}",
                obj.repr().map(|r| r.to_string()).unwrap_or_default()
            ))),
        }
    }
}

/// Borrow `obj` as a C-contiguous numpy array of T for reading.
fn read_c<'py, T: numpy::Element>(
    obj: &Bound<'py, PyAny>,
    name: &str,
    dtype: &str,
) -> PyResult<PyReadonlyArrayDyn<'py, T>> {
    let a = obj
        .cast::<PyArrayDyn<T>>()
        .map_err(|_| invalid(format!("{name} must be a numpy {dtype} array")))?;
    let ro = a
        .try_readonly()
        .map_err(|e| invalid(format!("{name} cannot be read: {e}")))?;
    if !ro.is_c_contiguous() {
        return Err(invalid(format!("{name} must be C-contiguous")));
    }
    Ok(ro)
}

/// Borrow `out` for writing: a C-contiguous float32 array of shape (E, V, width) or
/// (E, V, frames, width); returns it with its number of frames.
fn frames_out<'py>(
    out: &Bound<'py, PyAny>,
    envs: usize,
    vehicles: usize,
    width: usize,
) -> PyResult<(PyReadwriteArrayDyn<'py, f32>, usize)> {
    let a = out
        .cast::<PyArrayDyn<f32>>()
        .map_err(|_| invalid("out must be a numpy float32 array"))?;
    let shape = a.shape();
    let frames = match shape.len() {
        4 => shape[2],
        _ => 1,
    };
    let want: &[usize] = if shape.len() == 4 {
        &[envs, vehicles, frames, width]
    } else {
        &[envs, vehicles, width]
    };
    check_shape("out", shape, want)?;
    let rw = a
        .try_readwrite()
        .map_err(|e| invalid(format!("out cannot be written: {e}")))?;
    if !rw.is_c_contiguous() {
        return Err(invalid("out must be C-contiguous"));
    }
    Ok((rw, frames))
}

fn optional_mask(mask: Option<&Bound<'_, PyAny>>, envs: usize) -> PyResult<Option<Vec<bool>>> {
    match mask {
        Some(m) if !m.is_none() => Ok(Some(read_mask(m, envs)?)),
        _ => Ok(None),
    }
}

/// The normalised odometry columns and scan of an observation config.
#[pyclass(
    module = "roboracer_arena._core",
    name = "ObservationNormaliser",
    frozen
)]
pub struct ObservationNormaliser {
    inner: CoreNormaliser,
}

#[pymethods]
impl ObservationNormaliser {
    #[new]
    #[pyo3(signature = (odometry, *, position_scale, horizon, range_max, max_speed, max_steer))]
    fn new(
        py: Python<'_>,
        odometry: Vec<Wrap<OdometryField>>,
        position_scale: f64,
        horizon: f64,
        range_max: f64,
        max_speed: f64,
        max_steer: f64,
    ) -> PyResult<Self> {
        let fields = odometry.into_iter().map(|w| w.0).collect();
        let scales = ObservationScales {
            position_scale,
            horizon,
            range_max,
            max_speed,
            max_steer,
        };
        let inner = boundary::call(py, "ObservationNormaliser", move || {
            CoreNormaliser::new(fields, scales)
        })?;
        Ok(ObservationNormaliser { inner })
    }

    /// Names of the output columns (yaw gives yaw_sin, yaw_cos).
    #[getter]
    fn columns<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, self.inner.columns().iter().map(|c| c.name))
    }

    /// What each output column is divided by (1 for yaw_sin, yaw_cos).
    #[getter]
    fn column_scales<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, self.inner.columns().iter().map(|c| c.scale))
    }

    /// Where each output column is clipped (±bound; inf for x, y).
    #[getter]
    fn column_bounds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, self.inner.columns().iter().map(|c| c.bound))
    }

    /// The scan's factor, 1 / min(horizon, range_max) as float32.
    #[getter]
    fn scan_scale(&self) -> f32 {
        self.inner.scan_scale()
    }

    /// Write the normalised odometry of `state` ((E, V, S) float64) and `start_poses`
    /// ((E, V, 3) float64) into the newest frame of `out` ((E, V, K) or (E, V, k, K)
    /// float32), of every env or only of those where `env_mask` is True.
    #[pyo3(signature = (state, start_poses, out, env_mask = None))]
    fn odometry(
        &self,
        py: Python<'_>,
        state: &Bound<'_, PyAny>,
        start_poses: &Bound<'_, PyAny>,
        out: &Bound<'_, PyAny>,
        env_mask: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let st = read_c::<f64>(state, "state", "float64")?;
        let (envs, vehicles) = match st.shape() {
            [e, v, STATE_SIZE] => (*e, *v),
            got => {
                return Err(invalid(format!(
                    "state must have shape (E, V, {STATE_SIZE}), got {got:?}"
                )))
            }
        };
        let sp = read_c::<f64>(start_poses, "start_poses", "float64")?;
        check_shape("start_poses", sp.shape(), &[envs, vehicles, 3])?;
        let width = self.inner.columns().len();
        let (mut o, frames) = frames_out(out, envs, vehicles, width)?;
        let mask = optional_mask(env_mask, envs)?;
        let (st, sp) = (contiguous(&st)?, contiguous(&sp)?);
        let o = o.as_slice_mut().map_err(|e| invalid(e.to_string()))?;
        let inner = &self.inner;
        boundary::call(py, "ObservationNormaliser.odometry", move || {
            let layout = Frames {
                envs,
                vehicles,
                frames,
                env_mask: mask.as_deref(),
            };
            inner.write_odometry(st, sp, o, layout)
        })
    }

    /// Write the normalised `scans` ((E, V, B) float32, metres) into the newest frame of
    /// `out` ((E, V, B) or (E, V, k, B) float32), of every env or only of those where
    /// `env_mask` is True.
    #[pyo3(signature = (scans, out, env_mask = None))]
    fn scan(
        &self,
        py: Python<'_>,
        scans: &Bound<'_, PyAny>,
        out: &Bound<'_, PyAny>,
        env_mask: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let sc = read_c::<f32>(scans, "scans", "float32")?;
        let (envs, vehicles, beams) = match sc.shape() {
            [e, v, b] => (*e, *v, *b),
            got => {
                return Err(invalid(format!(
                    "scans must have shape (E, V, B), got {got:?}"
                )))
            }
        };
        let (mut o, frames) = frames_out(out, envs, vehicles, beams)?;
        let mask = optional_mask(env_mask, envs)?;
        let sc = contiguous(&sc)?;
        let o = o.as_slice_mut().map_err(|e| invalid(e.to_string()))?;
        let inner = &self.inner;
        boundary::call(py, "ObservationNormaliser.scan", move || {
            let layout = Frames {
                envs,
                vehicles,
                frames,
                env_mask: mask.as_deref(),
            };
            inner.write_scans(sc, beams, o, layout)
        })
    }

    fn __repr__(&self) -> String {
        let names: Vec<&str> = self.inner.fields().iter().map(|f| f.name()).collect();
        format!("ObservationNormaliser(odometry={names:?})")
    }
}

fn contiguous<'a, T: numpy::Element>(a: &'a PyReadonlyArrayDyn<'_, T>) -> PyResult<&'a [T]> {
    a.as_slice().map_err(|e| invalid(e.to_string()))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<ObservationNormaliser>()?;
    Ok(())
}
