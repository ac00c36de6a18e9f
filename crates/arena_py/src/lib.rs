//! `roboracer_arena._core`: thin pyo3 bindings over `arena_core`, one file per core
//! module. No logic lives here: extract inputs, call the core through `boundary::call` (GIL released, panics
//! caught, errors typed).

use pyo3::prelude::*;

mod boundary;
mod config;
mod convert;
mod domain;
mod episode;
mod errors;
mod generate;
mod geometry;
mod grid;
mod mirror;
mod nearest;
mod observation;
mod outcome;
mod progress;
mod reports;
mod sim;
mod start_grid;
mod track;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    boundary::install_panic_hook();
    errors::register(m)?;
    boundary::register(m)?;
    grid::register(m)?;
    generate::register(m)?;
    reports::register(m)?;
    geometry::register(m)?;
    track::register(m)?;
    config::register(m)?;
    sim::register(m)?;
    progress::register(m)?;
    episode::register(m)?;
    observation::register(m)?;
    start_grid::register(m)?;
    Ok(())
}
