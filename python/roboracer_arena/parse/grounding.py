"""The grounding guard: every non-default value a backend returns must be traceable to the
request text, or it is an invented constraint.

A value is traceable when

* numbers (lengths): a number written in the request (digits or words) equals the value
  in the unit written after it -- or, for a bare number, in some length unit -- within
  1 %, *and* a word naming that field occurs in the request ("radius" for the minimum
  radius, "straight" for the longest straight, ...). The second test catches a model that
  copies a stated number into a field nobody asked for. The one exception is the rules'
  lone-length reading: a lap equal to the only number-with-unit that no other field
  explains ("five hairpins, 45 metres") is traceable without a lap word;
* feature counts: the feature's noun occurs and the count is written (a number, "a",
  "another", ...), equals the number of times the noun occurs, or equals the counts
  written before each mention added up ("two hairpins ... two more hairpins");
* direction "clockwise": the request says clockwise (or "not counter-clockwise");
* name: the request contains it; feature order: the request uses an order word and
  names the features.

Values the rules parser derives from the same text are traceable by construction (the
rules backend only sets what it read), so the guard also accepts a value equal to the
rules parser's reading of that field.
"""

from __future__ import annotations

import warnings as _warnings
from dataclasses import dataclass, field
from typing import Any

from ..errors import ArenaError, GroundingError
from ..spec import TrackSpec
from .lexer import Tok, tokenize
from .limits import quote
from .result import DEFAULTS, FIELDS, Fragment, Span
from .rules import parse_rules
from .units import METRES_PER
from .vocab import CORRIDOR_NOUNS, HALL_NOUNS, LAP_NOUNS, ORDER_FORWARD, ORDER_REVERSE, ORDER_START

_LENGTH_CUES: dict[str, set[str]] = {
    "lap_length_m": set(LAP_NOUNS)
    | {"long", "length", "distance", "circumference", "perimeter", "around", "round", "total", "overall"},
    "corridor_width_m": set(CORRIDOR_NOUNS) | {"wide", "width", "across", "narrow"},
    "hall_x_m": set(HALL_NOUNS) | {"by", "x", "long", "length", "wide", "width"},
    "hall_y_m": set(HALL_NOUNS) | {"by", "x", "long", "length", "wide", "width"},
    "min_radius_m": {"radius", "tighter", "tightest", "sharpest", "smallest", "turning"},
    "longest_straight_m": {"straight", "straights"},
    "max_straight_m": {"straight", "straights"},
}
_COUNT_FIELDS = {"hairpins": "hairpin", "chicanes": "chicane", "sweepers": "sweeper"}
_ONE_WORDS = {"a", "an", "single", "another", "one"}
_ORDER_WORDS = ORDER_FORWARD | ORDER_REVERSE | ORDER_START | {"order", "sequence"}
_REL_TOL = 0.01


@dataclass
class Grounded:
    """The guard's verdict: the (possibly reset) spec, where each value was traced, the
    values it could not trace, and warnings (non-strict resets)."""

    spec: TrackSpec
    spans: dict[str, tuple[Span, ...]] = field(default_factory=dict)
    invented: dict[str, Any] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)


def _trace_length(value: float, toks: list[Tok]) -> Span | None:
    for k, t in enumerate(toks):
        if t.kind != "num" or t.value is None:
            continue
        nxt = toks[k + 1] if k + 1 < len(toks) else None
        units = [nxt.canon] if nxt is not None and nxt.kind == "unit" else list(METRES_PER)
        for u in units:
            if abs(t.value * METRES_PER[u] - value) <= max(1e-6, _REL_TOL * abs(value)):
                end = nxt.end if nxt is not None and nxt.kind == "unit" else t.end
                return t.start, end
    return None


def _trace_count(name: str, value: int, toks: list[Tok]) -> Span | None:
    noun = _COUNT_FIELDS[name]
    hits = [t for t in toks if t.canon in (noun, noun + "s")]
    if not hits:
        return None
    written = {int(t.value) for t in toks if t.kind == "num" and t.value is not None and float(t.value).is_integer()}
    if any(t.canon in _ONE_WORDS for t in toks):
        written.add(1)
    if any(t.canon == "each" for t in toks):  # "two sweepers, each followed by two chicanes"
        small = {w for w in written if 0 <= w <= 50}  # counts are small: keeps this product bounded
        written |= {a * b for a in small for b in small}
    if value in written or value == len(hits) or value == _summed(toks, noun):
        return hits[0].start, hits[-1].end
    return None


