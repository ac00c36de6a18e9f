//! Bindings for `arena_core::grid`: ROS map YAML + PGM/PNG reading and writing
//! (`grid::mapfile`), the distance transform and the rasteriser (Eq. 3, `grid::rasterise`);
//! GIL released for heavy work.

use crate::boundary;
use crate::convert::{grid_to_py, points_from_py, MapTuple};
use crate::domain::Wrap;
use crate::mirror::FromCore;
use crate::reports::MapMeta;
use arena_core::grid::mapfile::{self, ImageFormat};
use arena_core::grid::OccupancyGrid;
use numpy::{PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

/// A map from Python: `data` (H, W) uint8 (254 free, 0 occupied, 205 unknown, row 0 =
/// top image row), resolution (m/cell) and origin (x, y, yaw). Size, resolution and
/// origin are checked by the core (`limits::check_grid_header`) before the copy.
pub(crate) fn grid_from_py(
    py: Python<'_>,
    data: &PyReadonlyArray2<'_, u8>,
    resolution: f64,
    origin: (f64, f64, f64),
) -> PyResult<OccupancyGrid> {
    let (h, w) = (data.shape()[0], data.shape()[1]);
    let o = [origin.0, origin.1, origin.2];
    boundary::call(py, "map", || {
        arena_core::limits::check_grid_header(w, h, resolution, o)
    })?;
    // A C-contiguous array is one memcpy; anything else (Fortran order, strided views)
    // goes element by element in logical order (`as_slice` accepts Fortran order too).
    let cells: Vec<u8> = match data.as_slice() {
        Ok(s) if data.is_c_contiguous() => s.to_vec(),
        _ => data.as_array().iter().copied().collect(),
    };
    Ok(OccupancyGrid {
        width: w,
        height: h,
        resolution,
        origin: o,
        data: cells,
    })
}

/// `(data, resolution, origin, meta)` as returned to Python.
type LoadedMap<'py> = (Bound<'py, PyArray2<u8>>, f64, (f64, f64, f64), MapMeta);

/// Load a ROS map YAML and its image (nav2 rules for mode, negate and thresholds).
/// Returns ``(data uint8 (H, W), resolution, origin (x, y, yaw), meta)``, meta a
/// [`MapMeta`].
#[pyfunction]
fn load_map<'py>(py: Python<'py>, path: std::path::PathBuf) -> PyResult<LoadedMap<'py>> {
    let (g, meta) = boundary::call(py, "load_map", move || mapfile::load_map(&path))?;
    let res = g.resolution;
    let (data, origin) = grid_to_py(py, g);
    Ok((data, res, origin, MapMeta::from_core(py, meta)?))
}

/// Write a trinary map: ``STEM.png|pgm`` beside ``yaml_path``, then the YAML (atomically).
/// Returns the image path.
#[pyfunction]
#[pyo3(
    signature = (data, resolution, origin, yaml_path, image_format=Wrap(ImageFormat::Png)),
    text_signature = "(data, resolution, origin, yaml_path, image_format='png')"
)]
fn save_map(
    py: Python<'_>,
    data: PyReadonlyArray2<'_, u8>,
    resolution: f64,
    origin: (f64, f64, f64),
    yaml_path: std::path::PathBuf,
    image_format: Wrap<ImageFormat>,
) -> PyResult<String> {
    let g = grid_from_py(py, &data, resolution, origin)?;
    let img = boundary::call(py, "save_map", move || {
        mapfile::save_map(&g, &yaml_path, image_format.0)
    })?;
    Ok(img.display().to_string())
}

/// Exact Euclidean distance (in cells) from every cell to the nearest True cell.
#[pyfunction]
fn distance_transform<'py>(
    py: Python<'py>,
    feature: PyReadonlyArray2<'py, bool>,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let (h, w) = (feature.shape()[0], feature.shape()[1]);
    crate::boundary::call(py, "distance_transform", || {
        arena_core::limits::check_cells(w, h, "distance_transform feature array")
    })?;
    let mask: Vec<bool> = feature.as_array().iter().copied().collect();
    let d = crate::boundary::call_ok(py, "distance_transform", move || {
        arena_core::grid::edt::edt(&mask, w, h)
    })?;
    let arr = numpy::ndarray::Array2::from_shape_vec((h, w), d).expect("shape matches");
    Ok(PyArray2::from_owned_array(py, arr))
}

/// Rasterise a closed centreline with per-vertex full corridor widths (Eq. 3).
/// Returns ``(data uint8 (H, W), origin (x, y, yaw))``, row 0 = top image row.
#[pyfunction]
#[pyo3(signature = (xy, widths, resolution=0.05, wall_thickness=0.15, margin=0.5))]
fn rasterise_centreline<'py>(
    py: Python<'py>,
    xy: PyReadonlyArray2<'py, f64>,
    widths: PyReadonlyArray1<'py, f64>,
    resolution: f64,
    wall_thickness: f64,
    margin: f64,
) -> PyResult<MapTuple<'py>> {
    let pts = points_from_py(&xy, "xy")?;
    let w: Vec<f64> = widths.as_array().iter().copied().collect();
    let g = boundary::call(py, "rasterise_centreline", move || {
        arena_core::grid::rasterise::rasterise_centreline(
            &pts,
            &w,
            resolution,
            wall_thickness,
            margin,
        )
    })?;
    Ok(grid_to_py(py, g))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(load_map, m)?)?;
    m.add_function(wrap_pyfunction!(save_map, m)?)?;
    m.add_function(wrap_pyfunction!(distance_transform, m)?)?;
    m.add_function(wrap_pyfunction!(rasterise_centreline, m)?)?;
    Ok(())
}
