"""Runs hostile cases in one process under a memory cap; the fuzz tests start it.

Reads a JSON list of cases on stdin. Each case is run in a fresh directory:

* ``files``: name → ``{"text": ...}`` | ``{"b64": ...}`` | ``{"fifo": true}`` |
  ``{"dir": true}`` | ``{"symlink": target}`` written there first;
* ``env``: environment variables set for the case only;
* then either ``argv`` (the CLI, ``roboracer_arena.cli.main``) or ``api`` (a name from
  :data:`API` with ``args``) is run with stderr captured.

One JSON line per case goes to stdout (flushed, preceded by a ``START id`` line so a
crash names its case): the exit code (``api`` cases: 0, or 2 for an ``ArenaError``),
stderr, the repr of any escaping exception (a traceback in real use), and the files
left in the directory.
"""

from __future__ import annotations

import base64
import contextlib
import io
import json
import os
import sys
import tempfile
import traceback
from pathlib import Path

import numpy as np


def _api_analyse_curve(points, corner_radius=1.0, exclude_m=1.0):
    from roboracer_arena import _core

    _core.analyse_curve(np.asarray(points, dtype=np.float64).reshape(-1, 2), corner_radius, exclude_m)


def _api_polyline(fn, points, args=()):
    from roboracer_arena import _core

    getattr(_core, fn)(np.asarray(points, dtype=np.float64).reshape(-1, 2), *args)


def _api_distance_transform(h, w):
    from roboracer_arena import _core

    # A zero-stride view: no memory behind it, so only the core's door can refuse it.
    _core.distance_transform(np.broadcast_to(np.zeros((1, 1), dtype=bool), (h, w)))


def _api_extract_corridor(map_yaml, params):
    from roboracer_arena.maps.corridor import extract_corridor

    extract_corridor(map_yaml, params=params)


def _api_load_map(path):
    from roboracer_arena.maps.occupancy import load_map

    load_map(path)


def _api_measure(resolution, origin):
    from roboracer_arena import _core

    _core.measure_map(np.full((20, 20), 254, np.uint8), resolution, tuple(origin))


def _api_env(kwargs, options=None, actions=(), vector=0):
    """Make a ``RoboRacerArena-v0`` env (``vector`` > 0: a native vector env of that many
    envs) with hostile ``kwargs``, reset it with hostile ``options`` and step ``actions``."""
    import gymnasium as gym

    track = "gen-l040-w12-h2c1s1-clo-s0"
    if vector:
        env = gym.make_vec("RoboRacerArena-v0", num_envs=vector, track=track, **kwargs)
    else:
        env = gym.make("RoboRacerArena-v0", track=track, **kwargs)
    try:
        env.reset(seed=0, options=options)
        for a in actions:
            env.step(a)
    finally:
        env.close()


API = {
    "env": _api_env,
    "analyse_curve": _api_analyse_curve,
    "distance_transform": _api_distance_transform,
    "extract_corridor": _api_extract_corridor,
    "load_map": _api_load_map,
    "measure_map": _api_measure,
    "polyline": _api_polyline,
}


def _materialise(root: Path, files: dict) -> None:
    for name, spec in files.items():
        p = root / name
        p.parent.mkdir(parents=True, exist_ok=True)
        if "text" in spec:
            p.write_text(spec["text"], encoding=spec.get("encoding", "utf-8"))
        elif "b64" in spec:
            p.write_bytes(base64.b64decode(spec["b64"]))
        elif spec.get("fifo"):
            os.mkfifo(p)
        elif spec.get("dir"):
            p.mkdir(exist_ok=True)
        elif "symlink" in spec:
            os.symlink(spec["symlink"], p)


def run_case(case: dict) -> dict:
    from roboracer_arena.cli import main
    from roboracer_arena.errors import ArenaError

    with tempfile.TemporaryDirectory(prefix="fuzz-") as d:
        root = Path(d)
        _materialise(root, case.get("files", {}))
        before = {p.relative_to(root) for p in root.rglob("*")}
        err, exc, code = io.StringIO(), None, None
        cwd, env = os.getcwd(), dict(os.environ)
        os.environ.update(case.get("env", {}))
        os.chdir(root)
        try:
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                if "argv" in case:
                    try:
                        code = main(case["argv"])
                    except SystemExit as e:  # argparse usage errors
                        code = e.code if isinstance(e.code, int) else 2
                else:
                    try:
                        API[case["api"]](**case.get("args", {}))
                        code = 0
                    except ArenaError as e:
                        code = 2
                        err.write(f"{type(e).__name__}: {e}\n")
        except BaseException as e:
            exc = "".join(traceback.format_exception(e))[-2000:]
        finally:
            os.chdir(cwd)
            os.environ.clear()
            os.environ.update(env)
        left = sorted(str(q) for q in (p.relative_to(root) for p in root.rglob("*")) if q not in before)
        return {"id": case["id"], "code": code, "err": err.getvalue()[-2000:], "exc": exc, "left": left}


def main() -> None:
    for case in json.load(sys.stdin):
        print(f"START {case['id']}", flush=True)
        print(json.dumps(run_case(case)), flush=True)


if __name__ == "__main__":
    main()
