"""Beyond one machine: the executors batch jobs run on (a local process pool or Ray tasks)
and :class:`RayVectorEnv`, a gymnasium vector env whose environments live in Ray actors.

Ray is optional (``pip install 'roboracer-arena[ray]'``); without it only
:class:`LocalExecutor` is usable and nothing else in the package changes.
"""

from .executor import Executor, LocalExecutor, WorkerLostError, make_executor, map_ordered


def __getattr__(name: str):
    if name == "RayExecutor":
        from .ray_executor import RayExecutor

        return RayExecutor
    if name == "RayVectorEnv":
        from .ray_vector import RayVectorEnv

        return RayVectorEnv
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "Executor",
    "LocalExecutor",
    "RayExecutor",
    "RayVectorEnv",
    "WorkerLostError",
    "make_executor",
    "map_ordered",
]