_FEATURE_WORDS = {w for n in _COUNT_FIELDS.values() for w in (n, n + "s")}


def _summed(toks: list[Tok], noun: str) -> int:
    """The counts written before each mention of ``noun``, added up ("two hairpins then a
    chicane then two more hairpins": 4); a mention with no count adds nothing."""
    total = 0
    for k, t in enumerate(toks):
        if t.canon not in (noun, noun + "s"):
            continue
        for j in range(k - 1, max(-1, k - 5), -1):
            p = toks[j]
            if p.kind == "punct" or p.canon in _FEATURE_WORDS:
                break
            if p.kind == "num" and p.value is not None and float(p.value).is_integer() and 0 <= p.value <= 50:
                total += int(p.value)
                break
            if p.canon in _ONE_WORDS:
                total += 1
                break
    return total


def _metres(toks: list[Tok], k: int) -> list[float]:
    """What number token ``k`` may mean in metres: in its written unit, else in any unit."""
    nxt = toks[k + 1] if k + 1 < len(toks) else None
    units = [nxt.canon] if nxt is not None and nxt.kind == "unit" else list(METRES_PER)
    return [float(toks[k].value or 0.0) * METRES_PER[u] for u in units]


def _close(a: float, b: float) -> bool:
    return abs(a - b) <= max(1e-6, _REL_TOL * abs(b))


def _lone_length(value: float, values: dict[str, Any], toks: list[Tok]) -> Span | None:
    others = [float(values[k]) for k in _LENGTH_CUES if k != "lap_length_m" and values[k] not in (DEFAULTS[k], None)]
    lone = [
        k for k, t in enumerate(toks)
        if t.kind == "num" and k + 1 < len(toks) and toks[k + 1].kind == "unit"
        and not any(_close(m, o) for m in _metres(toks, k) for o in others)
    ]  # fmt: skip
    if len(lone) == 1 and _close(_metres(toks, lone[0])[0], value):
        return toks[lone[0]].start, toks[lone[0] + 1].end
    return None


def _counts_a_feature(toks: list[Tok], k: int, values: dict[str, Any]) -> bool:
    """Whether number ``k`` counts a feature the spec has at least that many of ("two
    hairpins ... two more hairpins" with 4 hairpins; "hairpins x2")."""
    near = [toks[j] for j in range(k + 1, min(len(toks), k + 5))]
    near = near[: next((i for i, t in enumerate(near) if t.kind == "punct" and t.canon != "x"), len(near))]
    near += [toks[j] for j in range(max(0, k - 2), k) if toks[j].canon in _FEATURE_WORDS]
    for t in near:
        if t.canon in _FEATURE_WORDS:
            have = int(values[t.canon.rstrip("s") + "s"])
            return have >= float(toks[k].value or 0.0) and (have > 0) == ((toks[k].value or 0.0) > 0)
    return False


def unexplained_numbers(text: str, values: dict[str, Any]) -> list[Fragment]:
    """Numbers in ``text`` that no field of ``values`` explains: no length field equals
    the number (in its unit, or any unit when none is written), no count equals it, and
    it is not inside the name. A lone "one" with no unit is a pronoun, not a number.

    Defaults count as explanations (a model that keeps the 60 m default lap for "a 60 m
    lap" is right), so a stray number equal to a default value ("in 20 minutes" with the
    20 m default hall) passes: this check catches dropped numbers, not coincidences."""
    toks = tokenize(text)
    name = str(values.get("name", ""))
    at = text.lower().find(name.lower()) if name and values.get("name") != DEFAULTS["name"] else -1
    lengths = [float(values[k]) for k in _LENGTH_CUES if values[k] is not None]
    counts = [int(values[k]) for k in _COUNT_FIELDS]
    out = []
    for k, t in enumerate(toks):
        if t.kind != "num" or t.value is None or (at >= 0 and at <= t.start and t.end <= at + len(name)):
            continue
        unit = k + 1 < len(toks) and toks[k + 1].kind == "unit"
        if not unit and text[t.start : t.end].lower() == "one":
            continue
        if any(_close(m, v) for m in _metres(toks, k) for v in lengths) or (not unit and t.value in counts):
            continue
        if not unit and _counts_a_feature(toks, k, values):
            continue
        end = toks[k + 1].end if unit else t.end
        out.append(Fragment(text[t.start : end], t.start, end))
    return out


