//! See the crate docs; filled in by the track work.
pub mod features;
pub mod metrics;
pub mod validate;
