"""The local executor (no Ray): results in item order whatever the pool size, and a worker
that dies mid-run is replaced and its task rerun, without duplicates or holes."""

from __future__ import annotations

import pytest
from faults import ExitOnce, always_dies, first, square

from roboracer_arena.distributed import LocalExecutor, WorkerLostError, map_ordered
from roboracer_arena.errors import ArenaError


def test_results_in_item_order_for_any_pool_size():
    items = list(range(23))
    for jobs in (1, 2):
        with LocalExecutor(jobs) as ex:
            assert map_ordered(ex, square, items) == [x * x for x in items]


def test_run_yields_every_index_once():
    with LocalExecutor(2) as ex:
        got = list(ex.run(square, list(range(9))))
    assert sorted(i for i, _ in got) == list(range(9)) and all(r == i * i for i, r in got)


def test_killed_worker_is_retried_without_duplicates_or_holes(tmp_path):
    items = [(i, f"item-{i}") for i in range(12)]
    fn = ExitOnce(first, tmp_path, die_at={3, 8}, key=first)
    with LocalExecutor(2) as ex:
        got = list(ex.run(fn, items))
    assert sorted(i for i, _ in got) == list(range(12))  # each index once
    assert all(r == i for i, r in got)
    assert (tmp_path / "died-3").exists() and (tmp_path / "died-8").exists()  # the workers really died


def test_a_task_that_always_kills_its_worker_gives_up(tmp_path):
    with LocalExecutor(2, max_retries=1) as ex, pytest.raises(WorkerLostError, match="died 2 times"):
        list(ex.run(always_dies, [(0,), (1,)]))


def test_task_exceptions_propagate_and_bad_jobs_are_refused():
    with LocalExecutor(2) as ex, pytest.raises(ZeroDivisionError):
        map_ordered(ex, _inverse, [1, 0, 2])
    with pytest.raises(ArenaError, match="jobs must be >= 1"):
        LocalExecutor(0)


def _inverse(x: int) -> float:
    return 1 / x


def test_ray_flag_without_ray_installed_is_a_clear_bad_input(tmp_path, monkeypatch, capsys):
    import json
    import sys

    from roboracer_arena.cli import main

    monkeypatch.setitem(sys.modules, "ray", None)  # as if the [ray] extra were not installed
    sweep = tmp_path / "s.json"
    sweep.write_text(json.dumps({"ranges": {"lap_length_m": [30, 40]}}))
    assert (
        main(["tracks", "generate", "--sweep", str(sweep), "--count", "1", "-o", str(tmp_path / "o"), "--ray", "auto"])
        == 2
    )
    assert "pip install 'roboracer-arena[ray]'" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()  # nothing written
