"""Register ``RoboRacerArena-v0`` with gymnasium without importing gymnasium eagerly.

Gymnasium >= 1.0 has no plugin entry points, so ``import roboracer_arena`` calls
:func:`install`: if gymnasium is already imported the env is registered at once;
otherwise a one-shot import hook registers it as soon as gymnasium finishes importing.
"""

from __future__ import annotations

import importlib.abc
import importlib.util
import sys
from typing import Any


def _register() -> None:
    from . import register_envs

    register_envs()


class _Loader(importlib.abc.Loader):
    def __init__(self, inner: Any) -> None:
        self._inner = inner

    def create_module(self, spec: Any) -> Any:
        return self._inner.create_module(spec)

    def exec_module(self, module: Any) -> None:
        self._inner.exec_module(module)
        _register()


class _Finder(importlib.abc.MetaPathFinder):
    def find_spec(self, name: str, path: Any = None, target: Any = None) -> Any:
        if name != "gymnasium":
            return None
        sys.meta_path.remove(self)  # one shot; also avoids finding ourselves
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.loader is not None:
            spec.loader = _Loader(spec.loader)
        return spec


def install() -> None:
    """Register now if gymnasium is loaded, else once it is imported."""
    if "gymnasium" in sys.modules:
        _register()
    elif not any(isinstance(f, _Finder) for f in sys.meta_path):
        sys.meta_path.insert(0, _Finder())
