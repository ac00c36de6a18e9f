"""The config documents the core returns are typed in ``_core.pyi`` (issue 37), and cannot
drift: the stub's ``TypedDict`` fields, the keys (and value types) the core actually
returns and the pydantic models' fields are the same, recursively.

The stub's block is generated from the pydantic models (``scripts/core_documents.py``);
these tests check it is current, and hold what the core returns (``config_defaults``,
``check_config``, ``Simulator.config``, ``Geometry.params``, ``NearestSuggestion.spec``)
to the type the stub names for each, key by key and value by value.
"""

from __future__ import annotations

import ast
import importlib.util
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from pydantic import BaseModel

from roboracer_arena import _core
from roboracer_arena.spec import TrackSpec

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "scripts" / "core_documents.py"
STUB = Path(_core.__file__).with_name("_core.pyi")

pytestmark = pytest.mark.skipif(not SCRIPT.is_file(), reason="needs the source checkout (scripts/)")


def _generator():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("core_documents", SCRIPT)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules["core_documents"] = mod
    spec.loader.exec_module(mod)
    return mod


STUB_TREE = ast.parse(STUB.read_text(encoding="utf-8"))
#: The stub's TypedDicts: name -> field -> annotation.
STUB_DOCS: dict[str, dict[str, ast.expr]] = {
    c.name: {
        f.target.id: f.annotation for f in c.body if isinstance(f, ast.AnnAssign) and isinstance(f.target, ast.Name)
    }
    for c in STUB_TREE.body
    if isinstance(c, ast.ClassDef) and any(isinstance(b, ast.Name) and b.id == "TypedDict" for b in c.bases)
}
SCALARS = {"float": float, "int": int, "bool": bool, "str": str}


def _mismatches(value: Any, ann: ast.expr, path: str) -> list[str]:
    """Where ``value`` (what the core returned) differs from the stub's annotation."""
    if isinstance(ann, ast.BinOp) and isinstance(ann.op, ast.BitOr):
        left, right = _mismatches(value, ann.left, path), _mismatches(value, ann.right, path)
        return left and right and [f"{path}: {value!r} is not {ast.unparse(ann)}"]
    if isinstance(ann, ast.Constant) and ann.value is None:
        return [] if value is None else [f"{path}: {value!r} is not None"]
    if isinstance(ann, ast.Name) and ann.id in STUB_DOCS:
        if not isinstance(value, dict):
            return [f"{path}: {type(value).__name__} is not the document {ann.id}"]
        fields = STUB_DOCS[ann.id]
        out = [f"{path}.{k}: only in the core" for k in value.keys() - fields.keys()]
        out += [f"{path}.{k}: only in the stub ({ann.id})" for k in fields.keys() - value.keys()]
        return out + [m for k in value.keys() & fields.keys() for m in _mismatches(value[k], fields[k], f"{path}.{k}")]
    if isinstance(ann, ast.Name) and ann.id in SCALARS:  # exact types: a bool is not an int here
        return [] if type(value) is SCALARS[ann.id] else [f"{path}: {value!r} is not {ann.id}"]
    if isinstance(ann, ast.Subscript) and isinstance(ann.value, ast.Name):
        args = ann.slice.elts if isinstance(ann.slice, ast.Tuple) else [ann.slice]
        if ann.value.id == "Literal":
            allowed = [a.value for a in args if isinstance(a, ast.Constant)]
            return [] if value in allowed else [f"{path}: {value!r} is not one of {allowed}"]
        if ann.value.id == "list":
            if not isinstance(value, list):
                return [f"{path}: {type(value).__name__} is not a list"]
            return [m for i, v in enumerate(value) for m in _mismatches(v, args[0], f"{path}[{i}]")]
    raise AssertionError(f"{path}: the test cannot check the stub type {ast.unparse(ann)}")


def _stub_function(name: str) -> list[ast.FunctionDef]:
    """The stub's definitions of ``name`` (``f`` or ``Class.f``; several for overloads)."""
    *owner, fn = name.split(".")
    body = STUB_TREE.body
    if owner:
        body = next(c.body for c in body if isinstance(c, ast.ClassDef) and c.name == owner[0])
    return [f for f in body if isinstance(f, ast.FunctionDef) and f.name == fn]


def _stub_returns(name: str, kind: str | None = None) -> str:
    """The document type the stub names as ``name``'s result (for ``kind``: its overload)."""
    for f in _stub_function(name):
        first = f.args.args[0].annotation if f.args.args and f.args.args[0].arg == "kind" else None
        if kind is None or (first is not None and ast.unparse(first) == f"Literal['{kind}']"):
            assert f.returns is not None
            return ast.unparse(f.returns)
    raise AssertionError(f"the stub has no {name} for {kind!r}")


