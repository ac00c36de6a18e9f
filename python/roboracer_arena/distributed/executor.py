"""One code path, two executors: run ``fn(item)`` for many items on a local process pool
(:class:`LocalExecutor`) or as Ray tasks across a cluster
(:class:`~roboracer_arena.distributed.ray_executor.RayExecutor`).

Both yield ``(index, result)`` pairs as tasks finish and retry a task whose worker
process died (killed, out of memory, ``os._exit``) up to ``max_retries`` times. A task
is a module-level function of one picklable item, so the result of item ``i`` depends on
the item only, never on the number of workers or the order of completion. Exceptions
raised by ``fn`` itself are not retried: they propagate to the caller.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from typing import Any, Protocol, TypeVar

from ..errors import ArenaError

T = TypeVar("T")
R = TypeVar("R")
#: ``progress(iterator, total)`` wraps the result iterator (e.g. a tqdm bar).
Progress = Callable[[Iterator[Any], int], Iterator[Any]]

DEFAULT_RETRIES = 3


class WorkerLostError(ArenaError):
    """A task's worker process died more often than the executor's ``max_retries``."""


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


def map_ordered(
    executor: Executor, fn: Callable[[T], R], items: Sequence[T], progress: Progress | None = None
) -> list[R]:
    """``[fn(x) for x in items]`` on ``executor``, results in item order (``progress``
    sees them in completion order)."""
    out: list[Any] = [None] * len(items)
    it: Iterator[tuple[int, R]] = executor.run(fn, items)
    for i, r in progress(it, len(items)) if progress else it:
        out[i] = r
    return out


class LocalExecutor:
    """``jobs`` spawned worker processes (``jobs <= 1``: in this process, no pool).

    The pool is created on first use and kept until :meth:`close` (or the end of a
    ``with`` block), so repeated :meth:`run` calls share it."""

    def __init__(self, jobs: int = 1, max_retries: int = DEFAULT_RETRIES) -> None:
        if jobs < 1:
            raise ArenaError(f"jobs must be >= 1, got {jobs}")
        self.workers = int(jobs)
        self.max_retries = int(max_retries)
        self._pool: ProcessPoolExecutor | None = None

    def __enter__(self) -> LocalExecutor:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None

    def _new_pool(self) -> ProcessPoolExecutor:
        from multiprocessing import get_context

        # spawn, not fork: the parent may hold rayon threads and open native handles.
        self._pool = ProcessPoolExecutor(self.workers, mp_context=get_context("spawn"))
        return self._pool

    def run(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[tuple[int, R]]:
        if self.workers == 1 or len(items) <= 1:
            for i, x in enumerate(items):
                yield i, fn(x)
            return
        pending = set(range(len(items)))
        failures = 0
        while pending:
            pool = self._pool or self._new_pool()
            futures: dict[Future, int] = {pool.submit(fn, items[i]): i for i in sorted(pending)}
            try:
                while futures:
                    done, _ = wait(futures, return_when=FIRST_COMPLETED)
                    for f in done:
                        i = futures.pop(f)
                        r = f.result()  # BrokenProcessPool if a worker died
                        pending.discard(i)
                        yield i, r
            except BrokenProcessPool:
                # Every unfinished task failed with the pool; the finished ones are kept, the
                # rest run again on a fresh pool (each index is yielded exactly once).
                pool.shutdown(wait=False, cancel_futures=True)
                self._pool = None
                failures += 1
                if failures > self.max_retries:
                    raise WorkerLostError(
                        f"a worker process died {failures} times ({len(pending)} task(s) unfinished); "
                        f"giving up after {self.max_retries} retries"
                    ) from None


def make_executor(
    jobs: int | None = None, ray_address: str | None = None, max_retries: int = DEFAULT_RETRIES
) -> Executor:
    """A :class:`LocalExecutor` with ``jobs`` processes (default: all cores), or, with
    ``ray_address`` (``"auto"``, ``"local"`` or ``"ray://HOST:PORT"`` / ``"HOST:PORT"``),
    a :class:`~roboracer_arena.distributed.ray_executor.RayExecutor` on that cluster."""
    if ray_address:
        from .ray_executor import RayExecutor

        return RayExecutor(ray_address, max_retries=max_retries)
    import os

    return LocalExecutor(jobs or os.cpu_count() or 1, max_retries=max_retries)
