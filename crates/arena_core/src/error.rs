//! The one error type of the core. Every variant maps to a Python exception class in
//! `roboracer_arena.errors` (see `arena_py/src/errors.rs`), so keep variants coarse and
//! messages self-contained: they are shown to users verbatim.

use std::path::Path;

/// Result alias used across the core.
pub type Result<T, E = ArenaError> = std::result::Result<T, E>;

#[derive(Debug, thiserror::Error)]
pub enum ArenaError {
    /// A file could not be read or written.
    #[error("{path}: {message}")]
    Io { path: String, message: String },
    /// A map file (YAML or image) is malformed or inconsistent.
    #[error("{path}: {message}")]
    MapFormat { path: String, message: String },
    /// The map loaded but holds no usable closed corridor (leaks, empty, ...).
    #[error("{0}")]
    Corridor(String),
    /// A caller passed an argument outside its documented domain.
    #[error("{0}")]
    InvalidArgument(String),
    /// A configuration (simulator, build geometry, constructor) is outside its schema;
    /// the pydantic models refuse the same values with the same class (`ConfigError`).
    #[error("{0}")]
    Config(String),
    /// A requirement specification is malformed (not: infeasible; that is a result).
    #[error("{0}")]
    Spec(String),
    /// The simulator was driven into a state it refuses (bad track, bad config).
    #[error("{0}")]
    Simulation(String),
}

impl ArenaError {
    pub fn io(path: impl AsRef<Path>, err: impl std::fmt::Display) -> Self {
        ArenaError::Io {
            path: path.as_ref().display().to_string(),
            message: err.to_string(),
        }
    }
    pub fn map_format(path: impl AsRef<Path>, message: impl Into<String>) -> Self {
        ArenaError::MapFormat {
            path: path.as_ref().display().to_string(),
            message: message.into(),
        }
    }
    pub fn config(message: impl Into<String>) -> Self {
        ArenaError::Config(message.into())
    }
    pub fn invalid(message: impl Into<String>) -> Self {
        ArenaError::InvalidArgument(message.into())
    }
}
