"""One code path, two executors: run ``fn(item)`` for many items on a local process pool
(:class:`~roboracer_arena.foundation.worker_pool.LocalExecutor`, the package's one pool) or as Ray tasks
across a cluster (:class:`~roboracer_arena.distributed.ray_executor.RayExecutor`).

Both yield ``(index, result)`` pairs as tasks finish and retry a task whose worker
process died (killed, out of memory, ``os._exit``) up to ``max_retries`` times. A task
is a module-level function of one picklable item, so the result of item ``i`` depends on
the item only, never on the number of workers or the order of completion. Exceptions
raised by ``fn`` itself are not retried: they propagate to the caller.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import Protocol, TypeVar

from ..foundation.worker_pool import DEFAULT_RETRIES, LocalExecutor, Progress, WorkerLostError, map_ordered
from .ray_executor import RayExecutor

T = TypeVar("T")
R = TypeVar("R")

__all__ = ["Executor", "LocalExecutor", "Progress", "WorkerLostError", "make_executor", "map_ordered"]


class Executor(Protocol):
    """What the library's batch jobs need from an executor."""

    #: Tasks that can run at once (processes, or the cluster's CPUs).
    workers: int

    def run(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[tuple[int, R]]:
        """``(index, fn(items[index]))`` for every item, in completion order."""
        ...

    def close(self) -> None:
        """Release the pool or the cluster connection this executor opened."""
        ...

    def __enter__(self) -> Executor: ...

    def __exit__(self, *exc: object) -> None: ...


def make_executor(
    jobs: int | None = None,
    ray_address: str | None = None,
    max_retries: int = DEFAULT_RETRIES,
    arg: str = "ray_address",
) -> Executor:
    """A :class:`LocalExecutor` with ``jobs`` processes (default: all cores), or, with
    ``ray_address`` (``"auto"``, ``"local"`` or ``"ray://HOST:PORT"`` / ``"HOST:PORT"``),
    a :class:`~roboracer_arena.distributed.ray_executor.RayExecutor` on that cluster.
    ``arg`` is how errors name the address (the CLI passes ``"--ray"``)."""
    if ray_address:
        return RayExecutor(ray_address, max_retries=max_retries, arg=arg)
    import os

    return LocalExecutor(jobs or os.cpu_count() or 1, max_retries=max_retries)
