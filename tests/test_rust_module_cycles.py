"""scripts/rust_module_cycles.py: the `make lint` gate that the Rust core has no module cycle.

Small crates written to a temporary directory exercise each way Rust code names another
module; the real core must have no cycle, and one made by appending a line must be found.
"""

from __future__ import annotations

import importlib.util
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "scripts" / "rust_module_cycles.py"
CORE = ROOT / "crates" / "arena_core" / "src"

pytestmark = pytest.mark.skipif(not SCRIPT.is_file(), reason="needs the source checkout (scripts/)")


def _load():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("rust_module_cycles", SCRIPT)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules["rust_module_cycles"] = mod
    spec.loader.exec_module(mod)
    return mod


rmc = _load()


def crate(tmp_path: Path, files: dict[str, str]) -> Path:
    """A crate source tree: ``lib.rs`` declares the top modules, ``m/mod.rs`` its own."""
    src = tmp_path / "src"
    for rel, text in files.items():
        p = src / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    return src


LIB = "pub mod m;\npub mod low;\n"
MOD = "pub mod a;\npub mod b;\n"


def cycles_with(tmp_path: Path, a: str, b: str, mod: str = MOD, low: str = "") -> list[list[str]]:
    src = crate(tmp_path, {"lib.rs": LIB, "m/mod.rs": mod, "m/a.rs": a, "m/b.rs": b, "low.rs": low})
    return rmc.cycles(src)


CYCLE = [["m::a", "m::b"]]
# b -> a in every case below; each test varies how a names b.
B_USES_A = "use super::a::A;\npub fn g() -> A { A }\n"


@pytest.mark.parametrize(
    "a_names_b",
    [
        "use super::b::g;\npub struct A;\n",
        "use crate::m::b::g;\npub struct A;\n",
        "use self::super::b;\npub struct A;\n",
        "use crate::{low::L, m::{b::{g as gee}}};\npub struct A;\n",
        "pub struct A;\nfn f() { let _ = crate::m::b::g(); }\n",
        "pub struct A;\nfn f() { let _ = super::b::g(); }\n",
        "use super::b;\npub struct A;\nfn f() { let _ = b::g(); }\n",
        "use crate::m::b as bee;\npub struct A;\nfn f() { let _ = bee::g(); }\n",
        "pub use super::b::g;\npub struct A;\n",
        "pub(crate) use super::b::*;\npub struct A;\n",
    ],
    ids=[
        "super",
        "crate",
        "self-super",
        "nested-group-alias",
        "body-crate",
        "body-super",
        "module-import",
        "module-alias",
        "pub-use",
        "glob",
    ],
)
def test_finds_each_way_of_naming_a_module(tmp_path: Path, a_names_b: str) -> None:
    assert cycles_with(tmp_path, a_names_b, B_USES_A) == CYCLE


def test_reexported_name_resolves_to_its_defining_module(tmp_path: Path) -> None:
    # `crate::m::G` is re-exported by m/mod.rs from b: a depends on b, not on m.
    mod = MOD + "pub use b::G;\n"
    assert (
        cycles_with(
            tmp_path,
            "pub struct A;\nfn f() { let _ = crate::m::G; }\n",
            "pub const G: u8 = 1;\nuse super::a::A;\n",
            mod=mod,
        )
        == CYCLE
    )
    # Re-exported under a glob from the crate root.
    files = {
        "lib.rs": LIB + "pub use m::b::*;\n",
        "m/mod.rs": MOD,
        "m/a.rs": "pub struct A;\nfn f() -> u8 { crate::G }\n",
        "m/b.rs": "pub const G: u8 = 1;\nuse super::a::A;\n",
        "low.rs": "",
    }
    assert rmc.cycles(crate(tmp_path, files)) == CYCLE


def test_mod_rs_and_its_child_can_form_a_cycle(tmp_path: Path) -> None:
    # `super::X` in a child names the parent's own item.
    got = cycles_with(
        tmp_path, "pub fn f() -> super::X { super::X }\n", "", mod=MOD + "pub struct X;\npub fn h() { a::f(); }\n"
    )
    assert got == [["m", "m::a"]]


def test_ignores_comments_strings_tests_and_other_crates(tmp_path: Path) -> None:
    a = (
        "// use super::b::g;\n/* crate::m::b::g() */\n/// [`super::b::g`]\n"
        'pub struct A;\nfn f() -> &\'static str { "crate::m::b::g" }\n'
        "use std::collections::BTreeMap;\nuse serde::Serialize;\n"
        "#[cfg(test)]\nmod tests {\n    use super::super::b::g;\n    #[test]\n    fn t() { g(); }\n}\n"
    )
    assert cycles_with(tmp_path, a, B_USES_A) == []


def test_test_declarations_do_not_hide_the_code_after_them(tmp_path: Path) -> None:
    # sim/mod.rs declares `#[cfg(test)] mod tests;` before its `pub use` lines.
    mod = MOD + '#[cfg(test)]\nmod tests;\n#[cfg(test)]\n#[path = "x_tests.rs"]\nmod more;\npub use b::G;\n'
    files = {
        "lib.rs": LIB,
        "m/mod.rs": mod,
        "m/tests.rs": "use super::a::A;\nuse super::b::G;\n",
        "m/a.rs": "pub struct A;\nfn f() -> u8 { crate::m::G }\n",
        "m/b.rs": "pub const G: u8 = 1;\nuse super::a::A;\n",
        "low.rs": "",
    }
    assert rmc.cycles(crate(tmp_path, files)) == CYCLE


def test_a_layered_crate_passes(tmp_path: Path) -> None:
    a = "use crate::low::L;\nuse super::b::g;\npub struct A(L);\n"
    b = "use crate::low::L;\npub fn g() -> L { L }\n"
    assert cycles_with(tmp_path, a, b, low="pub struct L;\n") == []


@pytest.mark.skipif(not CORE.is_dir(), reason="needs the source checkout (crates/)")
def test_core_has_no_cycle_and_an_added_one_is_found(tmp_path: Path) -> None:
    run = [sys.executable, str(SCRIPT)]
    ok = subprocess.run(run + [str(CORE)], capture_output=True, text=True, check=False)
    assert ok.returncode == 0, ok.stdout + ok.stderr
    assert "none among" in ok.stdout
    # track::features uses geometry::polyline; make polyline name features back.
    copy = tmp_path / "src"
    shutil.copytree(CORE, copy)
    with (copy / "geometry" / "polyline.rs").open("a") as f:
        f.write("\npub fn _back(k: crate::track::features::FeatureKind) -> bool { k == k }\n")
    bad = subprocess.run(run + [str(copy)], capture_output=True, text=True, check=False)
    assert bad.returncode == 1, bad.stdout
    assert "geometry::polyline" in bad.stdout and "track::features" in bad.stdout
