//! Pure-Rust core of RoboRacer Arena (no Python here; see `arena_py` for bindings).
//!
//! * [`grid`]: ROS occupancy maps (I/O, flood fill, distance transform, contours, rasterise)
//! * [`geometry`]: polylines, smoothing, simplification, meshes
//! * [`track`]: corridor isolation, centreline, metrics, validation
//! * [`generate`]: requirement screening and the lattice constructor
//! * [`sim`]: vehicles, worlds, lidar and batched stepping
//! * [`limits`]: pixel budget and plausible ranges checked before allocating

pub mod error;
pub mod fileio;
pub mod generate;
pub mod geometry;
pub mod grid;
pub mod limits;
pub mod sim;
pub mod track;

pub use error::{ArenaError, Result};
