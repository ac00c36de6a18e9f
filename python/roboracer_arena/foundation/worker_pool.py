"""The package's one worker pool: run ``fn(item)`` for many items on spawned processes (or
threads), with results in item order, an optional progress callback, and an error that
names the item that failed.

Every batch job that starts a pool goes through :class:`LocalExecutor` (directly, through
:func:`pool_map`, or as the local half of :mod:`roboracer_arena.distributed`):

* ``jobs == 1`` runs in this process, no pool (unless ``isolate``: one fresh worker);
* processes are *spawned*, never forked: the parent may hold rayon threads and native handles;
* a worker that dies (killed, out of memory, ``os._exit``) is replaced and its unfinished
  tasks rerun, up to ``max_retries`` times (:class:`WorkerLostError` after that);
* an exception raised by ``fn`` is not retried; it reaches the caller with the item's
  index and a short repr in its message, and keeps its type (so ``except`` clauses and
  the CLI's exit codes see what ``fn`` raised).
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, ThreadPoolExecutor, wait
from concurrent.futures import Executor as _FuturesExecutor
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager
from pathlib import Path
from typing import Any, NoReturn, TypeVar

from ..errors import ArenaError

T = TypeVar("T")
R = TypeVar("R")
#: ``progress(iterator, total)`` wraps the result iterator (e.g. a tqdm bar).
Progress = Callable[[Iterator[Any], int], Iterator[Any]]

DEFAULT_RETRIES = 3
#: Longest item repr quoted in an error message.
_ITEM_REPR = 80


class WorkerLostError(ArenaError):
    """A task's worker process died more often than the executor's ``max_retries``."""


def raise_named(exc: Exception, index: int, item: object) -> NoReturn:
    """Raise ``exc`` with the failing item in its message: a new exception of the same
    type (caused by ``exc``) when the type takes a plain message, else ``exc`` itself with
    the item as a note (Python >= 3.11)."""
    text = repr(item)
    short = text if len(text) <= _ITEM_REPR else text[: _ITEM_REPR - 3] + "..."
    msg = f"item {index} {short}: {exc}"
    try:
        new = type(exc)(msg)
    except Exception:
        new = None
    if new is None or str(new) != msg:
        if sys.version_info >= (3, 11):  # notes are new in 3.11; before, the error goes as raised
            exc.add_note(f"while running item {index} {short}")
        raise exc
    raise new from exc


class LocalExecutor:
    """``jobs`` spawned worker processes (or threads with ``threads=True``, for work that
    releases the GIL); ``jobs == 1`` runs in this process unless ``isolate`` asks for a
    fresh worker. ``initializer(*initargs)`` runs once in each worker.

    The pool is created on first use and kept until :meth:`close` (or the end of a
    ``with`` block), so repeated :meth:`run` calls share it."""

    def __init__(
        self,
        jobs: int = 1,
        max_retries: int = DEFAULT_RETRIES,
        *,
        threads: bool = False,
        isolate: bool = False,
        initializer: Callable[..., object] | None = None,
        initargs: tuple[Any, ...] = (),
    ) -> None:
        if jobs < 1:
            raise ArenaError(f"jobs must be >= 1, got {jobs}")
        self.workers = int(jobs)
        self.max_retries = int(max_retries)
        self.threads = threads
        self.isolate = isolate
        self._init = (initializer, initargs)
        self._pool: _FuturesExecutor | None = None

    def __enter__(self) -> LocalExecutor:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        """Shut the pool down (cancelling tasks not yet started)."""
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None

    def _new_pool(self) -> _FuturesExecutor:
        from multiprocessing import get_context

        init, initargs = self._init
        if self.threads:
            self._pool = ThreadPoolExecutor(self.workers, initializer=init, initargs=initargs)
        else:
            ctx = get_context("spawn")
            self._pool = ProcessPoolExecutor(self.workers, mp_context=ctx, initializer=init, initargs=initargs)
        return self._pool

    def run(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[tuple[int, R]]:
        """``(index, fn(items[index]))`` for every item, in completion order."""
        if not self.isolate and (self.workers == 1 or len(items) <= 1):
            init, initargs = self._init
            if init is not None and items:
                init(*initargs)
            for i, x in enumerate(items):
                try:
                    r = fn(x)
                except Exception as e:
                    raise_named(e, i, x)
                yield i, r
            return
        pending = set(range(len(items)))
        failures = 0
        while pending:
            pool = self._pool or self._new_pool()
            futures: dict[Future[R], int] = {pool.submit(fn, items[i]): i for i in sorted(pending)}
            try:
                while futures:
                    done, _ = wait(futures, return_when=FIRST_COMPLETED)
                    for f in done:
                        i = futures.pop(f)
                        try:
                            r = f.result()
                        except BrokenProcessPool:  # a worker died: handled below
                            raise
                        except Exception as e:
                            raise_named(e, i, items[i])
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
                        f"giving up after {self.max_retries} retries{_unspawnable_main_hint()}"
                    ) from None


def _unspawnable_main_hint() -> str:
    """Why every spawned worker may die at once: it re-imports the parent's ``__main__``,
    which fails when that script came from standard input."""
    main_file = getattr(sys.modules.get("__main__"), "__file__", None)
    if main_file is not None and Path(main_file).name == "<stdin>":
        return " (workers are spawned and re-import the main script, which came from stdin: run it from a file, or use jobs=1)"
    return ""


def map_ordered(executor: Any, fn: Callable[[T], R], items: Sequence[T], progress: Progress | None = None) -> list[R]:
    """``[fn(x) for x in items]`` on ``executor`` (anything with ``run(fn, items)``, e.g. a
    :class:`LocalExecutor` or a Ray executor), results in item order (``progress`` sees
    them in completion order)."""
    out: list[Any] = [None] * len(items)
    it: Iterator[tuple[int, R]] = executor.run(fn, items)
    for i, r in progress(it, len(items)) if progress else it:
        out[i] = r
    return out


@contextmanager
def local_unless(executor: Any, jobs: int) -> Iterator[Any]:
    """``executor`` as given (the caller owns it), or a :class:`LocalExecutor` of ``jobs``
    workers that is closed on exit."""
    if executor is not None:
        yield executor
    else:
        with LocalExecutor(jobs) as ex:
            yield ex


def tqdm_progress(desc: str, unit: str = "it", **options: Any) -> Progress:
    """A :data:`Progress` that shows a tqdm bar on stderr (hidden when it is not a
    terminal, unless ``disable`` is given in ``options``)."""
    from tqdm import tqdm

    options.setdefault("disable", None)
    return lambda it, total: tqdm(it, total=total, desc=desc, unit=unit, **options)


def pool_map(
    fn: Callable[[T], R],
    items: Sequence[T],
    jobs: int = 1,
    progress: Progress | None = None,
    **options: Any,
) -> list[R]:
    """``[fn(x) for x in items]`` on a :class:`LocalExecutor` of ``jobs`` workers that is
    closed afterwards; ``options`` are its keyword options (``threads``, ``isolate``,
    ``initializer``, ``initargs``, ``max_retries``)."""
    with LocalExecutor(jobs, **options) as ex:
        return map_ordered(ex, fn, items, progress)
