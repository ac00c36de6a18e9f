#!/usr/bin/env python3
"""Fail on function-local imports of the package's own modules and on private access
across subpackages (a `make lint` gate, issue #24 "floors that hold").

Two rules, read from the AST of every module under ``python/roboracer_arena``:

* **local-import**: an ``import`` / ``from … import`` inside a function body whose module
  is the package's own (relative, or ``roboracer_arena…``). Such an import hides a
  dependency from the reader and, when it closes a cycle, from the floors. An import stays
  local only when the imported module needs an optional dependency (an extra) or keeps
  the CLI's start-up fast; each such (file, module) pair is in :data:`ALLOWED_LOCAL` with
  its reason.
* **private-access**: a private name (one leading underscore, not a dunder) reached from
  another subpackage: ``from ..track import _from_corridor`` in ``envs/``, or an attribute
  ``obj._name`` (or ``getattr(obj, "_name")``, ``hasattr(obj, "_name")``) where ``obj`` is
  not ``self`` / ``cls`` and the module defines no ``_name`` of its own
  (``env.unwrapped._batch``). A subpackage is the first path
  component below the package (``envs``, ``library``; a top-level module is its own). The
  compiled binding ``_core`` is the one door to the core and is public in all but name.

An allow-list entry that no longer matches anything is an error too, so the list only
shrinks. Usage: ``python3 scripts/import_hygiene.py [PACKAGE_DIR]`` (default
``python/roboracer_arena``). Prints each finding as ``path:line: rule: detail`` and exits
1, else a one-line summary and 0.
"""

from __future__ import annotations

import ast
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

PACKAGE = "roboracer_arena"
#: Subtrees not checked, with the reason.
SKIPPED: dict[str, str] = {}
#: Private names that are public in all but name: the binding, and NamedTuple's API.
PUBLIC_PRIVATES = {"_core", "_asdict", "_replace", "_fields", "_make"}

# Reasons shared by several entries. Start-up: `roboracer-arena --help` builds every
# sub-command's parser (cli/__init__.make_parser), so a module-level import in cli/ is paid
# by every command; these load pxr, PIL or the env stack only when their command runs.
_CLI = "CLI start-up: loads pxr/PIL/the env stack only when the sub-command runs"

