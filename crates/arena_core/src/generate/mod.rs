//! Requirements → track: the spec as the core sees it, the admissibility screen
//! (Eqs. 1–2), the lattice constructor (growth, rounding) and the bounded generate loop
//! (Algorithm 1).

pub mod construct;
pub mod deadline;
pub mod lattice;
pub mod nearest;
pub mod polygon;
pub mod raster_budget;
pub mod ring;
pub mod rounding;
pub mod screen;
pub mod side_notch;
pub mod spec;
pub mod teardrop;
