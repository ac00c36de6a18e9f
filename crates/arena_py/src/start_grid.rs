//! Bindings for `arena_core::sim::start_grid` and the start spec of `arena_core::sim::starts`:
//! `StartGrid` (a track's grid start, wall clearance and free run) and `StartSpec` (how
//! `Simulator.reset_drawn` places the cars), both typed objects. Inputs are converted
//! here; the core checks them and computes everything.

use arena_core::sim::{StartGrid as CoreGrid, StartSpec as CoreSpec};
use arena_core::ArenaError as CoreError;
use numpy::{PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::boundary;
use crate::convert::points_from_py;
use crate::errors::to_py;

fn finite(name: &str, v: f64) -> PyResult<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(to_py(CoreError::invalid(format!(
            "{name} must be finite, got {v}"
        ))))
    }
}

/// The start geometry of one track: its wall edges, its centreline (or an open map's
/// start anchor), and whether s = 0 is the source's start line. Grid starts are cached
/// per (slots, spacing) in the object.
#[pyclass(module = "roboracer_arena._core", name = "StartGrid", frozen)]
pub struct StartGrid {
    inner: CoreGrid,
}

#[pymethods]
impl StartGrid {
    #[new]
    #[pyo3(signature = (walls, centreline, *, open_map = false, source_start = false))]
    fn new(
        py: Python<'_>,
        walls: Vec<PyReadonlyArray2<'_, f64>>,
        centreline: PyReadonlyArray2<'_, f64>,
        open_map: bool,
        source_start: bool,
    ) -> PyResult<Self> {
        let walls = walls
            .iter()
            .enumerate()
            .map(|(i, w)| points_from_py(w, &format!("walls[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        let line = points_from_py(&centreline, "centreline")?;
        let inner = boundary::call(py, "StartGrid", move || {
            CoreGrid::new(&walls, &line, open_map, source_start)
        })?;
        Ok(StartGrid { inner })
    }

    /// Lap length (m); 0 for an open map.
    #[getter]
    fn length(&self) -> f64 {
        self.inner.length()
    }

    /// Laid along an open map's start anchor (the constructor's ``open_map``).
    #[getter]
    fn open_map(&self) -> bool {
        self.inner.is_open()
    }

    /// s = 0 is the source's own start line (the constructor's ``source_start``).
    #[getter]
    fn source_start(&self) -> bool {
        self.inner.source_start()
    }

    /// (x, y, heading) on the centreline at arc length ``s`` (wrapped at the lap); on an
    /// open map, ``s`` m along the start heading.
    fn pose_at(&self, s: f64) -> PyResult<(f64, f64, f64)> {
        let [x, y, h] = self.inner.pose_at(finite("s", s)?);
        Ok((x, y, h))
    }

    /// Distance (m) from (x, y) along ``heading`` to the first wall (inf if none).
    fn free_run_ahead(&self, x: f64, y: f64, heading: f64) -> PyResult<f64> {
        let (x, y, h) = (
            finite("x", x)?,
            finite("y", y)?,
            finite("heading", heading)?,
        );
        Ok(self.inner.free_run_ahead(x, y, h))
    }

    /// Distance (m) from each of ``points`` (N, 2) to the nearest wall, (N,).
    fn clearance<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let pts = points_from_py(&points, "points")?;
        let grid = &self.inner;
        let out = boundary::call_ok(py, "StartGrid.clearance", move || {
            pts.iter().map(|&p| grid.clearance(p)).collect::<Vec<f64>>()
        })?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// Arc length (m) of the first slot of a grid of ``slots`` cars ``spacing`` m apart.
    fn grid_start_s(&self, py: Python<'_>, slots: usize, spacing: f64) -> PyResult<f64> {
        let grid = &self.inner;
        boundary::call(py, "StartGrid.grid_start_s", move || {
            grid.grid_start_s(slots, spacing)
        })
    }

    /// Poses (slots, 3) of the staggered grid whose first slot is at ``s0`` (default:
    /// ``grid_start_s(slots, spacing)``).
    #[pyo3(signature = (slots, spacing, offset, s0 = None))]
    fn grid_poses<'py>(
        &self,
        py: Python<'py>,
        slots: usize,
        spacing: f64,
        offset: f64,
        s0: Option<f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let grid = &self.inner;
        let poses = boundary::call(py, "StartGrid.grid_poses", move || {
            grid.grid_poses(slots, spacing, offset, s0)
        })?;
        let flat: Vec<f64> = poses.into_iter().flatten().collect();
        let arr = numpy::ndarray::Array2::from_shape_vec((flat.len() / 3, 3), flat)
            .expect("three values per pose");
        Ok(PyArray2::from_owned_array(py, arr))
    }
}

/// How ``Simulator.reset_drawn`` places the cars: built from keyword arguments, the
/// ranges checked by the core (``InvalidArgumentError``); read-only attributes.
#[pyclass(module = "roboracer_arena._core", name = "StartSpec", frozen, eq)]
#[derive(PartialEq)]
pub struct StartSpec {
    pub(crate) inner: CoreSpec,
}

#[pymethods]
impl StartSpec {
    #[new]
    #[pyo3(signature = (*, random_s, s0, grid_spacing, grid_offset, lateral_noise, heading_noise,
        side_clearance, speed_noise, noise_std, dropout, track_weights = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        random_s: bool,
        s0: Vec<f64>,
        grid_spacing: f64,
        grid_offset: f64,
        lateral_noise: f64,
        heading_noise: f64,
        side_clearance: f64,
        speed_noise: f64,
        noise_std: (f64, f64),
        dropout: f64,
        track_weights: Option<Vec<f64>>,
    ) -> PyResult<Self> {
        let inner = CoreSpec {
            random_s,
            s0,
            track_weights: track_weights.unwrap_or_default(),
            grid_spacing,
            grid_offset,
            lateral_noise,
            heading_noise,
            side_clearance,
            speed_noise,
            noise_std: [noise_std.0, noise_std.1],
            dropout,
        };
        let inner = boundary::call(py, "StartSpec", move || inner.check().map(|()| inner))?;
        Ok(StartSpec { inner })
    }

    /// First grid slot at a uniformly random arc length (else at ``s0[track]``).
    #[getter]
    fn random_s(&self) -> bool {
        self.inner.random_s
    }
    /// Arc length (m) of the first grid slot, per track.
    #[getter]
    fn s0(&self) -> Vec<f64> {
        self.inner.s0.clone()
    }
    /// Track draw weights, per track (empty: uniform).
    #[getter]
    fn track_weights(&self) -> Vec<f64> {
        self.inner.track_weights.clone()
    }
    #[getter]
    fn grid_spacing(&self) -> f64 {
        self.inner.grid_spacing
    }
    #[getter]
    fn grid_offset(&self) -> f64 {
        self.inner.grid_offset
    }
    #[getter]
    fn lateral_noise(&self) -> f64 {
        self.inner.lateral_noise
    }
    #[getter]
    fn heading_noise(&self) -> f64 {
        self.inner.heading_noise
    }
    #[getter]
    fn side_clearance(&self) -> f64 {
        self.inner.side_clearance
    }
    #[getter]
    fn speed_noise(&self) -> f64 {
        self.inner.speed_noise
    }
    #[getter]
    fn noise_std(&self) -> (f64, f64) {
        (self.inner.noise_std[0], self.inner.noise_std[1])
    }
    #[getter]
    fn dropout(&self) -> f64 {
        self.inner.dropout
    }

    fn __repr__(&self) -> String {
        format!("StartSpec({:?})", self.inner)
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<StartGrid>()?;
    m.add_class::<StartSpec>()?;
    Ok(())
}
