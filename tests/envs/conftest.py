"""Fixtures for the env tests: the shared recorded Berlin map (the synthetic ``oval``
is in the top-level conftest)."""

from __future__ import annotations

import pytest


@pytest.fixture(scope="session")
def berlin(sources):
    path = sources / "f1tenth-gym" / "maps" / "berlin.yaml"
    if not path.is_file():
        pytest.fail(f"missing shared map {path}")
    return path