def _simulator_config() -> Any:
    walls, line = _core.stadium_track()
    return _core.Simulator([(walls, line)], 1, 1).config


def _geometry_params() -> Any:
    _, line = _core.stadium_track()
    data, origin = _core.rasterise_centreline(line, np.full(len(line), 1.5))
    return _core.build_geometry(data, 0.05, origin).params


def _nearest_spec() -> Any:
    spec = TrackSpec(name="long-in-small-hall", lap_length_m=60, corridor_width_m=0.8, hall_x_m=12, hall_y_m=9)
    return _core.nearest_specs(spec, None, 0, 20.0).suggestions[0].spec


FEATURED = TrackSpec(hairpins=1, feature_order=["hairpin"], max_straight_m=8.0)
#: (stub member, overload kind, how to get what the core returns there).
SOURCES: list[tuple[str, str | None, Callable[[], Any]]] = [
    *[("config_defaults", k, lambda k=k: _core.config_defaults(k)) for k in ("sim", "build", "constructor")],
    *[("check_config", k, lambda k=k: _core.check_config(k, _core.config_defaults(k))) for k in ("sim", "build")],
    ("check_config", "constructor", lambda: _core.check_config("constructor", {})),
    ("check_config", "spec", lambda: _core.check_config("spec", TrackSpec())),
    ("check_config", "spec", lambda: _core.check_config("spec", FEATURED)),
    ("Simulator.config", None, _simulator_config),
    ("Geometry.params", None, _geometry_params),
    ("NearestSuggestion.spec", None, _nearest_spec),
]


def test_the_generated_block_is_current():
    gen = _generator()
    assert gen.stub_block(STUB.read_text(encoding="utf-8")) == gen.render(), "run scripts/core_documents.py"


def _model_fields(model: type[BaseModel], prefix: str = "") -> set[str]:
    out = set()
    for name, info in model.model_fields.items():
        ann = info.annotation
        nested = isinstance(ann, type) and issubclass(ann, BaseModel)
        out |= _model_fields(ann, f"{prefix}{name}.") if nested else {prefix + name}  # type: ignore[arg-type]
    return out


def _stub_fields(doc: str, prefix: str = "") -> set[str]:
    out = set()
    for name, ann in STUB_DOCS[doc].items():
        nested = isinstance(ann, ast.Name) and ann.id in STUB_DOCS
        out |= _stub_fields(ann.id, f"{prefix}{name}.") if nested else {prefix + name}  # type: ignore[union-attr]
    return out


def test_the_stub_names_each_models_fields():
    gen = _generator()
    assert set(gen.DOCUMENTS) and {gen.doc_name(m) for m in gen.DOCUMENTS} <= STUB_DOCS.keys()
    for model in gen.DOCUMENTS:
        assert _stub_fields(gen.doc_name(model)) == _model_fields(model), model.__name__


@pytest.mark.parametrize("member,kind,source", SOURCES, ids=[f"{m}-{k}" if k else m for m, k, _ in SOURCES])
def test_the_core_returns_the_document_the_stub_names(member, kind, source):
    doc = _stub_returns(member, kind)
    assert doc in STUB_DOCS, f"{member} returns {doc}, not a config document"
    assert _mismatches(source(), ast.Name(doc), doc) == []


def test_the_stub_types_every_document_result():
    """No config document crosses as an untyped dict: each function or property above
    names a document type, and ``_Dumps.model_dump`` returns a typed mapping."""
    for member, kind, _ in SOURCES:
        assert _stub_returns(member, kind) in STUB_DOCS
    assert _stub_returns("_Dumps.model_dump") == "Mapping[str, object]"
    for name in ("config_defaults", "check_config"):
        assert all(ast.unparse(f.returns) != "_Result" for f in _stub_function(name) if f.returns is not None)


def test_a_field_on_one_side_only_is_found():
    doc = _core.config_defaults("sim")
    doc["vehicle"]["spoiler"] = 1.0
    del doc["lidar"]["fov"]
    doc["physics"]["ccd"] = 0
    assert sorted(_mismatches(doc, ast.Name("SimConfigDoc"), "sim")) == [
        "sim.lidar.fov: only in the stub (LidarConfigDoc)",
        "sim.physics.ccd: 0 is not bool",
        "sim.vehicle.spoiler: only in the core",
    ]