#: (file relative to the package, imported module as written) -> why it stays local.
ALLOWED_LOCAL: dict[tuple[str, str], str] = {
    ("cli/drive.py", "..ros2.episode_recorder"): _CLI + " (--mcap: the ROS 2 recorder)",
    ("cli/drive.py", "..learn"): _CLI + " (--policy: the policy file and the env stack)",
    ("cli/drive.py", ".drive_physx"): _CLI + " (--engine physx: ovphysx, pxr)",
    ("cli/drive_physx.py", "..drivers"): _CLI + " (the env stack)",
    ("cli/drive_physx.py", "..envs.env_config"): _CLI + " (the env stack)",
    ("cli/drive_physx.py", "..physx"): _CLI + " (physx.available() before loading ovphysx)",
    ("cli/drive_physx.py", "..physx.laps"): _CLI + " (ovphysx, pxr; only with the [physx] extra)",
    ("cli/drive_physx.py", "..learn"): _CLI + " (--policy: the policy file and the env stack)",
    ("cli/drive_physx.py", "..learn.runner"): _CLI + " (--policy: the env stack)",
    ("cli/ros2.py", "..learn"): _CLI + " (--policy: the policy file and the env stack)",
    ("cli/ros2.py", "..ros2.policy_node"): _CLI + " (--policy: cyclonedds, the env stack)",
    ("cli/train.py", "..learn.recipe"): _CLI + " (learn: the env stack)",
    ("cli/train.py", "..catalog.catalog_file"): _CLI + " (reads the catalog only when training)",
    ("cli/train.py", "..learn.evaluate"): _CLI + " (learn: the env stack)",
    ("cli/train.py", "..learn.policy_file"): _CLI + " (learn: the env stack)",
    ("cli/train.py", "..learn.trainer"): _CLI + " (learn: the env stack)",
    ("cli/train.py", "..learn.curve"): _CLI + " (render: PIL)",
    ("cli/generate.py", "..builder"): "guarded by except ImportError: a missing USD builder is bad input, exit 2",
    ("cli/generate.py", "..maps.occupancy"): "guarded by except ImportError together with the builder (--build)",
    ("cli/physx_check.py", "..physx.check"): _CLI + " (the check loads pxr and the env stack, ~1 s)",
    ("cli/preview.py", "..render.formats"): _CLI + " (render: PIL)",
    ("cli/preview.py", "..render.still3d"): _CLI + " (render: PIL)",
    ("cli/preview.py", "..render.preview"): _CLI + " (render: PIL, pxr for a stage)",
    ("cli/raceline.py", "..raceline.export"): _CLI + " (raceline: scipy)",
    ("cli/raceline.py", "..raceline.limits"): _CLI + " (raceline: scipy)",
    ("cli/raceline.py", "..raceline.measure"): _CLI + " (raceline: scipy, the env stack)",
    ("cli/raceline.py", "..raceline.plan"): _CLI + " (raceline: scipy)",
    ("cli/raceline.py", "..raceline.source"): _CLI + " (raceline: scipy)",
    ("cli/raceline.py", "..render.formats"): _CLI + " (render: PIL)",
    ("cli/raceline.py", "..render.raceline_view"): _CLI + " (render: PIL, pxr)",
    ("cli/raceline.py", "..catalog.catalog_file"): _CLI + " (raceline --catalog: the library job)",
    ("cli/raceline.py", "..library.racelines"): _CLI + " (raceline --catalog: scipy, the env stack)",
    ("cli/drive.py", "..raceline.driver"): _CLI + " (--raceline: scipy)",
    ("cli/tracks.py", "..library.racelines"): _CLI + " (verify --raceline plans racelines: scipy)",
    ("cli/ros2.py", "..ros2.bridge"): _CLI + " (the bridge drives the env stack)",
    ("cli/tracks.py", "..library.verify"): _CLI + " (verify builds USD and drives laps)",
    ("cli/tracks.py", "..library.open_maps"): _CLI + " (open maps are verified: pxr, the env stack)",
    ("cli/tracks.py", "..library.sheet"): _CLI + " (the contact sheet: PIL)",
    ("cli/tracks.py", "..library.index"): _CLI + " (building the catalog verifies open maps)",
    ("cli/tracks.py", "..library.spec_sweep_run"): _CLI + " (the sweep builds and verifies tracks)",
    ("builder.py", ".usd"): "usd loads pxr (~0.5 s); builder is imported by the CLI at start-up",
    ("builder.py", ".usd.stage"): "usd loads pxr (~0.5 s); builder is imported by the CLI at start-up",
    ("builder.py", ".usd.vehicle"): "usd loads pxr (~0.5 s); builder is imported by the CLI at start-up",
    ("builder.py", ".usd.metadata"): "usd loads pxr (~0.5 s); builder is imported by the CLI at start-up",
    ("builder.py", ".usd.materials"): "usd loads pxr (~0.5 s); builder is imported by the CLI at start-up",
    ("maps/corridor.py", ".gaps"): "gaps needs scipy (ndimage): only close_gaps_m pays; the envs import no scipy",
    ("distributed/__init__.py", ".ray_executor"): "PEP 562 lazy attribute: the Ray classes load on first use",
    ("distributed/__init__.py", ".ray_vector"): "PEP 562 lazy attribute: the Ray classes load on first use",
    ("drivers.py", ".render.formats"): "render loads PIL, only for video; drivers is imported by the CLI at start-up",
    (
        "drivers.py",
        ".render.drive_view",
    ): "render loads PIL, only for video; drivers is imported by the CLI at start-up",
    ("drivers.py", ".render.video"): "render loads PIL, only for video; drivers is imported by the CLI at start-up",
    ("envs/__init__.py", "..track.drivable"): "PEP 562 lazy attribute: `import roboracer_arena` (gym ids) stays light",
    ("envs/single.py", "..render.sim_view"): "render (PIL) loads only when render() is called, not for gym.make",
    ("envs/vector.py", "..render.sim_view"): "render (PIL) loads only when render() is called, not for gym.make",
    ("physx/__init__.py", ".check"): "PEP 562 lazy attribute: physx.available() must not load pxr and the envs",
    ("ros2/episode_recorder.py", "..envs.single"): "the recorder wraps any env; ROS 2 users need not load the envs",
}

#: (file relative to the package, private name) -> why it is reached from outside.
ALLOWED_PRIVATE: dict[tuple[str, str], str] = {
    (
        "bench/env.py",
        "_batch",
    ): "the bench times the env's native calls by wrapping its simulator (instrumentation only)",
    ("cli/generate.py", "_actions"): "argparse has no public way to find an added action",
    ("ros2/dds.py", "_ref"): "cyclonedds' raw write needs the writer's handle; falls back to the public write",
}


@dataclass(frozen=True)
class Finding:
    path: str
    line: int
    rule: str
    detail: str

    def __str__(self) -> str:
        return f"{self.path}:{self.line}: {self.rule}: {self.detail}"


def _is_private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__") and name not in PUBLIC_PRIVATES


def _module_name(node: ast.Import | ast.ImportFrom) -> list[str]:
    """The modules an import names, as written (``..track``, ``roboracer_arena.maps.occupancy``)."""
    if isinstance(node, ast.Import):
        return [a.name for a in node.names]
    return ["." * node.level + (node.module or "")]


def _is_own(module: str) -> bool:
    return module.startswith(".") or module == PACKAGE or module.startswith(PACKAGE + ".")


