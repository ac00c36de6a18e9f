"""scripts/import_hygiene.py: the `make lint` gate against function-local imports of the
package's own modules and private access across subpackages.

Small packages written to a temporary directory exercise each rule and its allow-list;
the real package must pass, and a local import added to it must be found.
"""

from __future__ import annotations

import importlib.util
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "scripts" / "import_hygiene.py"
PACKAGE = ROOT / "python" / "roboracer_arena"

pytestmark = pytest.mark.skipif(not SCRIPT.is_file(), reason="needs the source checkout (scripts/)")


def _load():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("import_hygiene", SCRIPT)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules["import_hygiene"] = mod
    spec.loader.exec_module(mod)
    return mod


ih = _load()


def package(tmp_path: Path, files: dict[str, str]) -> Path:
    root = tmp_path / "roboracer_arena"
    for rel, text in {"__init__.py": "", **files}.items():
        p = root / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    return root


def found(root: Path, **allowed: dict[tuple[str, str], str]) -> set[tuple[str, str, str]]:
    return {(f.path, f.rule, f.detail) for f in ih.check(root, allowed.get("local", {}), allowed.get("private", {}))}


def test_local_imports_of_own_modules_are_found(tmp_path: Path) -> None:
    root = package(
        tmp_path,
        {
            "a.py": "import json\n\ndef f():\n    from . import b\n    import numpy\n    return b, numpy, json\n",
            "b.py": "def g():\n    import roboracer_arena.a\n\n    class C:\n        def h(self):\n            from .a import f\n",
            "c.py": "from .a import f\n\ndef k():\n    return f\n",
        },
    )
    assert found(root) == {
        ("a.py", "local-import", "."),
        ("b.py", "local-import", "roboracer_arena.a"),
        ("b.py", "local-import", ".a"),
    }


def test_type_checking_and_module_level_imports_pass(tmp_path: Path) -> None:
    root = package(
        tmp_path,
        {
            "a.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .b import g\ntry:\n    from .b import g\nexcept ImportError:\n    g = None\n",
            "b.py": "def g():\n    pass\n",
        },
    )
    assert found(root) == set()


def test_private_names_across_subpackages_are_found(tmp_path: Path) -> None:
    root = package(
        tmp_path,
        {
            "envs/__init__.py": "",
            "envs/batch.py": "class B:\n    def __init__(self):\n        self._row = 1\n",
            "envs/single.py": "from .batch import _helper\n\ndef f(b):\n    return b._row\n",
            "track.py": "def _from_corridor():\n    pass\n",
            "lib/__init__.py": "",
            "lib/x.py": (
                "from .. import _core\nfrom ..track import _from_corridor\n"
                "def f(env, nt):\n    return env.unwrapped._batch, nt._asdict(), _core\n"
            ),
            "lib/y.py": "class Y:\n    def __init__(self):\n        self._state = 0\n\n    def same(self, other):\n        return other._state == self._state\n",
        },
    )
    assert found(root) == {
        ("lib/x.py", "private-access", "_from_corridor"),
        ("lib/x.py", "private-access", "_batch"),
        # within envs the import passes; the attribute is not this module's own
        ("envs/single.py", "private-access", "_row"),
    }


def test_allow_lists_excuse_and_stale_entries_fail(tmp_path: Path) -> None:
    root = package(tmp_path, {"a.py": "def f():\n    from . import b\n", "b.py": "def g(x):\n    return x._secret\n"})
    assert found(root, local={("a.py", "."): "why"}, private={("b.py", "_secret"): "why"}) == set()
    stale = found(root, local={("a.py", "."): "why", ("gone.py", ".x"): "why"}, private={("b.py", "_secret"): "why"})
    assert stale == {("gone.py", "stale-allow", "local-import .x no longer occurs: drop it")}


def test_the_package_passes_and_a_new_local_import_fails(tmp_path: Path) -> None:
    assert ih.check(PACKAGE) == []
    copy = tmp_path / "roboracer_arena"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("*.so", "*.pyd", "__pycache__", "tracks", "data"))
    target = copy / "envs" / "track_pool.py"
    target.write_text(target.read_text() + "\n\ndef _late():\n    from ..maps import load_map\n\n    return load_map\n")
    out = subprocess.run([sys.executable, str(SCRIPT), str(copy)], capture_output=True, text=True)
    assert out.returncode == 1
    assert "envs/track_pool.py" in out.stdout and "local-import: ..maps" in out.stdout


def test_private_reads_through_getattr_are_found(tmp_path: Path) -> None:
    root = package(
        tmp_path,
        {
            "ros2/__init__.py": "",
            "ros2/source.py": (
                "def f(env):\n    return getattr(env, '_batch', None), hasattr(env, '_sim'), getattr(env, 'sim')\n"
            ),
            "drivers.py": "class D:\n    def g(self):\n        return getattr(self, '_slots')\n",
        },
    )
    assert found(root) == {("ros2/source.py", "private-access", "_batch"), ("ros2/source.py", "private-access", "_sim")}