def _trace(name: str, value: Any, text: str, toks: list[Tok], values: dict[str, Any]) -> Span | None:
    words = {t.canon for t in toks}
    if name in _LENGTH_CUES:
        if not words & _LENGTH_CUES[name]:
            return _lone_length(float(value), values, toks) if name == "lap_length_m" else None
        return _trace_length(float(value), toks)
    if name in _COUNT_FIELDS:
        return _trace_count(name, int(value), toks)
    if name == "direction":
        for k, t in enumerate(toks):
            negated = any(p.canon in ("not", "never") or p.canon.endswith("n't") for p in toks[max(0, k - 2) : k])
            if (t.canon == "cw" and not negated and value == "clockwise") or (
                t.canon == "ccw" and (negated == (value == "clockwise"))
            ):
                return t.start, t.end
        return None
    if name == "name":
        at = text.lower().find(str(value).lower())
        return (at, at + len(str(value))) if at >= 0 else None
    if name == "feature_order":
        if not words & _ORDER_WORDS:
            return None
        hits = [t for t in toks if t.canon.rstrip("s") in set(value)]
        if {t.canon.rstrip("s") for t in hits} != set(value):
            return None
        return hits[0].start, hits[-1].end
    return None


def _rules_reading(text: str) -> tuple[dict[str, Any], dict[str, tuple[Span, ...]]]:
    try:
        r = parse_rules(text)
    except ArenaError:
        return {}, {}
    dump = r.spec.model_dump()
    return {k: dump[k] for k in r.stated}, r.spans


def ground(text: str, spec: TrackSpec, *, strict: bool = True, rules_reading: bool = True) -> Grounded:
    """Check every non-default field of ``spec`` against ``text``.

    ``strict=True`` raises :class:`GroundingError` naming each invented value;
    ``strict=False`` resets them to their defaults (and an order that no longer matches
    the counts to empty) and reports each reset in ``warnings``.
    """
    toks = tokenize(text)
    values = spec.model_dump()
    rules_vals, rules_spans = _rules_reading(text) if rules_reading else ({}, {})
    spans: dict[str, tuple[Span, ...]] = {}
    invented: dict[str, Any] = {}
    for name in FIELDS:
        v = values[name]
        if v == DEFAULTS[name]:
            continue
        if name in rules_vals and rules_vals[name] == v:
            spans[name] = rules_spans[name]
            continue
        sp = _trace(name, v, text, toks, values)
        if sp is None:
            invented[name] = v
        else:
            spans[name] = (sp,)
    if not invented:
        return Grounded(spec, spans)
    listing = ", ".join(f"{k}={v!r}" for k, v in invented.items())
    if strict:
        raise GroundingError(
            f"invented constraint(s) not traceable to the request: {listing} (request: {quote(text, 0, len(text), 200)})"
        )
    fixed = dict(values)
    notes = []
    for name in invented:
        fixed[name] = DEFAULTS[name]
        notes.append(f"{name}={invented[name]!r} is not in the request; reset to the default {DEFAULTS[name]!r}")
        spans.pop(name, None)
    if fixed["feature_order"] and any(
        fixed["feature_order"].count(_COUNT_FIELDS[c]) != fixed[c] for c in _COUNT_FIELDS
    ):
        notes.append("feature_order no longer matches the feature counts; reset to empty")
        fixed["feature_order"] = []
        spans.pop("feature_order", None)
    for note in notes:
        _warnings.warn(f"grounding guard: {note}", stacklevel=2)
    return Grounded(TrackSpec.model_validate(fixed), spans, invented, notes)
