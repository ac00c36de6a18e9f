"""One schema per concept across the boundary: each pydantic config model and the core's
serde struct it mirrors agree on every field, every default and every limit.

Limits are probed, not compared as text: for every numeric field, values at and just
beyond each pydantic bound, plus NaN, ±inf and a huge value, are given to both sides;
each side must accept or refuse the same ones (the core through ``_core.check_config``,
which takes the document as a Python mapping, never as JSON text). A field only one side
has, or a bound only one side enforces, fails with its name. The track spec
(``TrackSpec`` / the core's ``Spec``) and the start spec (``EnvConfig``'s start fields /
``_core.StartSpec``) are held the same way.
"""

from __future__ import annotations

import json
import math
from typing import Any

import annotated_types as at
import pytest
from pydantic import BaseModel, ValidationError

from roboracer_arena import _core
from roboracer_arena.config.build import GeometryConfig
from roboracer_arena.config.constructor import ConstructorConfig
from roboracer_arena.config.sim import SimConfig
from roboracer_arena.errors import ArenaError
from roboracer_arena.spec import TrackSpec

PAIRS: list[tuple[str, type[BaseModel]]] = [
    ("sim", SimConfig),
    ("build", GeometryConfig),
    ("constructor", ConstructorConfig),
]
#: Schemas whose limits are probed: the configs, and the track spec (no core defaults:
#: ``TrackSpec`` is the one source of a spec's defaults).
LIMIT_PAIRS = [*PAIRS, ("spec", TrackSpec)]


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
        _core.check_config(kind, doc)
    except ArenaError:
        return False
    return True


def _defaults(model: type[BaseModel]) -> dict:
    return json.loads(model().model_dump_json())


@pytest.mark.parametrize("kind,model", PAIRS, ids=[k for k, _ in PAIRS])
def test_same_fields_and_defaults(kind, model):
    # (json round trip: the core's tuples read as the lists pydantic's dump has)
    ours, core = _defaults(model), json.loads(json.dumps(_core.config_defaults(kind)))
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


@pytest.mark.parametrize("kind,model", LIMIT_PAIRS, ids=[k for k, _ in LIMIT_PAIRS])
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
        _core.check_config("nope", {})


def test_spec_optional_and_text_fields_agree():
    """The spec's fields that are not plain numbers: the optional straight cap (issue 28),
    the name, the direction (an enum on both sides) and the feature order."""
    base = json.loads(TrackSpec().model_dump_json())
    assert "max_straight_m" not in base  # an unset cap is left out of the JSON (old spec files unchanged)
    probes: list[tuple[str, Any]] = [
        ("max_straight_m", v) for v in [None, *_probes(TrackSpec.model_fields["max_straight_m"])]
    ]
    probes += [("name", v) for v in ["", " ", "a", "x" * 120, "x" * 121, "tab\there", " padded "]]
    probes += [("direction", v) for v in ["clockwise", "counterclockwise", "Clockwise", "cw", ""]]
    probes += [("hairpins", 2.5), ("lap_length_m", True), ("name", 3)]
    disagree = []
    for field, v in probes:
        doc = {**base, field: v}
        py, core = _py_accepts(TrackSpec, doc), _core_accepts("spec", doc)
        if py != core:
            disagree.append(f"{field}={v!r}: pydantic {py}, core {core}")
    for order, hairpins in [(["hairpin"], 1), (["hairpin"], 0), ([], 2), (["hairpin", "hairpin"], 2), (["chicane"], 0)]:
        doc = {**base, "feature_order": order, "hairpins": hairpins}
        py, core = _py_accepts(TrackSpec, doc), _core_accepts("spec", doc)
        if py != core:
            disagree.append(f"feature_order={order} hairpins={hairpins}: pydantic {py}, core {core}")
    assert not disagree, "\n".join(disagree)


#: The env config's start fields -> the core's ``StartSpec`` keyword they become
#: (``start_grid.start_spec``); the ROS 2 bridge's ``StartConfig`` states the same fields.
START_FIELDS = {
    "grid_spacing": "grid_spacing",
    "grid_offset": "grid_offset",
    "start_lateral_noise": "lateral_noise",
    "start_heading_noise": "heading_noise",
    "start_speed_noise": "speed_noise",
}
START_BASE = {
    "random_s": False,
    "s0": [0.0],
    "grid_spacing": 1.0,
    "grid_offset": 0.0,
    "lateral_noise": 0.0,
    "heading_noise": 0.0,
    "side_clearance": 0.0,
    "speed_noise": 0.0,
    "noise_std": (0.0, 0.0),
    "dropout": 0.0,
}


def _start_spec_accepts(**fields: Any) -> bool:
    try:
        _core.StartSpec(**{**START_BASE, **fields})
    except ArenaError:
        return False
    return True


def test_start_spec_limits_agree():
    """``_core.StartSpec`` (the core's ``StartSpec::check``) accepts the start fields the
    pydantic models accept, and refuses the rest."""
    from roboracer_arena.envs.env_config import RandomisationConfig
    from roboracer_arena.ros2.start import StartConfig

    disagree = []
    for field, kw in START_FIELDS.items():
        for v in _probes(StartConfig.model_fields[field]):
            py = _py_accepts(StartConfig, {field: v})
            if py != _start_spec_accepts(**{kw: v}):
                disagree.append(f"{field}={v!r}: pydantic {'accepts' if py else 'refuses'}")
    for v in _probes(RandomisationConfig.model_fields["lidar_dropout"]):
        py = _py_accepts(RandomisationConfig, {"lidar_dropout": v})
        if py != _start_spec_accepts(dropout=v):
            disagree.append(f"lidar_dropout={v!r}: pydantic {'accepts' if py else 'refuses'}")
    for lo, hi in [(0, 0), (0, 1e4), (0, 1e4 + 1), (1, 0.5), (-1, 0), (0, math.inf), (math.nan, 1), (1e4, 1e4)]:
        py = _py_accepts(RandomisationConfig, {"lidar_noise_std": [lo, hi]})
        if py != _start_spec_accepts(noise_std=(lo, hi)):
            disagree.append(f"lidar_noise_std=({lo}, {hi}): pydantic {'accepts' if py else 'refuses'}")
    assert not disagree, "start spec limits drifted:\n" + "\n".join(disagree)


def test_env_and_bridge_state_the_same_start_fields():
    """The env config and the bridge's ``StartConfig`` bound each start field alike (the
    probe above runs on the bridge's)."""
    from roboracer_arena.envs.env_config import EnvConfig
    from roboracer_arena.ros2.start import StartConfig

    for field in START_FIELDS:
        env, bridge = EnvConfig.model_fields[field], StartConfig.model_fields[field]
        assert (env.default, env.metadata) == (bridge.default, bridge.metadata), field
