"""Deprecated: moved to :mod:`roboracer_arena.catalog.entry` (issue #24); this alias goes
in a later release."""

import warnings

from ..catalog.entry import *  # noqa: F403

warnings.warn("roboracer_arena.library.entry moved to roboracer_arena.catalog.entry", DeprecationWarning, stacklevel=2)
