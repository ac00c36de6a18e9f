"""Deprecated: moved to :mod:`roboracer_arena.catalog.tracks` (issue #24); this alias goes
in a later release."""

import warnings

from ..catalog.tracks import *  # noqa: F403

warnings.warn(
    "roboracer_arena.library.tracks moved to roboracer_arena.catalog.tracks", DeprecationWarning, stacklevel=2
)