def _absolute(module: str, rel: Path) -> list[str]:
    """``module`` (as written in file ``rel``) as a dotted path below the package."""
    if not module.startswith("."):
        return module.split(".")[1:]
    level = len(module) - len(module.lstrip("."))
    # ``pkg/mod.py`` and ``pkg/__init__.py`` both resolve ``.`` to ``pkg``.
    base = list(rel.with_suffix("").parts)[:-1]
    base = base[: len(base) - (level - 1)] if level > 1 else base
    tail = module.lstrip(".")
    return base + (tail.split(".") if tail else [])


def _subpackage(parts: list[str]) -> str:
    return parts[0] if parts else ""


def _local_imports(tree: ast.Module) -> Iterator[ast.Import | ast.ImportFrom]:
    """Import nodes inside a function body (at any depth)."""

    def walk(node: ast.AST, in_function: bool) -> Iterator[ast.Import | ast.ImportFrom]:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.Import, ast.ImportFrom)) and in_function:
                yield child
            inner = in_function or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
            yield from walk(child, inner)

    yield from walk(tree, False)


def _own_names(tree: ast.Module) -> set[str]:
    """Every name the module defines or binds itself (functions, classes, variables,
    attributes set on any object, arguments, import aliases), so ``obj._x`` with ``_x``
    among them is the module's own business (``other._state`` in ``__eq__``)."""
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            names.add(node.id)
        elif isinstance(node, ast.Attribute) and isinstance(node.ctx, (ast.Store, ast.Del)):
            names.add(node.attr)
        elif isinstance(node, ast.arg):
            names.add(node.arg)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
        elif isinstance(node, ast.alias):
            names.add(node.asname or node.name.split(".")[0])
    return names


def check_file(path: Path, root: Path) -> list[Finding]:
    """Findings in one module, before the allow-lists."""
    rel = path.relative_to(root)
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    here = _subpackage(list(rel.with_suffix("").parts))
    out: list[Finding] = []
    for node in _local_imports(tree):
        for module in _module_name(node):
            if _is_own(module):
                out.append(Finding(rel.as_posix(), node.lineno, "local-import", module))
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and _is_own("." * node.level + (node.module or "")):
            target = _absolute("." * node.level + (node.module or ""), rel)
            for alias in node.names:
                parts = target + [alias.name]
                if _is_private(alias.name) and _subpackage(parts) != here:
                    out.append(Finding(rel.as_posix(), node.lineno, "private-access", alias.name))
    own = _own_names(tree)
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Attribute)
            and isinstance(node.ctx, ast.Load)
            and _is_private(node.attr)
            and node.attr not in own
            and not (isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"))
        ):
            out.append(Finding(rel.as_posix(), node.lineno, "private-access", node.attr))
        elif (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Name)
            and node.func.id in ("getattr", "hasattr")
            and len(node.args) >= 2
            and isinstance(node.args[1], ast.Constant)
            and isinstance(node.args[1].value, str)
            and _is_private(node.args[1].value)
            and node.args[1].value not in own
            and not (isinstance(node.args[0], ast.Name) and node.args[0].id in ("self", "cls"))
        ):
            out.append(Finding(rel.as_posix(), node.lineno, "private-access", node.args[1].value))
    return out


def _key(f: Finding) -> tuple[str, str]:
    return (f.path, f.detail)


def check(
    root: Path,
    allowed_local: dict[tuple[str, str], str] | None = None,
    allowed_private: dict[tuple[str, str], str] | None = None,
) -> list[Finding]:
    """Every finding under ``root`` not allowed, plus every allow-list entry left unused
    (the allow-lists default to this file's)."""
    findings: list[Finding] = []
    for path in sorted(root.rglob("*.py")):
        if path.relative_to(root).parts[0] in SKIPPED:
            continue
        findings.extend(check_file(path, root))
    allowed = {
        "local-import": ALLOWED_LOCAL if allowed_local is None else allowed_local,
        "private-access": ALLOWED_PRIVATE if allowed_private is None else allowed_private,
    }
    used: set[tuple[str, tuple[str, str]]] = set()
    out: list[Finding] = []
    for f in findings:
        if _key(f) in allowed[f.rule]:
            used.add((f.rule, _key(f)))
        else:
            out.append(f)
    for rule, table in allowed.items():
        for key in table:
            if (rule, key) not in used:
                out.append(Finding(key[0], 0, "stale-allow", f"{rule} {key[1]} no longer occurs: drop it"))
    return out


def main(argv: list[str]) -> int:
    root = Path(argv[1] if len(argv) > 1 else "python/roboracer_arena")
    if not root.is_dir():
        print(f"import_hygiene: {root}: no such directory", file=sys.stderr)
        return 2
    out = check(root)
    for f in out:
        print(f)
    if out:
        print(f"import_hygiene: {len(out)} finding(s) in {root}", file=sys.stderr)
        return 1
    n_allowed = len(ALLOWED_LOCAL) + len(ALLOWED_PRIVATE)
    print(
        f"import_hygiene: {root}: no function-local own import, no private cross-package access ({n_allowed} allowed)"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
