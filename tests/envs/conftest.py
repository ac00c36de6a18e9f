"""Fixtures for the env tests: a synthetic stadium track (exact geometry, no map needed)
and the shared recorded Berlin map."""

from __future__ import annotations

import pytest
from synthetic_tracks import stadium

from roboracer_arena.track import Track


@pytest.fixture(scope="session")
def oval() -> Track:
    return stadium()


@pytest.fixture(scope="session")
def berlin(sources):
    path = sources / "f1tenth-gym" / "maps" / "berlin.yaml"
    if not path.is_file():
        pytest.fail(f"missing shared map {path}")
    return path
