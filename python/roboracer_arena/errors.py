"""Typed exceptions. Every error the package raises on purpose derives from
:class:`ArenaError`; the CLI maps them to exit codes and one-line messages.

The classes raised by the Rust core are defined there and re-exported here, so
``except roboracer_arena.errors.MapFormatError`` catches them wherever they come from.

The bad-value errors (:class:`MapFormatError`, :class:`InvalidArgumentError`,
:class:`ConfigError`, :class:`SpecError`) are also ``ValueError``s, as pydantic's
``ValidationError`` is, so ``except ValueError`` catches a wrong action shape or a bad
config wherever the check runs.
"""

from __future__ import annotations

from ._core import (
    ArenaError,
    ConfigError,
    CorridorError,
    InternalError,
    InvalidArgumentError,
    MapFormatError,
    MapIOError,
    SimulationError,
    SpecError,
)


class RequestParseError(ArenaError):
    """A natural-language request could not be turned into a TrackSpec."""


class BackendError(ArenaError):
    """A parser backend (e.g. an Ollama server) failed: down, missing model, timeout."""


class BackendUnavailableError(BackendError):
    """The parser backend's server cannot be reached (down, wrong host)."""


class ModelNotFoundError(BackendError):
    """The backend server does not have the requested model (HTTP 404)."""


class BackendTimeoutError(BackendError):
    """The backend did not answer within the timeout."""


class MalformedOutputError(BackendError):
    """The backend answered, but not with a valid TrackSpec."""


class GroundingError(ArenaError):
    """A parser produced a value that cannot be traced to the request (an invention)."""


class PolicyFileError(ArenaError):
    """A policy file is unreadable, corrupt, of an unknown format version, or does not
    match the env it is asked to drive (its observation or action spaces differ)."""


__all__ = [
    "ArenaError",
    "BackendError",
    "BackendTimeoutError",
    "BackendUnavailableError",
    "ConfigError",
    "CorridorError",
    "GroundingError",
    "InternalError",
    "InvalidArgumentError",
    "MapFormatError",
    "MalformedOutputError",
    "MapIOError",
    "ModelNotFoundError",
    "PolicyFileError",
    "RequestParseError",
    "SimulationError",
    "SpecError",
]
