"""Shared fixtures: where the public track data lives, and small maps written on the fly."""

from __future__ import annotations

from pathlib import Path

import pytest

from shared_data import sources_dir

REPO = Path(__file__).resolve().parent.parent


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
