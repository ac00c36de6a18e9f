"""The catalog reading lives in ``roboracer_arena.catalog`` alone (issue #24 moved it; issue
#37 removed the deprecated aliases): the old ``roboracer_arena.library`` module paths are
gone and ``library`` no longer re-exports the catalog's names (a 0.x package owes no
deprecation period)."""

from __future__ import annotations

import importlib

import pytest

import roboracer_arena.catalog as catalog
import roboracer_arena.library as library

OLD_PATHS = ["catalog", "entry", "entry_text", "directions", "tracks"]


@pytest.mark.parametrize("old", OLD_PATHS)
def test_old_module_path_is_gone(old: str) -> None:
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module(f"roboracer_arena.library.{old}")


def test_catalog_names_live_in_catalog_alone() -> None:
    assert catalog.__all__
    for name in catalog.__all__:
        assert not hasattr(library, name)
