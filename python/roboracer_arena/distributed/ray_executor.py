"""The Ray executor: each item is one Ray task (one CPU). A task whose worker process dies
is resubmitted by Ray itself (``max_retries``); results come back to the driver, which
alone writes files, so a retried task can neither duplicate nor lose an output."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import Any, TypeVar

from ..errors import InvalidArgumentError
from ..foundation.worker_pool import DEFAULT_RETRIES, WorkerLostError, raise_named
from .ray_cluster import cluster_cpus, connect, import_ray

T = TypeVar("T")
R = TypeVar("R")


def _call(fn: Callable[[Any], Any], item: Any) -> Any:
    return fn(item)


class RayExecutor:
    """Run tasks on the Ray cluster at ``address`` (see :mod:`.ray_cluster`)."""

    def __init__(
        self,
        address: str = "auto",
        max_retries: int = DEFAULT_RETRIES,
        workers: int | None = None,
        arg: str = "address",
    ) -> None:
        """``workers``: tasks in flight at most (default: the cluster's CPUs, with as many
        again queued so no CPU waits for the driver's round trip). ``arg``: how errors name
        the address (``"--ray"`` from the CLI)."""
        self._owns = connect(address, arg)
        ray = import_ray()
        self.max_retries = int(max_retries)
        self.workers = int(workers) if workers else cluster_cpus()
        if self.workers < 1:
            raise InvalidArgumentError(f"workers must be >= 1, got {workers}")
        # A bounded window also keeps the driver's memory flat for libraries of thousands of tracks.
        self.max_in_flight = self.workers if workers else 2 * self.workers
        # One CPU per task, so one native thread (rayon) per task: tasks on a node do not oversubscribe it.
        self._remote = ray.remote(
            num_cpus=1,
            max_retries=self.max_retries,
            retry_exceptions=False,
            runtime_env={"env_vars": {"RAYON_NUM_THREADS": "1"}},
        )(_call)

    def __enter__(self) -> RayExecutor:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        if self._owns:
            import_ray().shutdown()
            self._owns = False

    def run(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[tuple[int, R]]:
        ray = import_ray()
        from ray.exceptions import WorkerCrashedError

        fn_ref = ray.put(fn)
        todo = iter(range(len(items)))
        refs: dict[Any, int] = {}

        def submit() -> None:
            for i in todo:
                refs[self._remote.remote(fn_ref, items[i])] = i
                if len(refs) >= self.max_in_flight:
                    return

        submit()
        try:
            while refs:
                done, _ = ray.wait(list(refs), num_returns=1)
                for ref in done:
                    i = refs.pop(ref)
                    try:
                        r = ray.get(ref)
                    except WorkerCrashedError as e:
                        raise WorkerLostError(
                            f"task {i}: its worker died more than {self.max_retries} times ({e})"
                        ) from None
                    except ray.exceptions.RayTaskError as e:
                        raise_named(e.as_instanceof_cause(), i, items[i])  # the task's own exception type
                    yield i, r
                submit()
        finally:
            for ref in refs:  # the caller stopped early: do not leave tasks running
                ray.cancel(ref, force=True)
