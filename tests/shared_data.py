"""Where the public track data lives for the tests (importable from any test module:
``tests/`` is on sys.path through the rootdir conftest)."""

from __future__ import annotations

from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def sources_dir() -> Path:
    """The public track data: what the package resolves (``roboracer_arena.foundation.paths``), else
    ../shared/track-sources beside this checkout (the tests may run against an installed wheel)."""
    from roboracer_arena.foundation.paths import default_sources_dir

    return default_sources_dir() or (REPO.parent / "shared" / "track-sources")
