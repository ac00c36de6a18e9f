//! See the crate docs; filled in by the track work.
pub mod build;
pub mod centreline;
pub mod corridor;
pub mod features;
pub mod metrics;
pub mod open;
pub mod params;
pub mod validate;
