"""Fixtures for the round-2 hostile-input tests: a small ROS map and a runner for the CLI
in a subprocess (signals, exit codes, files left behind)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest


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
