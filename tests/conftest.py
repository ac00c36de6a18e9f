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


@pytest.fixture(scope="session")
def ellipse_map(tmp_path_factory) -> Path:
    """A 12 x 7 m elliptical track, 1.8 m wide, as a ROS map YAML (+ PGM image)."""
    import numpy as np

    from roboracer_arena import _core
    from roboracer_arena.maps.occupancy import OccupancyMap

    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    xy = np.column_stack([6.0 * np.cos(t), 3.5 * np.sin(t)])
    data, origin = _core.rasterise_centreline(xy, np.full(len(xy), 1.8), resolution=0.05)
    return OccupancyMap(data, 0.05, origin).save(tmp_path_factory.mktemp("map") / "ellipse.yaml")
