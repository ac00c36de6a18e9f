"""Fault injection for the executor tests: a task wrapper whose worker process dies
(``os._exit``) on the first attempt at chosen items, recorded by marker files so the
retry runs normally. Picklable, so it crosses process and Ray boundaries."""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import Any


class ExitOnce:
    """``fn(item)``, except that the first attempt at an item in ``die_at`` kills its worker."""

    def __init__(self, fn: Callable[[Any], Any], marker_dir: Path, die_at: set[int], key: Callable[[Any], int]) -> None:
        self.fn, self.marker_dir, self.die_at, self.key = fn, Path(marker_dir), set(die_at), key

    def __call__(self, item: Any) -> Any:
        k = self.key(item)
        if k in self.die_at:
            marker = self.marker_dir / f"died-{k}"
            if not marker.exists():
                marker.write_text(str(os.getpid()))
                os._exit(17)  # no cleanup, no exception: as if the process were killed
        return self.fn(item)


def square(x: int) -> int:
    return x * x


def first(item: tuple) -> int:
    return int(item[0])


def task_index(item: tuple) -> int:
    """Index of a sweep request from its track id ``<name>-<k>``."""
    return int(item[0].rsplit("-", 1)[1])


def always_dies(item: Any) -> Any:
    os._exit(3)
