"""``roboracer-arena train`` end to end on a tiny budget: it writes a policy file that
``drive --policy`` and ``load_policy`` use, ``--resume`` continues a checkpoint exactly as
an uninterrupted run, and Ctrl-C leaves the last whole checkpoint (exit 130)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import roboracer_arena as ra
from roboracer_arena.cli import main

TRACK = "gen-l040-w12-h2c1s1-clo-s0"
TINY = ["--tracks", TRACK, "--pairs", "2", "--no-eval", "--seed", "3"]


def test_train_writes_a_policy_that_drive_uses(tmp_path, capsys):
    out = tmp_path / "p.npz"
    assert main(["train", *TINY, "--generations", "2", "--out", str(out), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["generations"] == 2 and summary["env_steps"] > 0
    assert (tmp_path / "p.curve.png").is_file()
    policy = ra.load_policy(out)
    assert policy.spec.base == "pure_pursuit" and policy.training["track_names"] == [TRACK]
    assert main(["drive", TRACK, "--policy", str(out), "--json"]) in (0, 5)
    lap = json.loads(capsys.readouterr().out)
    assert lap["track"] == TRACK and lap["distance"] > 5.0


def test_resume_continues_exactly(tmp_path):
    whole, part = tmp_path / "whole.npz", tmp_path / "part.npz"
    assert main(["train", *TINY, "--generations", "4", "--out", str(whole), "--json"]) == 0
    assert main(["train", *TINY, "--generations", "2", "--out", str(part), "--json"]) == 0
    assert main(["train", *TINY, "--generations", "4", "--out", str(part), "--resume", "--json"]) == 0
    a, b = ra.load_policy(whole), ra.load_policy(part)
    assert np.array_equal(a.theta, b.theta)
    assert [r["mean_return"] for r in a.training["curve"]] == [r["mean_return"] for r in b.training["curve"]]


def test_resume_with_other_settings_is_refused(tmp_path, capsys):
    out = tmp_path / "p.npz"
    assert main(["train", *TINY, "--generations", "1", "--out", str(out), "--json"]) == 0
    capsys.readouterr()
    assert main(["train", *TINY, "--generations", "2", "--out", str(out), "--resume", "--recipe", "plain"]) == 2
    assert "same recipe" in capsys.readouterr().err
    assert main(["train", *TINY, "--out", str(tmp_path / "none.npz"), "--resume"]) == 2


def test_ctrl_c_keeps_the_last_whole_checkpoint(tmp_path):
    out = tmp_path / "p.npz"
    cmd = [str(Path(sys.executable).parent / "roboracer-arena"), "train", *TINY, "--generations", "10000"]
    cmd += ["--checkpoint-every", "1", "--out", str(out)]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=os.environ.copy())
    deadline = time.monotonic() + 120
    while not out.exists() and time.monotonic() < deadline:
        time.sleep(0.2)
    assert out.exists(), "no checkpoint within 120 s"
    time.sleep(1.0)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "--resume continues it" in err
    done = ra.load_policy(out).training["generation"]
    assert done >= 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.npz"]  # nothing half-written beside it


def test_a_policy_trained_once_drives_a_map_the_user_brings(tmp_path, ellipse_map, capsys):
    from roboracer_arena.envs.single import RoboRacerEnv
    from roboracer_arena.learn import PolicyDriver, evaluate_policy, policy_env_kwargs

    out = tmp_path / "p.npz"
    assert main(["train", *TINY, "--generations", "2", "--out", str(out), "--json"]) == 0
    capsys.readouterr()
    assert main(["drive", str(ellipse_map), "--policy", str(out), "--json"]) == 0
    cli_lap = json.loads(capsys.readouterr().out)["lap_times"][0]
    policy = ra.load_policy(out)
    (lap,) = evaluate_policy(policy, [str(ellipse_map)])
    assert lap["clean_lap"] and abs(lap["lap_time"] - cli_lap) < 0.2
    env = RoboRacerEnv(track=str(ellipse_map), **policy_env_kwargs(policy))
    driver = PolicyDriver(env, policy)
    obs, _ = env.reset(seed=0)
    for _ in range(40):
        obs, _, terminated, _, info = env.step(driver.act(obs))
        assert not terminated
    assert info["progress"] > 3.0
