#!/usr/bin/env python3
"""Fail when the Rust core's modules depend on each other in a cycle (a `make lint` gate).

A module is one source file (``sim/lidar.rs`` is ``sim::lidar``; ``sim/mod.rs`` is ``sim``).
An edge ``a -> b`` is a path in ``a``'s non-test code that names ``b``: every ``use``
(``crate::``, ``super::``, ``self::``, a child module, nested ``{…}`` groups, ``as``
renames, ``pub use`` re-exports) and every path in a body (``crate::x::f()``,
``super::y::Z``, or ``m::f()`` through a ``use``-imported module ``m``). A name that a
module re-exports (``pub use child::Name``, ``pub use child::*``) resolves to the module
that defines it, so importing ``crate::sim::Track`` depends on ``sim::shared_track``, not on
``sim``. Test code (``#[cfg(test)]`` items, modules declared under it, ``*tests.rs``
files) is left out: tests may reach across layers. Comments and string literals are
blanked first, so a path in a doc comment or a message is not an edge.

Usage: ``python3 scripts/rust_module_cycles.py [CRATE_SRC]`` (default
``crates/arena_core/src``). Prints each cycle and exits 1, else a one-line summary and 0.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

Module = tuple[str, ...]
IDENT = r"[A-Za-z_][A-Za-z0-9_]*"
# Comments, then string, byte-string, raw-string and char literals (lifetimes never
# close with a quote one character later, so they are left alone).
NOISE = re.compile(
    r"//[^\n]*|/\*.*?\*/|\bb?r(#*)\".*?\"\1|b?\"(?:\\.|[^\"\\])*\"|b?'(?:\\.|[^\\'\n])'",
    re.S,
)
USE = re.compile(r"\buse\s+([^;]*);")
BODY_PATH = re.compile(rf"(?<![A-Za-z0-9_:])((?:{IDENT}\s*::\s*)+{IDENT})")
DEFINES = re.compile(rf"\b(?:fn|struct|enum|union|trait|type|const|static|mod|macro_rules!)\s+({IDENT})")
TEST_ATTR = re.compile(r"#\[cfg\(test\)\]")
ATTR = re.compile(r"\s*#\[[^\]]*\]")
MOD_DECL = re.compile(rf"\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+({IDENT})\s*;")


def module_name(src: Path, path: Path) -> Module:
    parts = path.relative_to(src).with_suffix("").parts
    if parts[-1] in ("mod", "lib"):
        parts = parts[:-1]
    return tuple(parts)


def blank(text: str) -> str:
    """``text`` without comments and literal contents (strings become ``""``)."""

    def keep_quotes(m: re.Match[str]) -> str:
        s = m.group(0)
        return " " if s.startswith("/") else '""'

    return NOISE.sub(keep_quotes, text)


def drop_test_items(text: str) -> tuple[str, list[str]]:
    """``text`` without ``#[cfg(test)]`` items, and the names of ``mod x;`` among them."""
    test_mods: list[str] = []
    while m := TEST_ATTR.search(text):
        end = m.end()
        while a := ATTR.match(text, end):
            end = a.end()
        if d := MOD_DECL.match(text, end):
            test_mods.append(d.group(1))
        semi, brace = text.find(";", end), text.find("{", end)
        if brace < 0 or 0 <= semi < brace:
            stop = len(text) if semi < 0 else semi + 1
        else:
            depth, stop = 0, len(text)
            for i in range(brace, len(text)):
                depth += {"{": 1, "}": -1}.get(text[i], 0)
                if depth == 0:
                    stop = i + 1
                    break
        text = text[: m.start()] + text[stop:]
    return text, test_mods


def use_tree(tree: str) -> list[tuple[list[str], str]]:
    """The (path, bound name) pairs of one ``use`` tree; the name is ``*`` for a glob."""
    tokens = re.findall(rf"::|[{{}},*]|{IDENT}", tree)
    while tokens and tokens[0] == "::":  # `use ::std::…`: an external crate
        tokens = tokens[1:]
    out: list[tuple[list[str], str]] = []

    def parse(i: int, prefix: list[str]) -> int:
        path = list(prefix)
        while i < len(tokens):
            tok = tokens[i]
            if tok == "{":
                i += 1
                while i < len(tokens) and tokens[i] != "}":
                    i = parse(i, path)
                    if i < len(tokens) and tokens[i] == ",":
                        i += 1
                return i + 1
            if tok == "*":
                out.append((path, "*"))
                return i + 1
            path.append(tok)
            i += 1
            if i < len(tokens) and tokens[i] == "::":
                i += 1
                continue
            if path[-1] == "self":  # `use a::b::{self}` binds `b`
                path = path[:-1]
            name = path[-1] if path else ""
            if i + 1 < len(tokens) and tokens[i] == "as":
                name, i = tokens[i + 1], i + 2
            out.append((path, name))
            return i
        return i

    parse(0, [])
    return out


