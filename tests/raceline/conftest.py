"""Fixtures of the raceline tests: a stadium planned once per session."""

from __future__ import annotations

import pytest

from roboracer_arena.raceline import plan_raceline, preset


@pytest.fixture(scope="session")
def stadium_line(oval):
    """The f1tenth-racetracks-limits raceline of the synthetic stadium (exact walls)."""
    return plan_raceline(oval, preset("f1tenth-racetracks"))
