"""The catalog reading moved from ``roboracer_arena.library`` to ``roboracer_arena.catalog``
(issue #24): the package's names still resolve through ``library``, and the old module
paths still import, with a DeprecationWarning naming the new home."""

from __future__ import annotations

import importlib
import sys

import pytest

import roboracer_arena.catalog as catalog
import roboracer_arena.library as library

MOVED = {
    "catalog": "catalog_file",
    "entry": "entry",
    "entry_text": "entry_text",
    "directions": "directions",
    "tracks": "tracks",
}


def test_library_reexports_the_catalog_names() -> None:
    for name in catalog.__all__:
        assert getattr(library, name) is getattr(catalog, name)


@pytest.mark.parametrize(("old", "new"), sorted(MOVED.items()))
def test_old_module_path_warns_and_reexports(old: str, new: str) -> None:
    sys.modules.pop(f"roboracer_arena.library.{old}", None)
    with pytest.warns(DeprecationWarning, match=f"roboracer_arena.catalog.{new}"):
        shim = importlib.import_module(f"roboracer_arena.library.{old}")
    target = importlib.import_module(f"roboracer_arena.catalog.{new}")
    public = [n for n in vars(target) if not n.startswith("_")]
    assert public
    for name in public:
        assert getattr(shim, name) is getattr(target, name)
