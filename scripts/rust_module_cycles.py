#!/usr/bin/env python3
"""Fail when the Rust core's modules depend on each other in a cycle.

A module is one source file (``sim/lidar.rs`` is ``sim::lidar``; ``sim/mod.rs`` is ``sim``).
An edge ``a -> b`` is a path in ``a``'s non-test code that names ``b``: ``use crate::…``,
``use super::…`` or an inline ``crate::…`` / ``super::…`` path. Names a ``mod.rs``
re-exports (``pub use child::{Name}``) resolve to the child that defines them, so a
module that imports ``crate::sim::Track`` depends on ``sim::track``, not on ``sim``.
Test code (``#[cfg(test)]`` modules and ``*tests.rs`` files) is left out: tests may
reach across layers.

Usage: ``python3 scripts/rust_module_cycles.py [CRATE_SRC]`` (default
``crates/arena_core/src``). Prints each cycle and exits 1, or prints a one-line summary.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

PATH = re.compile(r"\b(crate|super)((?:::[A-Za-z_][A-Za-z0-9_]*)+)")
USE_GROUP = re.compile(r"\buse\s+(crate|super)((?:::[A-Za-z_][A-Za-z0-9_]*)*)::\{([^;]*)\};", re.S)
REEXPORT = re.compile(r"\bpub\s+use\s+([a-z_][a-z0-9_]*)::\{?([^;]*?)\}?;", re.S)


def module_name(src: Path, path: Path) -> tuple[str, ...]:
    parts = path.relative_to(src).with_suffix("").parts
    if parts[-1] in ("mod", "lib"):
        parts = parts[:-1]
    return tuple(parts)


def non_test_code(text: str) -> str:
    """The text before the first ``#[cfg(test)]`` (test modules sit at the end)."""
    text = re.sub(r"//[^\n]*", "", text)
    cut = text.find("#[cfg(test)]")
    return text if cut < 0 else text[:cut]


def main(argv: list[str]) -> int:
    src = Path(argv[1] if len(argv) > 1 else "crates/arena_core/src")
    files = {
        module_name(src, p): p
        for p in sorted(src.rglob("*.rs"))
        if not (p.stem.endswith("tests") or p.stem == "tests")
    }
    code = {m: non_test_code(p.read_text()) for m, p in files.items()}
    # (parent module, re-exported name) -> child module that defines it
    reexports: dict[tuple[tuple[str, ...], str], tuple[str, ...]] = {}
    for m, text in code.items():
        if files[m].stem not in ("mod", "lib"):
            continue
        for child, names in REEXPORT.findall(text):
            for name in re.findall(r"[A-Za-z_][A-Za-z0-9_]*", names):
                if m + (child,) in files:
                    reexports[(m, name)] = m + (child,)

    def resolve(base: tuple[str, ...], segments: list[str]) -> tuple[str, ...] | None:
        mod = base
        for i, seg in enumerate(segments):
            if mod + (seg,) in files:
                mod = mod + (seg,)
                continue
            return reexports.get((mod, seg), mod)
        return mod

    def anchor(m: tuple[str, ...], root: str) -> tuple[str, ...]:
        if root == "crate":
            return ()
        # `super` of a file module is its folder's module; of a mod.rs, the folder's parent.
        own = m if files[m].stem in ("mod", "lib") else m
        return own[:-1]

    edges: dict[tuple[str, ...], set[tuple[str, ...]]] = {m: set() for m in files}
    for m, text in code.items():
        found: list[tuple[str, list[str]]] = []
        for root, prefix, group in USE_GROUP.findall(text):
            pre = [s for s in prefix.split("::") if s]
            for item in re.split(r",", group):
                first = re.findall(r"[A-Za-z_][A-Za-z0-9_]*", item)
                if first:
                    found.append((root, pre + [first[0]]))
        for root, rest in PATH.findall(USE_GROUP.sub("", text)):
            found.append((root, [s for s in rest.split("::") if s]))
        for root, segs in found:
            while segs and segs[0] == "super":
                segs = segs[1:]
                root = "super"
            target = resolve(anchor(m, root), segs)
            if target is not None and target != m and target != () and not m[: len(target)] == target:
                edges[m].add(target)

    cycles = strongly_connected(edges)
    if cycles:
        for c in cycles:
            print("cycle: " + " <-> ".join("::".join(x) for x in sorted(c)))
        return 1
    print(f"rust module cycles: none among {len(files)} modules of {src}")
    return 0


def strongly_connected(edges: dict[tuple[str, ...], set[tuple[str, ...]]]) -> list[set[tuple[str, ...]]]:
    """Tarjan's algorithm; returns the components of more than one module."""
    index: dict[tuple[str, ...], int] = {}
    low: dict[tuple[str, ...], int] = {}
    stack: list[tuple[str, ...]] = []
    on: set[tuple[str, ...]] = set()
    out: list[set[tuple[str, ...]]] = []
    sys.setrecursionlimit(10_000)

    def visit(v: tuple[str, ...]) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = set()
            while True:
                w = stack.pop()
                on.discard(w)
                comp.add(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(comp)

    for v in list(edges):
        if v not in index:
            visit(v)
    return out


if __name__ == "__main__":
    sys.exit(main(sys.argv))
