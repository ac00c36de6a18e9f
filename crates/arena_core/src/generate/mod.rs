//! Requirements → track: the spec as the core sees it, the admissibility screen
//! (Eqs. 1–2), the lattice constructor (growth, rounding) and the bounded generate loop
//! (Algorithm 1).

pub mod budget;
pub mod construct;
pub mod lattice;
pub mod nearest;
pub mod polygon;
pub mod ring;
pub mod rounding;
pub mod screen;
pub mod side_notch;
pub mod spec;
pub mod teardrop;
