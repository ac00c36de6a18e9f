"""Does a request for Ray actors fit the cluster? Checked before any actor starts.

Ray queues an actor whose CPUs no node can give and waits for them forever, so
``RayVectorEnv(num_actors=8, ...)`` on a 2-core machine would hang in its constructor.
:func:`check_actors_fit` fails at once instead, with one line naming the API arguments
and what would fit. With ``address="local"`` the check runs before Ray starts, against the
CPUs a local cluster would get (:func:`local_cpus`), so it takes no Ray start-up time.
"""

from __future__ import annotations

import math
import os

from ..errors import InvalidArgumentError
from .ray_cluster import import_ray


def local_cpus() -> int:
    """CPUs a local ``ray.init()`` would offer: the CPUs this process may run on (Ray
    also honours cgroup quotas, which this ignores: the check is then the looser one and
    the cluster's own figure, checked after start-up, is the binding one)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def check_actors_fit(
    num_actors: int,
    cpus_per_actor: float,
    total_cpus: float,
    free_cpus: float | None = None,
    *,
    envs_per_actor: int | None = None,
    where: str = "the Ray cluster",
) -> None:
    """Raise :class:`~roboracer_arena.errors.InvalidArgumentError` (one line) unless
    ``num_actors`` actors of ``cpus_per_actor`` CPUs fit in ``total_cpus`` (and, when given,
    in the ``free_cpus`` not already held by other actors and tasks). The message says how
    many actors fit and, with ``envs_per_actor``, the ``envs_per_actor`` that keeps the total."""
    need = num_actors * cpus_per_actor
    cap = total_cpus if free_cpus is None else min(total_cpus, free_cpus)
    if need <= cap + 1e-9:
        return
    fits = int(math.floor(cap / cpus_per_actor + 1e-9)) if cpus_per_actor > 0 else num_actors
    have = f"{where} has {total_cpus:g} CPUs" + (
        f" ({free_cpus:g} free, the rest held by other actors or tasks)"
        if free_cpus is not None and free_cpus < total_cpus
        else ""
    )
    if fits >= 1:
        hint = f"at most num_actors={fits} fit"
        if envs_per_actor is not None:
            per = math.ceil(num_actors * envs_per_actor / fits)
            hint += f" (envs_per_actor={per} keeps about the same {num_actors * envs_per_actor} envs)"
    else:
        hint = "no actor fits"
    if cap > 0:
        hint += f"; or lower num_cpus_per_actor to {cap / num_actors:g}"
    raise InvalidArgumentError(
        f"num_actors={num_actors} x num_cpus_per_actor={cpus_per_actor:g} needs {need:g} CPUs but {have}: "
        f"Ray would wait for them forever; {hint}"
    )


#: How long a request that fits the cluster's total CPUs waits for enough of them to be free
#: (s): actors killed a moment ago (``RayVectorEnv.close``) give their CPUs back asynchronously.
FREE_WAIT_S = 3.0


def check_cluster_fits(
    num_actors: int, cpus_per_actor: float, envs_per_actor: int | None = None, wait_s: float = FREE_WAIT_S
) -> None:
    """:func:`check_actors_fit` against the connected cluster's CPUs: at once against its
    total, then against its free CPUs, which it waits up to ``wait_s`` seconds for."""
    import time

    ray = import_ray()
    total = float(ray.cluster_resources().get("CPU", 0.0))
    check_actors_fit(num_actors, cpus_per_actor, total, envs_per_actor=envs_per_actor)
    deadline = time.monotonic() + wait_s
    while True:
        free = float(ray.available_resources().get("CPU", 0.0))
        if num_actors * cpus_per_actor <= free + 1e-9 or time.monotonic() >= deadline:
            break
        time.sleep(0.05)
    check_actors_fit(num_actors, cpus_per_actor, total, free, envs_per_actor=envs_per_actor)
