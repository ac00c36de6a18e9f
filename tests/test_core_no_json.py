"""No JSON text crosses ``_core`` (issue 24): specs, configs and params go in as Python
objects and results come out as objects. Checked on ``_core.pyi``, which stubtest (``make
lint``) holds to the extension's real signatures: no parameter named ``json`` or
``*_json``, and ``str`` only where the value is genuinely text (a path, a name); closed domains are
``Literal`` types.
"""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest

import roboracer_arena
from roboracer_arena import _core

STUB = Path(roboracer_arena.__file__).with_name("_core.pyi")

#: (function or Class.method, parameter) pairs whose ``str`` is text, not a document.
TEXT_PARAMS = {
    ("load_map", "path"),
    ("save_map", "yaml_path"),
}
#: Results holding ``str`` as text (how many of their values): an image path, the state
#: field names, a check's words for people and a map file's paths.
TEXT_RESULTS = {
    "save_map": 1,
    "Simulator.state_fields": 1,
    "Check.name": 1,
    "Check.measured": 1,
    "Check.bound": 1,
    "MapMeta.yaml_path": 1,
    "MapMeta.image_path": 1,
}


def _defs() -> list[tuple[str, ast.FunctionDef]]:
    tree = ast.parse(STUB.read_text(encoding="utf-8"))
    out = []
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            out.append((node.name, node))
        elif isinstance(node, ast.ClassDef) and not node.name.startswith("_"):  # (stub-only helpers)
            out += [(f"{node.name}.{f.name}", f) for f in node.body if isinstance(f, ast.FunctionDef)]
    return out


def _str_count(annotation: ast.expr | None) -> int:
    """How many values of the annotation are ``str``: the value itself, an alternative of
    it, or elements of a tuple; keys of a mapping and items of other containers are not
    looked at."""
    match annotation:
        case ast.Name(id="str"):
            return 1
        case ast.BinOp(op=ast.BitOr()):
            return max(_str_count(annotation.left), _str_count(annotation.right))
        case ast.Subscript(value=ast.Name(id="tuple"), slice=ast.Tuple(elts=elts)):
            return sum(_str_count(e) for e in elts)
        case ast.Subscript(value=ast.Name(id="tuple"), slice=one):
            return _str_count(one)
    return 0


def test_the_stub_declares_every_entry_point():
    names = {name for name, _ in _defs()}
    assert {"screen", "validate_map", "generate_lattice", "check_config", "Simulator.__new__"} <= names


def test_no_core_entry_point_takes_or_returns_json_text():
    problems = []
    for name, fn in _defs():
        args = fn.args
        for a in [*args.posonlyargs, *args.args, *args.kwonlyargs]:
            if a.arg == "json" or a.arg.endswith("_json"):
                problems.append(f"{name}({a.arg}): a JSON parameter")
            elif _str_count(a.annotation) and (name.split(".")[-1], a.arg) not in TEXT_PARAMS:
                problems.append(f"{name}({a.arg}: str): text where an object belongs?")
        if name.endswith("_json"):
            problems.append(f"{name}: a JSON result")
        elif _str_count(fn.returns) > TEXT_RESULTS.get(name, 0):
            problems.append(f"{name} -> str: text where an object belongs?")
    assert not problems, "\n".join(problems)


def test_results_are_objects_at_runtime():
    """The stub is checked by stubtest for names and parameters, not for what a call
    returns: the results are typed objects (or dicts) here, not strings."""
    from roboracer_arena import TrackSpec

    spec = TrackSpec(lap_length_m=45, corridor_width_m=1.2, hairpins=1)
    assert isinstance(_core.screen(spec), _core.ScreenResult)
    assert isinstance(_core.derived_geometry(spec.model_dump()), _core.Derived)
    assert isinstance(_core.config_defaults("sim"), dict)
    assert isinstance(_core.check_config("spec", spec), dict)
    t = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    assert isinstance(_core.analyse_curve(np.c_[5 * np.cos(t), 5 * np.sin(t)], 1.0, 2.0), _core.CurveAnalysis)
    sim = _core.Simulator([_core.stadium_track()], 1, 1)
    assert isinstance(sim.config, dict) and sim.config["lidar"]["num_beams"] > 0


@pytest.mark.parametrize("text", ["{}", '{"lap_length_m": 60}'])
def test_json_text_is_refused_where_an_object_belongs(text):
    from roboracer_arena.errors import ArenaError

    with pytest.raises(ArenaError):
        _core.screen(text)
    with pytest.raises(ArenaError):
        _core.Simulator([_core.stadium_track()], 1, 1, text)
