"""Deprecated: moved to :mod:`roboracer_arena.catalog.entry_text` (issue #24); this alias goes
in a later release."""

import warnings

from ..catalog.entry_text import *  # noqa: F403

warnings.warn(
    "roboracer_arena.library.entry_text moved to roboracer_arena.catalog.entry_text", DeprecationWarning, stacklevel=2
)
