//! See the crate docs; filled in by the track work.
