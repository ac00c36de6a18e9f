"""Fixtures for the round-2 hostile-input tests: a small ROS map and a runner for the CLI
in a subprocess (signals, exit codes, files left behind)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest


@pytest.fixture(scope="session")
def ellipse_map(tmp_path_factory) -> Path:
    """A 12 x 7 m elliptical track, 1.8 m wide, as a ROS map YAML (+ PGM image)."""
    from roboracer_arena import _core
    from roboracer_arena.maps import OccupancyMap

    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    xy = np.column_stack([6.0 * np.cos(t), 3.5 * np.sin(t)])
    data, origin = _core.rasterise_centreline(xy, np.full(len(xy), 1.8), resolution=0.05)
    return OccupancyMap(data, 0.05, origin).save(tmp_path_factory.mktemp("map") / "ellipse.yaml")


def cli(*args: str, cwd: Path | None = None) -> subprocess.Popen:
    """``roboracer-arena ARGS`` in a subprocess (stdout/stderr piped, text)."""
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    env.setdefault("RAYON_NUM_THREADS", "2")
    return subprocess.Popen(
        [sys.executable, "-c", "import sys; from roboracer_arena.cli import main; sys.exit(main())", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        cwd=cwd,
    )


def strays(folder: Path) -> list[str]:
    """Hidden temporaries left in ``folder`` (recorder, atomic writes, staging folders)."""
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


@pytest.fixture(autouse=True, scope="session")
def _warm_cli() -> None:
    """Import every subcommand once, so timings of "refused before any work" measure the
    command, not the first import of the CLI."""
    from roboracer_arena.cli import make_parser

    make_parser()
