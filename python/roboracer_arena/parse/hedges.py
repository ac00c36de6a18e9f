"""Hedges around a stated quantity ("about 45 m", "at most 1.2 m", "at least 2 m radius",
"50 m or so") and what they mean for a TrackSpec field.

A TrackSpec field holds one value, so a hedge never changes the number; it decides
whether the number can be used:

* *approximately* ("about", "around", "roughly", "approximately", "some", "circa",
  "nearly", "almost", "~", "... or so", "45-ish"): the value is the target. Every length
  is a target the generator meets within its own tolerance anyway.
* *at most* ("at most", "no more than", "up to", "max", "maximum", "under", "less than",
  "below", "within", "no longer/wider/bigger than", "... or less", "... tops") and
  *at least* ("at least", "no less than", "min", "minimum", "over", "more than", "above",
  "no shorter/narrower/tighter than", "... or more"):

  - ``min_radius_m`` and ``longest_straight_m`` are floors already: *at least* is their
    meaning; *at most* on a radius cannot be expressed and is refused, while *at most* on
    a straight ("straights of at most 8 m") is the speed cap ``max_straight_m``
    (:func:`straight_caps`), whose meaning it is (*at least* on a cap is refused).
  - hall sizes are the space available: either bound reads as that size.
  - ``lap_length_m``, ``corridor_width_m`` and the feature counts are targets: a bound
    reads as a target equal to the bound, and the result carries a warning saying so.
"""

from __future__ import annotations

from ..errors import RequestParseError
from .found import Found
from .lexer import Canon
from .limits import FIELD_RANGES

APPROX, AT_MOST, AT_LEAST = "approximately", "at most", "at least"

_BEFORE: dict[tuple[str, ...], str] = {
    **{(w,): APPROX for w in ("about", "around", "roughly", "approximately", "approx", "~", "some", "circa", "nearly", "almost", "ca")},
    **{p: AT_MOST for p in (
        ("at", "most"), ("no", "more", "than"), ("not", "more", "than"), ("up", "to"), ("max",), ("maximum",),
        ("under",), ("less", "than"), ("below",), ("within",), ("no", "longer", "than"), ("no", "wider", "than"),
        ("no", "bigger", "than"), ("no", "larger", "than"), ("not", "exceeding"), ("<",), ("≤",),
    )},
    **{p: AT_LEAST for p in (
        ("at", "least"), ("no", "less", "than"), ("not", "less", "than"), ("min",), ("minimum",), ("over",),
        ("more", "than"), ("above",), ("no", "shorter", "than"), ("no", "narrower", "than"), ("tighter", "than"),
        (">",), ("≥",),
    )},
}  # fmt: skip
_AFTER: dict[tuple[str, ...], str] = {
    ("or", "so"): APPROX, ("ish",): APPROX,
    ("or", "less"): AT_MOST, ("at", "most"): AT_MOST, ("max",): AT_MOST, ("maximum",): AT_MOST, ("tops",): AT_MOST,
    ("or", "more"): AT_LEAST, ("at", "least"): AT_LEAST, ("minimum",): AT_LEAST, ("min",): AT_LEAST,
}  # fmt: skip
_FLOORS = {"min_radius_m", "longest_straight_m"}
_CAPS = {"max_straight_m"}
_HALL = {"hall_x_m", "hall_y_m"}


def _phrase_before(c: Canon, k: int) -> tuple[str, range] | None:
    for n in (3, 2, 1):
        if k - n < 0:
            continue
        words = tuple(c.tokens[j].canon for j in range(k - n, k))
        if words in _BEFORE:
            return _BEFORE[words], range(k - n, k)
    return None


def _phrase_after(c: Canon, k: int) -> tuple[str, range] | None:
    j = k + 1
    if j < len(c.tokens) and c.tokens[j].kind == "unit":
        j += 1
    for n in (2, 1):
        words = tuple(c.tokens[i].canon for i in range(j, min(j + n, len(c.tokens))))
        if len(words) == n and words in _AFTER:
            return _AFTER[words], range(j, j + n)
    return None


def read_hedges(c: Canon, spans: dict[str, list[tuple[int, int]]]) -> dict[str, tuple[str, tuple[int, int]]]:
    """field -> (hedge, source span of hedge and number) for every hedged stated number;
    the hedge words are consumed."""
    starts = {t.start: k for k, t in enumerate(c.tokens) if t.kind == "num"}
    out: dict[str, tuple[str, tuple[int, int]]] = {}
    for name, field_spans in spans.items():
        if name not in FIELD_RANGES:
            continue  # only numeric fields take hedges (not the name, not the order)
        for s, e in field_spans:
            for k in (starts.get(p) for p in range(s, e) if p in starts):
                if k is None:
                    continue
                hedge = c.tokens[k].hedge
                if hedge is not None:
                    out.setdefault(name, (hedge, (c.tokens[k].start, c.tokens[k].end)))
                    continue
                found = _phrase_before(c, k) or _phrase_after(c, k)
                if found is None:
                    continue
                hedge, words = found
                for j in words:
                    c.consume_token(j)
                unit = k + 1 if k + 1 < len(c.tokens) and c.tokens[k + 1].kind == "unit" else k
                lo, hi = min(words.start, k), max(words.stop - 1, unit)
                out.setdefault(name, (hedge, (c.tokens[lo].start, c.tokens[hi].end)))
    return out


def straight_caps(f: Found, hedges: dict[str, tuple[str, tuple[int, int]]]) -> None:
    """A straight bounded from above ("straights of at most 8 m", "the longest straight
    under 8 m") states the cap ``max_straight_m``, not the floor: move it there."""
    h = hedges.get("longest_straight_m")
    if h is None or h[0] != AT_MOST or "longest_straight_m" not in f.values:
        return
    value = f.values.pop("longest_straight_m")
    for span in f.spans.pop("longest_straight_m"):
        f.set("max_straight_m", value, span)
    hedges["max_straight_m"] = hedges.pop("longest_straight_m")


def apply_hedges(text: str, hedges: dict[str, tuple[str, tuple[int, int]]]) -> list[str]:
    """Warnings for bounds read as targets; :class:`RequestParseError` for a cap on a floor."""
    notes = []
    for name, (hedge, (s, e)) in hedges.items():
        if hedge == APPROX or name in _HALL or (name in _FLOORS and hedge == AT_LEAST):
            continue
        if name in _CAPS:
            if hedge == AT_MOST:
                continue
            raise RequestParseError(
                f"{name} is a maximum; {text[s:e]!r} (characters {s}-{e}) is a floor. State a cap "
                "(e.g. 'no straight longer than 8 m') or a plain value"
            )
        if name in _FLOORS:
            raise RequestParseError(
                f"{name} is a minimum; {text[s:e]!r} (characters {s}-{e}) caps it. State a floor "
                "(e.g. 'at least 2 m') or a plain value"
            )
        notes.append(f"{name}: {text[s:e]!r} is a bound; read as the target value (one value per field)")
    return notes
