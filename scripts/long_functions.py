#!/usr/bin/env python3
"""List the functions longer than a limit in Rust and Python sources (a `make lint` gate).

A function's length is its lines from the ``fn``/``def`` line (Python: its first
decorator) to its closing line, blank lines and comments included: what a reader has to
hold. Rust bodies are found by matching braces after comments and literals are blanked
(newlines kept), so a brace in a string or a comment does not count; a nested function
is counted inside its parent and on its own. Python lengths come from ``ast``.

Usage: ``python3 scripts/long_functions.py [--max N] [--allow [PATH:]NAME ...] [ROOT ...]``
(default 100 lines; roots ``crates/arena_core/src crates/arena_py/src
python/roboracer_arena``). Prints ``path:line name length`` for each function over the
limit and exits 1 if any is not allowed, else prints a one-line summary and exits 0.
"""

from __future__ import annotations

import argparse
import ast
import re
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import NamedTuple

DEFAULT_ROOTS = ("crates/arena_core/src", "crates/arena_py/src", "python/roboracer_arena")
IDENT = r"[A-Za-z_][A-Za-z0-9_]*"
# Comments, then string, byte-string, raw-string and char literals (lifetimes never
# close with a quote one character later, so they are left alone).
NOISE = re.compile(
    r"//[^\n]*|/\*.*?\*/|\bb?r(#*)\".*?\"\1|b?\"(?:\\.|[^\"\\])*\"|b?'(?:\\.|[^\\'\n])'",
    re.S,
)
FN = re.compile(rf"\bfn\s+({IDENT})")


class Function(NamedTuple):
    path: str
    line: int
    name: str
    length: int

    def allowed_by(self, allow: set[str]) -> bool:
        """Whether an ``--allow`` entry names this function: ``NAME``, or the tail of
        ``path:NAME`` (``drivers.py:_drive``), so an entry survives a package move."""
        key = f"{self.path}:{self.name}"
        return self.name in allow or any(":" in a and key.endswith(a) for a in allow)


def blank_rust(text: str) -> str:
    """``text`` with comments and literal contents replaced by spaces, newlines kept."""
    return NOISE.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)


def rust_functions(text: str, path: str) -> Iterator[Function]:
    """Every ``fn`` with a body in one Rust source file."""
    code = blank_rust(text)
    for m in FN.finditer(code):
        depth, i = 0, m.end()
        # The body opens at the first `{` outside the signature's brackets; a `;` first
        # means a declaration without a body (a trait method).
        while i < len(code) and not (depth == 0 and code[i] in "{;"):
            depth += {"(": 1, "[": 1, ")": -1, "]": -1}.get(code[i], 0)
            i += 1
        if i >= len(code) or code[i] == ";":
            continue
        depth, end = 0, len(code) - 1
        for j in range(i, len(code)):
            depth += {"{": 1, "}": -1}.get(code[j], 0)
            if depth == 0:
                end = j
                break
        first, last = code.count("\n", 0, m.start()), code.count("\n", 0, end)
        yield Function(path, first + 1, m.group(1), last - first + 1)


def python_functions(text: str, path: str) -> Iterator[Function]:
    """Every function and method in one Python source file, named ``Class.method``."""

    def walk(node: ast.AST, prefix: str) -> Iterator[Function]:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                start = min([child.lineno, *(d.lineno for d in child.decorator_list)])
                end = child.end_lineno or child.lineno
                yield Function(path, start, prefix + child.name, end - start + 1)
                yield from walk(child, prefix + child.name + ".")
            elif isinstance(child, ast.ClassDef):
                yield from walk(child, prefix + child.name + ".")
            else:
                yield from walk(child, prefix)

    yield from walk(ast.parse(text, filename=path), "")


def functions(root: Path) -> Iterator[Function]:
    """Every function under ``root`` (a directory or one file), paths as given."""
    files = [root] if root.is_file() else sorted([*root.rglob("*.rs"), *root.rglob("*.py")])
    for f in files:
        text = f.read_text(encoding="utf-8")
        yield from (rust_functions if f.suffix == ".rs" else python_functions)(text, f.as_posix())


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("roots", nargs="*", default=list(DEFAULT_ROOTS))
    ap.add_argument("--max", type=int, default=100, help="longest allowed function, in lines")
    ap.add_argument(
        "--allow", action="append", default=[], metavar="[PATH:]NAME", help="a function let through (repeatable)"
    )
    args = ap.parse_args(argv)
    allowed = set(args.allow)
    found = [f for root in args.roots for f in functions(Path(root))]
    long = sorted((f for f in found if f.length > args.max), key=lambda f: -f.length)
    for f in long:
        note = " (allowed)" if f.allowed_by(allowed) else ""
        print(f"{f.path}:{f.line} {f.name} {f.length} lines{note}")
    refused = [f for f in long if not f.allowed_by(allowed)]
    if refused:
        print(f"{len(refused)} function(s) over {args.max} lines", file=sys.stderr)
        return 1
    print(f"long functions: none over {args.max} lines among {len(found)}, besides {len(long)} allowed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
