"""The package's one worker pool (:mod:`roboracer_arena.foundation.worker_pool`): results in item order,
``jobs == 1`` in this process, threads and isolated workers on request, and an error
that names the item that failed while keeping its type."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from roboracer_arena.errors import SpecError
from roboracer_arena.foundation.worker_pool import LocalExecutor, pool_map


def _pid(_: object) -> int:
    return os.getpid()


def _slow_square(x: int) -> int:
    import time

    time.sleep(0.01 * (5 - x % 5))  # later items tend to finish first
    return x * x


def _inverse(x: int) -> float:
    return 1 / x


def _bad_spec(x: int) -> int:
    if x == 2:
        raise SpecError("lap_length_m: must be > 0")
    return x


def _env_threads(_: object) -> str | None:
    return os.environ.get("RRA_POOL_TEST")


def _set_env(value: str) -> None:
    os.environ["RRA_POOL_TEST"] = value


@pytest.mark.parametrize("options", [{"jobs": 1}, {"jobs": 2}, {"jobs": 3, "threads": True}])
def test_results_come_back_in_item_order(options):
    seen: list[int] = []

    def progress(it, total):
        assert total == 10
        for i, r in it:
            seen.append(i)
            yield i, r

    assert pool_map(_slow_square, list(range(10)), progress=progress, **options) == [x * x for x in range(10)]
    assert sorted(seen) == list(range(10))  # progress saw each item once


def test_one_job_runs_in_this_process_and_more_jobs_do_not():
    assert set(pool_map(_pid, [0, 1, 2], jobs=1)) == {os.getpid()}
    assert os.getpid() not in set(pool_map(_pid, [0, 1, 2], jobs=2))


def test_isolate_runs_one_item_in_a_fresh_initialised_worker():
    got = pool_map(_env_threads, [0], isolate=True, initializer=_set_env, initargs=("3",))
    assert got == ["3"] and "RRA_POOL_TEST" not in os.environ  # set in the worker, not here


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_failing_item_names_itself_and_keeps_its_type(jobs):
    with pytest.raises(ZeroDivisionError, match=r"^item 1 0: division by zero$"):
        pool_map(_inverse, [1, 0, 2], jobs=jobs)
    with pytest.raises(SpecError, match=r"^item 2 2: lap_length_m: must be > 0$"):
        pool_map(_bad_spec, [0, 1, 2, 3], jobs=jobs)


def test_an_exception_that_takes_no_plain_message_gets_a_note():
    with pytest.raises(KeyError) as info:
        pool_map({"a": 1}.__getitem__, ["a", "b"])
    assert info.value.args == ("b",)
    assert "while running item 1 'b'" in "".join(info.value.__notes__)


def _refuse(_: object) -> None:
    raise ValueError("refused")


def test_long_items_are_shortened_in_the_message():
    with pytest.raises(ValueError, match=r"^item 0 'x{76}\.\.\.: refused$"):
        pool_map(_refuse, ["x" * 500])


def test_bad_jobs_are_refused():
    from roboracer_arena.errors import ArenaError

    with pytest.raises(ArenaError, match="jobs must be >= 1"):
        LocalExecutor(0)


def test_a_main_script_from_stdin_gets_a_hint_not_only_dead_workers():
    """Spawned workers re-import ``__main__``; from stdin that fails in every worker, and
    the error says why instead of only counting deaths."""
    script = "from roboracer_arena.foundation.worker_pool import pool_map\nprint(pool_map(abs, [-1, -2], 2))\n"
    run = subprocess.run([sys.executable, "-"], input=script, capture_output=True, text=True, timeout=120)
    assert run.returncode != 0
    assert "WorkerLostError" in run.stderr and "came from stdin: run it from a file, or use jobs=1" in run.stderr
