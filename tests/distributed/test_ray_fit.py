"""Ray requests that do not fit the machine fail at once, in one line naming the API
arguments; the README's Ray example runs as written from a fresh process."""

from __future__ import annotations

import re
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest
import ray  # CI installs the [ray] extra: these tests never skip

from roboracer_arena.distributed import RayVectorEnv
from roboracer_arena.distributed.ray_fit import check_actors_fit, local_cpus
from roboracer_arena.errors import InvalidArgumentError
from synthetic_tracks import stadium

README = Path(__file__).resolve().parents[2] / "README.md"
SMALL = "gen-l040-w12-h2c1s1-clo-s0"  # a generated track shipped in the wheel


def run_fresh(code: str, cwd: Path, timeout: float) -> subprocess.CompletedProcess:
    """``code`` in a new Python process (no Ray connection), outside the checkout."""
    return subprocess.run(
        [sys.executable, "-c", code], cwd=cwd, capture_output=True, text=True, timeout=timeout, check=False
    )


def test_the_message_says_what_is_asked_what_there_is_and_what_fits():
    check_actors_fit(2, 1.0, 2.0, 2.0)  # fits: no error
    check_actors_fit(8, 0.25, 2.0)
    with pytest.raises(InvalidArgumentError) as e:
        check_actors_fit(8, 1.0, 2.0, 2.0, envs_per_actor=256)
    msg = str(e.value)
    assert "\n" not in msg and "--ray" not in msg
    for part in ("num_actors=8", "needs 8 CPUs", "has 2 CPUs", "at most num_actors=2 fit", "envs_per_actor=1024"):
        assert part in msg
    assert "num_cpus_per_actor to 0.25" in msg
    with pytest.raises(InvalidArgumentError, match=r"has 4 CPUs \(1 free, the rest held.*num_actors=1 fit"):
        check_actors_fit(2, 1.0, 4.0, 1.0)
    with pytest.raises(InvalidArgumentError, match="no actor fits"):
        check_actors_fit(1, 4.0, 2.0)


def test_too_many_local_actors_fail_in_under_5_s_before_ray_starts(tmp_path):
    code = textwrap.dedent(
        """
        import sys, time
        from roboracer_arena.distributed import RayVectorEnv
        from roboracer_arena.distributed.ray_fit import local_cpus
        t0 = time.perf_counter()
        try:
            RayVectorEnv(num_actors=4 * local_cpus(), envs_per_actor=256, address="local", track="generated")
        except Exception as e:
            print(type(e).__name__, round(time.perf_counter() - t0, 3), "ray" in sys.modules, sep="|")
            print(e)
        """
    )
    t0 = time.perf_counter()
    out = run_fresh(code, tmp_path, timeout=120)
    total = time.perf_counter() - t0
    head, msg = out.stdout.strip().split("\n")
    kind, seconds, ray_imported = head.split("|")
    # The fit is checked first, before the track check's imports: no work in the constructor.
    assert kind == "InvalidArgumentError" and float(seconds) < 1.0, out
    assert ray_imported == "False"  # decided before Ray was even imported, let alone started
    assert "this machine (address='local')" in msg and "num_actors=" in msg and "--ray" not in msg
    assert total < 60  # the whole process, imports included (a loaded CI machine has slack)


def test_cli_errors_name_the_flag_and_api_errors_the_argument(tmp_path):
    code = textwrap.dedent(
        """
        from roboracer_arena.distributed.ray_cluster import connect
        from roboracer_arena.distributed.executor import make_executor
        for call in (lambda: connect("", "address"), lambda: connect("", "--ray")):
            try:
                call()
            except Exception as e:
                print(type(e).__name__, "|", e)
        """
    )
    lines = run_fresh(code, tmp_path, timeout=120).stdout.strip().splitlines()
    assert lines[0].startswith("InvalidArgumentError | address='': expected auto, local or HOST:PORT")
    assert lines[1].startswith("InvalidArgumentError | --ray : expected auto, local or HOST:PORT")


def readme_ray_example() -> str:
    text = README.read_text(encoding="utf-8")
    section = text[text.index("## Beyond one machine (Ray)") :]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_the_readme_ray_example_runs_as_written_from_a_fresh_process(tmp_path):
    code = readme_ray_example()
    assert 'address="local"' in code and "num_actors=2" in code
    out = run_fresh(code, tmp_path, timeout=600)
    if local_cpus() < 2:  # what the README promises there: one line at once, no hang
        assert out.returncode != 0 and "InvalidArgumentError: num_actors=2" in out.stderr
        return
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.strip().splitlines()[-1] == "(128, 1081) (128,)"
    assert "Token authentication" not in out.stderr  # Ray's notice is kept off the terminal


@pytest.fixture(scope="module")
def two_cpu_cluster():
    ray.init(num_cpus=2, include_dashboard=False, logging_level="ERROR", log_to_driver=False)
    yield
    ray.shutdown()


def test_a_connected_cluster_too_small_fails_fast_and_counts_held_cpus(two_cpu_cluster):
    oval = [stadium()]
    t0 = time.perf_counter()
    with pytest.raises(InvalidArgumentError, match=r"needs 3 CPUs but the Ray cluster has 2 CPUs.*num_actors=2 fit"):
        RayVectorEnv(3, 4, track=oval)
    assert time.perf_counter() - t0 < 5.0
    held = RayVectorEnv(2, 1, track=oval)  # both CPUs now held by its actors
    try:
        t0 = time.perf_counter()
        with pytest.raises(InvalidArgumentError, match=r"has 2 CPUs \(0 free, the rest held"):
            RayVectorEnv(1, 1, track=oval)
        assert time.perf_counter() - t0 < 5.0
    finally:
        held.close()
    again = RayVectorEnv(2, 1, track=oval)  # the closed env's CPUs come back (asynchronously): no error
    again.close()
    assert ray.is_initialized()  # the test's own cluster is left as it was
