//! Bindings for `arena_core::track`: the build (occupancy map → walls, ducts, centreline,
//! meshes and the round-trip check, one call), the raster measurements the track library
//! uses (`track::metrics`), the raster validator (`track::validate`) and the curve
//! analysis (`track::features`); GIL released for the heavy work.

use crate::boundary;
use crate::convert::{from_py, line_to_py, points_from_py, to_dict};
use crate::generate::parse;
use crate::mirror::FromCore;
use crate::reports::{CurveAnalysis, ValidationReport};
use arena_core::geometry::mesh::TriMesh;
use arena_core::track::build;
use arena_core::track::metrics;
use arena_core::track::open;
use arena_core::track::params::{self, BuildParams};
use arena_core::track::{features, validate};
use arena_core::ArenaError;
use numpy::{PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

fn mesh_to_py<'py>(
    py: Python<'py>,
    m: TriMesh,
) -> (Bound<'py, PyArray2<f32>>, Bound<'py, PyArray2<u32>>) {
    let (nv, nt) = (m.vertices.len(), m.triangles.len());
    let v =
        numpy::ndarray::Array2::from_shape_vec((nv, 3), m.vertices.into_iter().flatten().collect())
            .expect("shape");
    let t = numpy::ndarray::Array2::from_shape_vec(
        (nt, 3),
        m.triangles.into_iter().flatten().collect(),
    )
    .expect("shape");
    (
        PyArray2::from_owned_array(py, v),
        PyArray2::from_owned_array(py, t),
    )
}

/// The geometry of one built map (``build_geometry`` / ``build_open_geometry``;
/// ``roboracer_arena.corridor.CorridorGeometry`` is its public view): read-only.
#[pyclass(module = "roboracer_arena._core", frozen, get_all)]
pub struct Geometry {
    /// Closed wall polylines (N, 2), map metres.
    walls: Py<PyList>,
    /// Air-duct centre polylines (N, 2).
    ducts: Py<PyList>,
    /// The closed centreline (N, 2); empty for an open map.
    centreline: Py<PyArray2<f64>>,
    /// name ("floor", "walls", "ducts", "rings") -> (vertices (V, 3) float32, triangles (T, 3) uint32).
    meshes: Py<PyDict>,
    /// Duct texture coordinates: (st (U, 2) float32, one index per triangle corner uint32).
    duct_st: Py<PyTuple>,
    /// Raster round-trip intersection over union.
    iou: f64,
    /// Largest wall deviation of the round trip (cells).
    max_wall_deviation_cells: f64,
    /// The corridor's free cells (H, W) bool.
    corridor_mask: Py<PyArray2<bool>>,
    /// Corridor cells touching the map border.
    border_contact_cells: usize,
    /// Seconds per build stage.
    timings: Py<PyDict>,
    /// The build parameters used (`GeometryConfig` fields).
    params: Py<PyDict>,
    /// An open map's start pose (x, y, yaw): the given start, else the free cell farthest
    /// from the walls; None for a track.
    start_pose: Option<(f64, f64, f64)>,
    /// Clearance (m) of that default start (NaN for a given start); None for a track.
    start_clearance_m: Option<f64>,
}

/// Build parameters from Python (a mapping of `GeometryConfig` fields or the model; None =
/// defaults); the core's range check runs in the caller's boundary call.
fn build_params(py: Python<'_>, params: Option<&Bound<'_, PyAny>>) -> PyResult<BuildParams> {
    from_py(py, params, "build params", ArenaError::config)
}

/// Build the environment geometry of a map (walls, ducts, centreline, meshes and the
/// raster round-trip check).
#[pyfunction]
#[pyo3(signature = (data, resolution, origin, params=None, start=None))]
fn build_geometry<'py>(
    py: Python<'py>,
    data: PyReadonlyArray2<'py, u8>,
    resolution: f64,
    origin: (f64, f64, f64),
    params: Option<&Bound<'py, PyAny>>,
    start: Option<Vec<f64>>,
) -> PyResult<Geometry> {
    let params = build_params(py, params)?;
    let g = crate::grid::grid_from_py(py, &data, resolution, origin)?;
    let (w, h) = (g.width, g.height);
    let geo = boundary::call(py, "build_geometry", move || {
        let start = start.as_deref().map(params::start_point).transpose()?;
        params.validate()?;
        build::build_geometry(&g, &params, start.map(|[x, y, _]| [x, y]))
    })?;
    geometry_to_py(py, geo, w, h, None)
}

/// Build an open map's geometry (a floor plan: every free cell drivable, every other
/// cell a wall, no centreline), with ``start_pose`` (``start`` (x, y[, yaw]) checked to lie
/// on a drivable cell, else the free cell farthest from the walls) and
/// ``start_clearance_m`` (NaN for a given start).
#[pyfunction]
#[pyo3(signature = (data, resolution, origin, params=None, unknown_free=false, start=None))]
fn build_open_geometry<'py>(
    py: Python<'py>,
    data: PyReadonlyArray2<'py, u8>,
    resolution: f64,
    origin: (f64, f64, f64),
    params: Option<&Bound<'py, PyAny>>,
    unknown_free: bool,
    start: Option<Vec<f64>>,
) -> PyResult<Geometry> {
    let params = build_params(py, params)?;
    let g = crate::grid::grid_from_py(py, &data, resolution, origin)?;
    let (w, h) = (g.width, g.height);
    let o = boundary::call(py, "build_open_geometry", move || {
        let start = start.as_deref().map(params::start_point).transpose()?;
        params.validate()?;
        open::build_open_geometry(&g, &params, open::OpenOptions { unknown_free }, start)
    })?;
    let s = o.start;
    geometry_to_py(
        py,
        o.geometry,
        w,
        h,
        Some(((s[0], s[1], s[2]), o.start_clearance_m)),
    )
}

fn geometry_to_py(
    py: Python<'_>,
    geo: build::Geometry,
    w: usize,
    h: usize,
    start: Option<((f64, f64, f64), f64)>,
) -> PyResult<Geometry> {
    let lines = |ls: &[Vec<[f64; 2]>]| PyList::new(py, ls.iter().map(|l| line_to_py(py, l)));
    let meshes = PyDict::new(py);
    meshes.set_item("floor", mesh_to_py(py, geo.floor))?;
    meshes.set_item("walls", mesh_to_py(py, geo.wall_mesh))?;
    meshes.set_item("ducts", mesh_to_py(py, geo.duct_mesh))?;
    meshes.set_item("rings", mesh_to_py(py, geo.ring_mesh))?;
    let (st, st_idx) = geo.duct_st;
    let st =
        numpy::ndarray::Array2::from_shape_vec((st.len(), 2), st.into_iter().flatten().collect())
            .expect("shape");
    let duct_st = PyTuple::new(
        py,
        [
            PyArray2::from_owned_array(py, st).into_any(),
            numpy::PyArray1::from_vec(py, st_idx).into_any(),
        ],
    )?;
    let mask = numpy::ndarray::Array2::from_shape_vec((h, w), geo.corridor.mask).expect("shape");
    let timings = PyDict::new(py);
    for (k, v) in &geo.timings {
        timings.set_item(*k, *v)?;
    }
    Ok(Geometry {
        walls: lines(&geo.walls)?.unbind(),
        ducts: lines(&geo.ducts)?.unbind(),
        centreline: line_to_py(py, &geo.centreline).unbind(),
        meshes: meshes.unbind(),
        duct_st: duct_st.unbind(),
        iou: geo.iou,
        max_wall_deviation_cells: geo.max_wall_deviation_cells,
        corridor_mask: PyArray2::from_owned_array(py, mask).unbind(),
        border_contact_cells: geo.corridor.border_contact,
        timings: timings.unbind(),
        params: to_dict(py, &geo.params)?.unbind(),
        start_pose: start.map(|(p, _)| p),
        start_clearance_m: start.map(|(_, c)| c),
    })
}

