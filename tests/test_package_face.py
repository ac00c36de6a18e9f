"""The root package is a face (issue #37 "floors without exceptions"): ``import
roboracer_arena`` loads nothing of the package but the leaf ``registration``, registers the
gym id, and every public name still resolves on first use; the import floors need no
ignored import."""

from __future__ import annotations

import configparser
import subprocess
import sys
from pathlib import Path

import gymnasium as gym

import roboracer_arena as ra
from roboracer_arena.envs.env_config import EnvConfig
from roboracer_arena.registration import ENV_ID, REGISTERED_MAX_EPISODE_STEPS

ROOT = Path(__file__).resolve().parents[1]
PUBLIC = ["load_map", "build_environment", "generate_track", "parse_request", "TrackSpec", "load_policy"]


def test_import_loads_only_the_registration_leaf() -> None:
    code = (
        "import sys, roboracer_arena, gymnasium\n"
        "print(sorted(m for m in sys.modules if m.startswith('roboracer_arena')))\n"
        "print('RoboRacerArena-v0' in gymnasium.registry)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split("\n")
    assert out[0] == "['roboracer_arena', 'roboracer_arena.registration']"
    assert out[1] == "True"


def test_public_names_resolve_lazily() -> None:
    for name in PUBLIC:
        assert callable(getattr(ra, name)), name
    assert ra.errors.ArenaError.__name__ == "ArenaError"
    assert isinstance(ra.__version__, str) and ra.__version__
    assert set(PUBLIC) <= set(dir(ra)) and set(PUBLIC) <= set(ra.__all__)


def test_registered_limit_is_the_env_configs_default() -> None:
    assert REGISTERED_MAX_EPISODE_STEPS == EnvConfig().max_episode_steps
    assert gym.spec(ENV_ID).max_episode_steps == REGISTERED_MAX_EPISODE_STEPS
    assert gym.spec(ENV_ID).entry_point == "roboracer_arena.envs.single:RoboRacerEnv"


def test_the_floors_ignore_no_import() -> None:
    config = configparser.ConfigParser()
    config.read(ROOT / ".importlinter")
    for section in config.sections():
        assert not config.get(section, "ignore_imports", fallback="").strip(), section
