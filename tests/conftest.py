"""Shared fixtures: where the public track data lives, and small maps written on the fly."""

from __future__ import annotations

from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent


def sources_dir() -> Path:
    """The public track data: what the package resolves (``roboracer_arena.paths``), else
    ../shared/track-sources beside this checkout (the tests may run against an installed wheel)."""
    from roboracer_arena.paths import default_sources_dir

    return default_sources_dir() or (REPO.parent / "shared" / "track-sources")


@pytest.fixture(scope="session")
def oval():
    """A synthetic stadium track (exact geometry, no map needed)."""
    from synthetic_tracks import stadium

    return stadium()


@pytest.fixture(scope="session")
def sources() -> Path:
    d = sources_dir()
    if not (d / "map-inventory.csv").is_file():
        pytest.fail(f"track sources not found at {d}; set ROBORACER_ARENA_SOURCES")
    return d
