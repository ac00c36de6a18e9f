"""One schema per concept across the boundary: each pydantic config model and the core's
serde struct it mirrors agree on every field, every default and every limit.

Limits are probed, not compared as text: for every numeric field, values at and just
beyond each pydantic bound, plus NaN, ±inf and a huge value, are given to both sides;
each side must accept or refuse the same ones (the core through ``_core.check_config``).
A field only one side has, or a bound only one side enforces, fails with its name.
"""

from __future__ import annotations

import json
import math
from typing import Any

import annotated_types as at
import pytest
from pydantic import BaseModel, ValidationError

from roboracer_arena import _core
from roboracer_arena.build_config import GeometryConfig
from roboracer_arena.constructor_config import ConstructorConfig
from roboracer_arena.errors import ArenaError
from roboracer_arena.sim_config import SimConfig

PAIRS: list[tuple[str, type[BaseModel]]] = [
    ("sim", SimConfig),
    ("build", GeometryConfig),
    ("constructor", ConstructorConfig),
]


def _leaves(model: type[BaseModel], prefix: tuple[str, ...] = ()) -> list[tuple[tuple[str, ...], Any]]:
    """(path, FieldInfo) of every scalar field, nested models flattened."""
    out = []
    for name, info in model.model_fields.items():
        ann = info.annotation
        if isinstance(ann, type) and issubclass(ann, BaseModel):
            out += _leaves(ann, (*prefix, name))
        else:
            out.append(((*prefix, name), info))
    return out


def _set(doc: dict, path: tuple[str, ...], value: Any) -> dict:
    d = json.loads(json.dumps(doc))
    node = d
    for p in path[:-1]:
        node = node[p]
    node[path[-1]] = value
    return d


def _probes(info: Any) -> list[float]:
    """Values at and just beyond each bound, and the classic hostile ones."""
    values = [math.nan, math.inf, -math.inf, 1e300, -1e300]
    for m in info.metadata:
        for attr in ("gt", "ge", "lt", "le"):
            b = getattr(m, attr, None) if isinstance(m, (at.Gt, at.Ge, at.Lt, at.Le)) else None
            if b is None:
                continue
            eps = 1e-6 * max(1.0, abs(b))
            values += [b, b - eps, b + eps, b - 1, b + 1]
    return values


def _py_accepts(model: type[BaseModel], doc: dict) -> bool:
    try:
        model.model_validate_json(json.dumps(doc, allow_nan=True))
    except ValidationError:
        return False
    return True


def _core_accepts(kind: str, doc: dict) -> bool:
    try:
        _core.check_config(kind, json.dumps(doc, allow_nan=True))
    except ArenaError:
        return False
    return True


def _defaults(model: type[BaseModel]) -> dict:
    return json.loads(model().model_dump_json())


@pytest.mark.parametrize("kind,model", PAIRS, ids=[k for k, _ in PAIRS])
def test_same_fields_and_defaults(kind, model):
    ours, core = _defaults(model), json.loads(_core.config_defaults(kind))
    flat = lambda d, p=(): {
        k: v
        for key, val in d.items()
        for k, v in (flat(val, (*p, key)).items() if isinstance(val, dict) else [((*p, key), val)])
    }
    a, b = flat(ours), flat(core)
    assert sorted(a) == sorted(b), (
        f"fields only in pydantic: {sorted(set(a) - set(b))}; only in core: {sorted(set(b) - set(a))}"
    )
    differ = {
        ".".join(k): (a[k], b[k])
        for k in a
        if not (a[k] == b[k] or (isinstance(a[k], float) and math.isclose(a[k], b[k], rel_tol=1e-12)))
    }
    assert not differ, f"defaults differ (pydantic, core): {differ}"


@pytest.mark.parametrize("kind,model", PAIRS, ids=[k for k, _ in PAIRS])
def test_same_limits(kind, model):
    base = _defaults(model)
    assert _py_accepts(model, base) and _core_accepts(kind, base)
    disagree = []
    for path, info in _leaves(model):
        if info.annotation not in (float, int):
            continue
        for v in _probes(info):
            if info.annotation is int and not (math.isfinite(v) and float(v).is_integer() and abs(v) < 2**53):
                continue
            doc = _set(base, path, int(v) if info.annotation is int else v)
            py, core = _py_accepts(model, doc), _core_accepts(kind, doc)
            if py != core:
                disagree.append(
                    f"{'.'.join(path)}={v!r}: pydantic {'accepts' if py else 'refuses'}, core {'accepts' if core else 'refuses'}"
                )
    assert not disagree, "limits drifted:\n" + "\n".join(disagree)


def test_unknown_kind_is_a_typed_error():
    with pytest.raises(ArenaError, match="config kind"):
        _core.check_config("nope", "{}")


def test_spec_straight_cap_limits_agree():
    """``max_straight_m`` (issue 28): TrackSpec and the core's Spec accept and refuse the
    same caps (the core reads the spec in every call; ``_core.screen`` is the cheapest)."""
    from roboracer_arena.spec import TrackSpec

    cfg = ConstructorConfig().model_dump_json()
    base = json.loads(TrackSpec().model_dump_json())
    assert "max_straight_m" not in base  # an unset cap is left out of the JSON (old spec files unchanged)
    info = TrackSpec.model_fields["max_straight_m"]
    disagree = []
    for v in [None, *_probes(info)]:
        doc = {**base, "max_straight_m": v}
        py = _py_accepts(TrackSpec, doc)
        try:
            _core.screen(json.dumps(doc, allow_nan=True), cfg)
            core = True
        except ArenaError:
            core = False
        if py != core:
            disagree.append(f"max_straight_m={v!r}: pydantic {py}, core {core}")
    assert not disagree, "\n".join(disagree)
