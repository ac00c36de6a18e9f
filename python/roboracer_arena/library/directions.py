"""Deprecated: moved to :mod:`roboracer_arena.catalog.directions` (issue #24); this alias goes
in a later release."""

import warnings

from ..catalog.directions import *  # noqa: F403

warnings.warn(
    "roboracer_arena.library.directions moved to roboracer_arena.catalog.directions", DeprecationWarning, stacklevel=2
)
