//! See the crate docs; filled in by the geometry work.