class Crate:
    """The module graph of one crate's source tree."""

    def __init__(self, src: Path) -> None:
        raw = {module_name(src, p): p for p in sorted(src.rglob("*.rs"))}
        code: dict[Module, str] = {}
        test_modules: set[Module] = set()
        for m, p in raw.items():
            code[m], mods = drop_test_items(blank(p.read_text()))
            test_modules.update(m + (name,) for name in mods)
        self.files = {m for m, p in raw.items() if m not in test_modules and not p.stem.endswith("tests")}
        self.code = {m: code[m] for m in self.files}
        self.defs = {m: set(DEFINES.findall(t)) for m, t in self.code.items()}
        # Per module: names bound by `use` (name -> absolute path) and glob imports.
        self.binds: dict[Module, dict[str, list[str]]] = {m: {} for m in self.files}
        self.globs: dict[Module, list[list[str]]] = {m: [] for m in self.files}
        self.uses: dict[Module, list[list[str]]] = {m: [] for m in self.files}
        for m in sorted(self.files, key=len):  # parents first: children may use their names
            for tree in USE.findall(self.code[m]):
                for path, name in use_tree(tree):
                    full = self.absolute(m, path)
                    if full is None:
                        continue
                    self.uses[m].append(full)
                    if name == "*":
                        self.globs[m].append(full)
                    elif name and name != "_":
                        self.binds[m][name] = full

    def absolute(self, m: Module, path: list[str]) -> list[str] | None:
        """``path`` as written in ``m``, from the crate root; None when it leaves the crate."""
        if not path:
            return None
        head, rest = path[0], path[1:]
        if head == "crate":
            base: list[str] = []
        elif head == "self":
            base = list(m)
        elif head == "super":
            base = list(m[:-1])
        elif m + (head,) in self.files:
            base, rest = list(m) + [head], rest
        elif head in self.binds.get(m, {}):
            return self.binds[m][head] + rest
        else:
            return None  # std, serde, a local item or a generic: not a crate module
        while rest and rest[0] == "super" and head in ("self", "super"):
            base, rest = base[:-1], rest[1:]
        return base + rest

    def resolve(self, path: list[str], depth: int = 0) -> Module:
        """The module that defines what ``path`` (from the crate root) names."""
        cur: Module = ()
        for k, seg in enumerate(path):
            if cur + (seg,) in self.files:
                cur = cur + (seg,)
                continue
            if seg in self.defs[cur] or depth > 16:
                return cur
            rest = path[k + 1 :]
            if seg in self.binds[cur]:
                return self.resolve(self.binds[cur][seg] + rest, depth + 1)
            for g in self.globs[cur]:
                target = self.resolve(g, depth + 1)
                if seg in self.defs[target] or seg in self.binds[target]:
                    return self.resolve(g + [seg] + rest, depth + 1)
            return cur
        return cur

    def edges(self) -> dict[Module, set[Module]]:
        out: dict[Module, set[Module]] = {m: set() for m in self.files}
        for m in self.files:
            paths = list(self.uses[m])
            body = USE.sub(" ", self.code[m])
            for p in BODY_PATH.findall(body):
                full = self.absolute(m, [s.strip() for s in p.split("::")])
                if full is not None:
                    paths.append(full)
            for p in paths:
                target = self.resolve(p)
                if target != m and target != ():
                    out[m].add(target)
        return out


def strongly_connected(edges: dict[Module, set[Module]]) -> list[set[Module]]:
    """Tarjan's algorithm (iterative); the components of more than one module."""
    index: dict[Module, int] = {}
    low: dict[Module, int] = {}
    stack: list[Module] = []
    on: set[Module] = set()
    out: list[set[Module]] = []
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, iter(sorted(edges[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(edges.get(w, ())))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
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
    return out


def cycles(src: Path) -> list[list[str]]:
    """Each cycle among ``src``'s modules, as sorted ``a::b`` names."""
    comps = strongly_connected(Crate(src).edges())
    return sorted(sorted("::".join(x) for x in c) for c in comps)


def main(argv: list[str]) -> int:
    src = Path(argv[1] if len(argv) > 1 else "crates/arena_core/src")
    if not src.is_dir():
        print(f"rust module cycles: no such directory {src}", file=sys.stderr)
        return 2
    found = cycles(src)
    for c in found:
        print("cycle: " + " <-> ".join(c))
    if found:
        return 1
    n = len(Crate(src).files)
    print(f"rust module cycles: none among {n} modules of {src}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
