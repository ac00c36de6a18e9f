"""scripts/long_functions.py: the `make lint` gate that no function runs over 100 lines.

Small sources exercise how a length is measured (braces in strings and comments, trait
declarations, nested functions, Python decorators and methods); the Rust core, its binding
and the Python package must hold no function over 100 lines (issue 37 split the fourteen
that did).
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "scripts" / "long_functions.py"

pytestmark = pytest.mark.skipif(not SCRIPT.is_file(), reason="needs the source checkout (scripts/)")


def _load():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("long_functions", SCRIPT)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules["long_functions"] = mod
    spec.loader.exec_module(mod)
    return mod


lf = _load()


def lengths(found) -> dict[str, int]:  # type: ignore[no-untyped-def]
    return {f.name: f.length for f in found}


def test_a_rust_body_ends_at_its_own_brace_whatever_strings_and_comments_hold() -> None:
    src = """
trait T {
    fn declared(&self) -> u8;
}

/// fn not_a_function() { in a doc comment }
pub fn outer<F: Fn(u8) -> u8>(f: F) -> [u8; 2]
where
    F: Copy,
{
    let s = "}}} fn fake() {";
    let r = r#"{"json": "}"}"#;
    let c = '}';
    /* { */
    fn inner() -> u8 {
        1
    }
    [f(inner()), s.len() as u8 + r.len() as u8 + c as u8]
}
"""
    got = lengths(lf.rust_functions(src, "x.rs"))
    assert got == {"outer": 13, "inner": 3}, got


def test_python_lengths_count_decorators_and_name_methods_by_class() -> None:
    src = """
import functools


@functools.cache
def top(x: int) -> int:
    def helper() -> int:
        return x

    return helper()


class Box:
    def method(self) -> None:
        pass
"""
    got = lengths(lf.python_functions(src, "x.py"))
    assert got == {"top": 6, "top.helper": 2, "Box.method": 2}, got


def test_the_gate_fails_over_the_limit_unless_allowed(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    body = "\n".join(f"    let x{i} = {i};" for i in range(5))
    (tmp_path / "long.rs").write_text(f"fn long() {{\n{body}\n}}\n\nfn short() {{}}\n")
    assert lf.main(["--max", "6", str(tmp_path)]) == 1
    assert "long.rs:1 long 7 lines" in capsys.readouterr().out
    assert lf.main(["--max", "7", str(tmp_path)]) == 0
    assert lf.main(["--max", "6", "--allow", "long.rs:long", str(tmp_path)]) == 0
    assert lf.main(["--max", "6", "--allow", "long", str(tmp_path)]) == 0
    assert lf.main(["--max", "6", "--allow", "other.rs:long", str(tmp_path)]) == 1


@pytest.mark.parametrize("root", ["crates/arena_core/src", "crates/arena_py/src", "python/roboracer_arena"])
def test_no_function_in_the_crates_or_the_package_is_over_100_lines(root: str) -> None:
    found = list(lf.functions(ROOT / root))
    assert len(found) > 50
    long = [f"{f.path}:{f.line} {f.name} {f.length}" for f in found if f.length > 100]
    assert long == []
