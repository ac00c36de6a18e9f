"""Shared fixtures: where the public track data lives, and small maps written on the fly."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent


def sources_dir() -> Path:
    """The public track data (../shared/track-sources by default)."""
    return Path(os.environ.get("ROBORACER_ARENA_SOURCES", REPO.parent / "shared" / "track-sources"))


@pytest.fixture(scope="session")
def sources() -> Path:
    d = sources_dir()
    if not (d / "map-inventory.csv").is_file():
        pytest.fail(f"track sources not found at {d}; set ROBORACER_ARENA_SOURCES")
    return d