/// What `measure_map` found on a trinary grid, as the validator measures it: plain
/// numbers and arrays (read-only attributes).
#[pyclass(module = "roboracer_arena._core", frozen, get_all)]
pub struct RasterMeasurement {
    /// Free components holding at least 0.5 % of the largest one's cells.
    corridor_components: usize,
    /// Enclosed regions inside the corridor (1 for a plain ring).
    infields: usize,
    /// Mean free width of the corridor (m).
    mean_width_m: f64,
    /// Extent (x, y) of the known (walls and free) cells (m).
    extent_m: (f64, f64),
    /// Length of the closed medial centreline (m).
    centreline_length_m: f64,
    /// The closed medial centreline, counter-clockwise, map metres (N, 2).
    centreline: Py<PyArray2<f64>>,
    /// Local free width at each centreline vertex (N,).
    widths: Py<PyArray1<f64>>,
}

/// Measure a trinary grid (254 free / 0 occupied / 205 unknown) as the validator does.
/// Raises ``CorridorError`` when the grid has no closed corridor.
#[pyfunction]
fn measure_map<'py>(
    py: Python<'py>,
    data: PyReadonlyArray2<'py, u8>,
    resolution: f64,
    origin: (f64, f64, f64),
) -> PyResult<RasterMeasurement> {
    let grid = crate::grid::grid_from_py(py, &data, resolution, origin)?;
    let t = boundary::call(py, "measure_map", move || metrics::measure_raster(&grid))?;
    Ok(RasterMeasurement {
        corridor_components: t.corridor_components,
        infields: t.infields,
        mean_width_m: t.mean_width_m,
        extent_m: (t.extent_m[0], t.extent_m[1]),
        centreline_length_m: t.centreline_length_m,
        centreline: line_to_py(py, &t.centreline).unbind(),
        widths: PyArray1::from_vec(py, t.widths).unbind(),
    })
}

/// Validate an occupancy grid against a spec, measuring the raster only. Returns
/// ``(report (a [`ValidationReport`]), measured centreline (N, 2) in the driving direction)``.
#[pyfunction]
#[pyo3(signature = (data, resolution, origin, spec, config=None))]
fn validate_map<'py>(
    py: Python<'py>,
    data: PyReadonlyArray2<'py, u8>,
    resolution: f64,
    origin: (f64, f64, f64),
    spec: &Bound<'py, PyAny>,
    config: Option<&Bound<'py, PyAny>>,
) -> PyResult<(ValidationReport, Bound<'py, PyArray2<f64>>)> {
    let (spec, cfg) = parse(py, spec, config)?;
    boundary::call(py, "validate_map", || {
        validate::check_frame(resolution, [origin.0, origin.1, origin.2])
    })?;
    let grid = crate::grid::grid_from_py(py, &data, resolution, origin)?;
    let report = boundary::call_ok(py, "validate_map", move || {
        validate::validate_map(&grid, &spec, &cfg)
    })?;
    let line = line_to_py(py, &report.centreline);
    Ok((ValidationReport::from_core(py, report)?, line))
}

/// Curvature analysis of a closed curve (driving direction): turns, features, minimum
/// radius, longest straight, total turn; plus its self-clearance outside `exclude_m`: a
/// [`CurveAnalysis`].
#[pyfunction]
#[pyo3(signature = (xy, corner_radius, exclude_m))]
fn analyse_curve(
    py: Python<'_>,
    xy: PyReadonlyArray2<'_, f64>,
    corner_radius: f64,
    exclude_m: f64,
) -> PyResult<CurveAnalysis> {
    let pts = points_from_py(&xy, "xy")?;
    let out = boundary::call(py, "analyse_curve", move || {
        features::analyse_curve(&pts, corner_radius, exclude_m)
    })?;
    CurveAnalysis::from_core(py, out)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(build_geometry, m)?)?;
    m.add_function(wrap_pyfunction!(build_open_geometry, m)?)?;
    m.add_function(wrap_pyfunction!(measure_map, m)?)?;
    m.add_function(wrap_pyfunction!(validate_map, m)?)?;
    m.add_function(wrap_pyfunction!(analyse_curve, m)?)?;
    m.add_class::<RasterMeasurement>()?;
    m.add_class::<Geometry>()?;
    Ok(())
}
