"""Everything on Ray, against ONE local cluster (``ray.init(num_cpus=2)``, module scope):
determinism across worker counts, retry after a killed worker, the RayVectorEnv contract
(gymnasium's checks, same rollouts as the local vector env), ``tracks generate --ray``
end to end, and the ES example on Ray actors."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import faults
import gymnasium as gym
import numpy as np
import pytest
import ray  # CI installs the [ray] extra: these tests never skip
from faults import ExitOnce, task_index
from gymnasium.utils.env_checker import check_reset_seed_determinism, data_equivalence
from gymnasium.vector import AutoresetMode

import roboracer_arena  # noqa: F401  (registers RoboRacerArena-v0)
from roboracer_arena.cli import main
from roboracer_arena.distributed import LocalExecutor, RayExecutor, RayVectorEnv, map_ordered
from roboracer_arena.library.generated import generate_files
from roboracer_arena.library.spec_sweep import SweepFile
from synthetic_tracks import stadium

SWEEP = {
    "name": "r",
    "base_seed": 3,
    "ranges": {
        "lap_length_m": [30, 45],
        "hairpins": [0, 1],
        "direction": {"choice": ["clockwise", "counterclockwise"]},
    },
    "fixed": {"corridor_width_m": 1.5, "hall_x_m": 15, "hall_y_m": 12},
}
SMALL_ENV = {"sim": {"lidar": {"num_beams": 109}}, "reset_poses": "random"}


@pytest.fixture(scope="module", autouse=True)
def cluster():
    # Ray workers do not see pytest's sys.path: ship the test helpers by value.
    ray.cloudpickle.register_pickle_by_value(faults)
    ray.init(num_cpus=2, include_dashboard=False, logging_level="ERROR", log_to_driver=False)
    yield
    ray.shutdown()


@pytest.fixture(scope="module")
def ovals():
    return [stadium(), stadium(4.0, 2.0, name="b")]


def strip(rec: dict) -> dict:
    return {k: v for k, v in rec.items() if k != "seconds"}


def same_results(a: list, b: list) -> bool:
    """generate_files results equal but for wall-clock seconds (record and report.json)."""

    def norm(r):
        rec, files = r
        files = {
            k: (v if k != "report.json" else json.dumps({**json.loads(v), "seconds": 0})) for k, v in files.items()
        }
        return rec.model_copy(update={"seconds": 0.0}), files

    return [norm(r) for r in a] == [norm(r) for r in b]


# ---------------------------------------------------------------- library on Ray tasks
def test_tracks_are_identical_on_local_and_ray_executors_of_any_width(tmp_path):
    sw = SweepFile.model_validate(SWEEP)
    tasks = sw.requests(0, 6)
    with LocalExecutor(1) as ex:
        local = map_ordered(ex, generate_files, tasks)
    for workers in (1, 2):
        ex = RayExecutor("auto", workers=workers)
        assert ex.workers == workers
        assert same_results(map_ordered(ex, generate_files, tasks), local)
    assert sum(bool(files) for _, files in local) >= 3  # real tracks, not only rejections


def test_killed_ray_worker_is_retried_without_duplicates_or_holes(tmp_path):
    sw = SweepFile.model_validate(SWEEP)
    tasks = sw.requests(0, 6)
    with LocalExecutor(1) as ex:
        want = map_ordered(ex, generate_files, tasks)
    fn = ExitOnce(generate_files, tmp_path, die_at={1, 4}, key=task_index)
    got = list(RayExecutor("auto").run(fn, tasks))
    assert sorted(i for i, _ in got) == list(range(6))  # each task once: no duplicate, no hole
    assert (tmp_path / "died-1").exists() and (tmp_path / "died-4").exists()  # two workers really died
    assert same_results([r for _, r in sorted(got, key=lambda x: x[0])], want)


def test_tracks_generate_and_verify_ray_cli_end_to_end(tmp_path, capsys):
    sweep = tmp_path / "sweep.json"
    sweep.write_text(json.dumps(SWEEP))
    ray_out, local_out = tmp_path / "ray", tmp_path / "local"
    assert (
        main(
            ["tracks", "generate", "--sweep", str(sweep), "--count", "3", "-o", str(ray_out), "--ray", "auto", "--json"]
        )
        == 0
    )
    s = json.loads(capsys.readouterr().out)
    assert "records" not in s and s["kept"] == 3 and s["executor"] == "RayExecutor" and s["workers"] == 2
    assert main(["tracks", "generate", "--sweep", str(sweep), "--count", "3", "-o", str(local_out), "--jobs", "1"]) == 0
    capsys.readouterr()
    for d in ("r-00000", "r-00001"):
        for f in ("map.png", "map.yaml", "centreline.csv", "spec.json"):
            assert (ray_out / "generated" / d / f).read_bytes() == (local_out / "generated" / d / f).read_bytes()
    assert [strip(r) for r in json.loads((ray_out / "sweep.json").read_text())["records"]] == [
        strip(r) for r in json.loads((local_out / "sweep.json").read_text())["records"]
    ]
    assert (
        main(["tracks", "verify", "--catalog", str(ray_out / "catalog.json"), "--no-usd", "--ray", "auto", "--json"])
        == 0
    )
    v = json.loads(capsys.readouterr().out)
    assert v["passed"] == v["tracks"] == 3 and all(r["checks"]["drive"]["status"] == "pass" for r in v["results"])


# ---------------------------------------------------------------- RayVectorEnv
def local_vec(n, tracks, **kw):
    return gym.make_vec(
        "RoboRacerArena-v0", num_envs=n, vectorization_mode="vector_entry_point", track=tracks, **{**SMALL_ENV, **kw}
    )


@pytest.mark.parametrize("mode", [AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP])
def test_ray_vector_env_rolls_out_exactly_like_the_local_vector_env(ovals, mode, monkeypatch):
    from roboracer_arena.distributed import ray_vector

    monkeypatch.setattr(ray_vector, "INLINE_BYTES", 2000)  # step results come back in several pieces
    kw = {"autoreset_mode": mode, "max_episode_steps": 15}  # short episodes: autoresets happen
    renv, lenv = RayVectorEnv(2, 3, track=ovals, **SMALL_ENV, **kw), local_vec(6, ovals, **kw)
    try:
        assert renv.single_observation_space == lenv.single_observation_space
        assert renv.observation_space == lenv.observation_space and renv.action_space == lenv.action_space
        assert renv.metadata["autoreset_mode"] == mode and renv.num_envs == 6
        assert data_equivalence(renv.reset(seed=11), lenv.reset(seed=11), exact=True)
        lenv.action_space.seed(0)
        ended, finals = 0, 0
        for _ in range(40):
            a = lenv.action_space.sample()
            r, lo = renv.step(a), lenv.step(a)
            assert data_equivalence(r, lo, exact=True)
            assert renv.observation_space.contains(r[0])
            ended += int((r[2] | r[3]).sum())
            finals += int(r[4].get("_final_obs", np.zeros(1, bool)).sum())
        assert ended >= 6  # every env went through at least one autoreset
        assert renv._chunks > 1
        assert finals == (ended if mode == AutoresetMode.SAME_STEP else 0)
        # Partial reset with per-env options is split over the actors the same way.
        opts = {"reset_mask": np.array([1, 0, 0, 0, 1, 1], bool), "track_ids": np.array([1, 0, 0, 0, 1, 0])}
        assert data_equivalence(renv.reset(options=opts), lenv.reset(options=opts), exact=True)
        assert np.array_equal(renv.current_track_ids, lenv.unwrapped.current_track_ids)
        assert data_equivalence(renv.start_state(), lenv.unwrapped.start_state(), exact=True)
    finally:
        renv.close()
        lenv.close()


def test_ray_vector_env_passes_gymnasium_checks_and_wrappers(ovals):
    env = RayVectorEnv(2, 2, track=ovals, **SMALL_ENV)
    try:
        check_reset_seed_determinism(env)  # gymnasium's own check (its step check is single-env only)
        a = env.action_space.sample()
        first = (env.reset(seed=5), env.step(a))
        assert data_equivalence(first, (env.reset(seed=5), env.step(a)), exact=True)
        wrapped = gym.wrappers.vector.RecordEpisodeStatistics(env)
        wrapped.reset(seed=0)
        for _ in range(3):
            obs, rew, term, trunc, info = wrapped.step(env.action_space.sample())
        assert rew.shape == (4,) and rew.dtype == np.float64 and obs["scan"].shape == (4, 109)
        with pytest.raises(ValueError, match="leading axis of 4"):
            env.step(np.zeros((3, 2), np.float32))
    finally:
        env.close()
    with pytest.raises(ValueError, match="num_actors"):
        RayVectorEnv(0, 2, track=ovals)


def test_es_example_script_runs_with_ray(tmp_path, monkeypatch):
    import runpy

    example = Path(__file__).resolve().parents[2] / "examples" / "train_es.py"
    out = tmp_path / "es.json"
    monkeypatch.setattr(
        sys,
        "argv",
        [
            "train_es.py",
            "--track",
            "gen-l070-w20-h0c0s0-ccw-s0",
            "--generations",
            "1",
            "--pairs",
            "2",
            "--episode-steps",
            "10",
            "--no-lap",
            "--ray",
            "auto",
            "--ray-actors",
            "2",
            "--json",
            str(out),
        ],
    )
    with pytest.raises(SystemExit) as e:
        runpy.run_path(str(example), run_name="__main__")
    assert e.value.code == 0 and len(json.loads(out.read_text())["curve"]) == 1
    assert ray.is_initialized()  # the example used the test's cluster and left it running


def test_es_on_ray_actors_gives_the_local_curve():
    from roboracer_arena.learn import ESConfig, train
    from roboracer_arena.learn.es import make_training_env

    track = "gen-l070-w20-h0c0s0-ccw-s0"
    cfg = ESConfig(generations=2, pairs=2, episode_steps=20, seed=3)
    env = make_training_env(track, cfg, ray_actors=2)
    try:
        on_ray = train(track, cfg, env=env)
    finally:
        env.close()
    local = train(track, cfg)
    assert np.array_equal(on_ray.theta, local.theta)
    assert [strip(r) for r in on_ray.curve] == [strip(r) for r in local.curve]


def test_ray_vector_env_bad_kwargs_raise_the_envs_own_error(ovals):
    with pytest.raises(Exception, match="lidar|num_beams") as e:
        RayVectorEnv(1, 2, track=ovals, sim={"lidar": {"num_beams": -3}})
    assert "Ray" not in type(e.value).__name__
