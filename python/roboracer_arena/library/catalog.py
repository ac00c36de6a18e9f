"""Deprecated: moved to :mod:`roboracer_arena.catalog.catalog_file` (issue #24); this alias goes
in a later release."""

import warnings

from ..catalog.catalog_file import *  # noqa: F403

warnings.warn(
    "roboracer_arena.library.catalog moved to roboracer_arena.catalog.catalog_file", DeprecationWarning, stacklevel=2
)
