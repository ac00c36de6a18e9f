"""``import roboracer_arena`` registers RoboRacerArena-v0 with gymnasium directly, in either
import order, and leaves no import hook behind (a fresh interpreter per case)."""

from __future__ import annotations

import subprocess
import sys

import pytest

CHECK = """
import sys
{imports}
import gymnasium
assert "RoboRacerArena-v0" in gymnasium.registry, "not registered"
hooks = [f for f in sys.meta_path if type(f).__module__.startswith("roboracer_arena")]
assert not hooks, hooks
print("ok")
"""


@pytest.mark.parametrize(
    "imports", ["import roboracer_arena\nimport gymnasium", "import gymnasium\nimport roboracer_arena"]
)
def test_import_registers_the_env_without_a_hook(imports):
    out = subprocess.run(
        [sys.executable, "-c", CHECK.format(imports=imports)], capture_output=True, text=True, timeout=120
    )
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


def test_the_module_prefix_form_works_too():
    code = "import gymnasium as g; e = g.make('roboracer_arena:RoboRacerArena-v0', track='gen-l040-w12-h1c1s0-ccw-s0'); print('ok')"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr
