//! See the crate docs; filled in by the sim work.
