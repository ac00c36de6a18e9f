"""The rules backend: a deterministic parser that extracts every TrackSpec field a person
would state in English and never invents one.

Each rule is a regular expression over the canonical token string of :mod:`.lexer`
(numbers as digits, units as symbols). Rules run in a fixed order -- ranges (refused),
name, hall, then quantities followed by their noun ("a 38 m lap"), then nouns followed
by their quantity ("lap of 45 m"), then values before their field ("six metres is the
longest straight"), then bare fallbacks ("60 metres long") -- and each consumes its
tokens, so no number is read twice. After the features and hedges (:mod:`.hedges`), a
lone length left over is the lap (nothing else in a track request is a bare length);
any other number left over is refused (``lenient=True``: ignored with a warning).
Words left that are not known filler are reported in :attr:`ParseResult.unparsed`.

Every rule pass is one left-to-right scan (:meth:`.lexer.Canon.text` is rebuilt once
per pass), so the work is linear in the request's length.
"""

from __future__ import annotations

import re
from collections.abc import Callable

from ..errors import RequestParseError, SpecError
from ..spec import TrackSpec
from .features import parse_features
from .found import Found
from .hedges import apply_hedges, read_hedges, straight_caps
from .lexer import Canon, tokenize
from .limits import MAX_REQUEST_CHARS, check_length, quote
from .result import FIELDS, Fragment, ParseResult
from .units import to_metres
from .vocab import CORR, CORRIDOR_NOUNS, FILL, FILLER, HALL, LAP, LAP_NOUNS, NUM, UNIT, alt

_B, _E = r"(?<![^ ])", r"(?![^ ])"  # token boundaries in the canonical string


def _q(name: str) -> str:
    return rf"(?P<{name}>{NUM})(?: (?P<{name}u>{UNIT}))?"


def _rx(body: str) -> re.Pattern[str]:
    return re.compile(_B + body + _E)


# A quantity that is not the start of a hall pair or a feature count.
_QEND = r"(?! (?:x|by|\d|hairpins?|chicanes?|sweepers?)(?: |$))"
_LONG = alt("long", "in length", "length")
_LENGTHN = alt("length", "distance", "circumference", "perimeter")
_WIDE = alt("wide", "in width", "width", "across")
_MINR = "(?:" + alt("minimum", "min", "smallest", "tightest", "least", "lowest") + " )?"
_RKIND = "(?:" + alt("turning", "turn", "corner", "cornering", "curve", "bend", "centreline", "curvature") + " )?"
_STRAIGHT_ADJ = "(?:" + alt("longest", "main", "long", "back", "home", "front", "start", "finish") + " )?"
#: Words that make a straight a cap ("max straight 3 m") or a floor ("min straight 3 m").
_CAP = alt("max", "max .", "maximum", "at most", "maximal", "biggest allowed", "largest allowed")
_FLOOR = alt("min", "min .", "minimum", "at least", "minimal")
_TURNS = alt("turn", "turns", "corner", "corners", "bend", "bends", "curve", "curves")

Handler = Callable[[re.Match[str], Canon, Found], None]


def _qty(m: re.Match[str], name: str, fallback_unit: str | None = None) -> float:
    return to_metres(float(m[name]), m[name + "u"] or fallback_unit)


def _span(c: Canon, m: re.Match[str], group: str | int = 0) -> tuple[int, int]:
    return c.span(m.start(group), m.end(group))


def _qspan(c: Canon, m: re.Match[str], name: str) -> tuple[int, int]:
    end = m.end(name + "u") if m[name + "u"] else m.end(name)
    return c.span(m.start(name), end)


def _hall_pair(m: re.Match[str], c: Canon, f: Found) -> None:
    # "15 by 12 m": a unit given once applies to both numbers.
    a, b = _qty(m, "a", m["bu"]), _qty(m, "b", m["au"])
    wa, wb = m["wa"] or "", m["wb"] or ""
    if "wide" in wa or "width" in wa or "long" in wb or "length" in wb:
        a, b = b, a  # "15 m wide by 20 m long": x is the length
        sa, sb = _qspan(c, m, "b"), _qspan(c, m, "a")
    else:
        sa, sb = _qspan(c, m, "a"), _qspan(c, m, "b")
    f.set("hall_x_m", a, sa)
    f.set("hall_y_m", b, sb)


def _setter(name: str, q: str = "q") -> Handler:
    def handle(m: re.Match[str], c: Canon, f: Found) -> None:
        f.set(name, _qty(m, q), _span(c, m))

    return handle


def _hall_one(m: re.Match[str], c: Canon, f: Found) -> None:
    which = m["w"]
    name = "hall_y_m" if ("wide" in which or "width" in which or "across" in which) else "hall_x_m"
    f.set(name, _qty(m, "q"), _span(c, m))


# A number right after a field noun belongs to that noun ("width 1.2 m lap 40 m"): the
# quantity-before-noun rules must not take it for the noun that follows.
_FREE = "".join(
    f"(?<!{w} )" for w in sorted({*LAP_NOUNS, *CORRIDOR_NOUNS, "width", "radius", "straight", "straights", "length"})
)
_DIM = rf"(?: (?P<wa>{_LONG}|{_WIDE}))?"
# "one lap", "two laps" count laps: a unitless 1 before a lap noun, or a unitless number
# before a plural one, is not a length.
_NOT_LAP_COUNT = rf"(?!1 {LAP}(?: |$))(?!{NUM} {alt(*[w for w in LAP_NOUNS if w.endswith('s')])}(?: |$))"
# Words that may join a value to the field after it ("6 m is the longest straight").
_CONN = (
    "(?:"
    + alt(
        "is",
        "as",
        "for",
        "of",
        "be",
        "being",
        "the",
        "my",
        "our",
        "its",
        "a",
        "an",
        "should",
        "must",
        "will",
        "would",
        "to",
    )
    + " ){0,3}"
)
# "between 40 and 50 m", "40-50 m", "from 40 to 50", "2 or 3 hairpins": refused.
_RANGE = _rx(
    rf"between {NUM}(?: {UNIT})? and {NUM}(?: {UNIT})?|(?:from )?{NUM}(?: {UNIT})? (?:to|or) {NUM}(?: {UNIT})?"
)
_HALL_TAIL = rf"(?: {HALL})?"

# (pattern, handler) in the order they run.
RULES: list[tuple[re.Pattern[str], Handler]] = [
    # -- hall: "15 by 12 m hall", "15x12", "20 m long by 15 m wide", "a hall of 20 x 15 m"
    (
        _rx(
            rf"(?:{HALL} (?:{FILL}))?{_q('a')}{_DIM} (?:x|by|times) {_q('b')}(?: (?P<wb>{_LONG}|{_WIDE}))?{_HALL_TAIL}"
        ),
        _hall_pair,
    ),
    # "a hall 15 m wide and 12 m long", "hall: 20 m long, 15 m wide"
    (
        _rx(
            rf"{HALL} (?:{FILL}){_q('a')} (?P<wa>{_LONG}|{_WIDE})(?: and| ,)? (?:{FILL}){_q('b')} (?P<wb>{_LONG}|{_WIDE})"
        ),
        _hall_pair,
    ),
    # "15 m wide and 12 m long hall"
    (_rx(rf"{_q('a')} (?P<wa>{_LONG}|{_WIDE})(?: and| ,| by)? {_q('b')} (?P<wb>{_LONG}|{_WIDE}) {HALL}"), _hall_pair),
    # "hall width of 15 m", "a hall 20 m long", "a 20 m long hall"
    (_rx(rf"{HALL} (?:{FILL})(?P<w>{_LONG}|{_WIDE}) (?:{FILL}){_q('q')}{_QEND}"), _hall_one),
    (_rx(rf"{HALL} (?:{FILL}){_q('q')} (?P<w>{_LONG}|{_WIDE})"), _hall_one),
    (_rx(rf"{_q('q')} (?P<w>{_LONG}|{_WIDE}) {HALL}"), _hall_one),
    # -- the speed cap: "no straight longer than 8 m", "no straight is over 8 m long"
    (
        _rx(
            rf"(?:no|not a|not one|never a) (?:single )?{_STRAIGHT_ADJ}straights? (?:(?:is|should be|may be|must be|can be) )?"
            rf"(?:longer than|more than|over|above|exceeding|exceeds) {_q('q')}(?: long| in length)?{_QEND}"
        ),
        _setter("max_straight_m"),
    ),
    # -- a capped straight: "max straight 3 m", "maximum straight length of 3 m", "3 m max
    # straight", "at most a 3 m straight" is the cap max_straight_m, never the floor
    (
        _rx(rf"{_CAP} (?:{_STRAIGHT_ADJ})?straights?(?: length)? (?:{FILL}){_q('q')}(?: long| in length)?{_QEND}"),
        _setter("max_straight_m"),
    ),
    (_rx(rf"{_FREE}{_q('q')} (?:long )?{_CAP} {_STRAIGHT_ADJ}straights?(?: length)?"), _setter("max_straight_m")),
    # ... and a "min"/"minimum" one the floor longest_straight_m, whose meaning it is
    (
        _rx(rf"{_FLOOR} (?:{_STRAIGHT_ADJ})?straights?(?: length)? (?:{FILL}){_q('q')}(?: long| in length)?{_QEND}"),
        _setter("longest_straight_m"),
    ),
    # -- quantity then noun ("no turn tighter than 2 m radius" first: it ends in "radius")
    (
        _rx(rf"(?:{FILL})?(?:no|not|never) (?:{_TURNS} )?(?:{FILL})tighter than (?:a )?{_q('q')}(?: radius)?{_QEND}"),
        _setter("min_radius_m"),
    ),
    (_rx(rf"{_FREE}{_q('q')} {_MINR}{_RKIND}radius"), _setter("min_radius_m")),
    (_rx(rf"{_FREE}{_q('q')} (?:long )?{_STRAIGHT_ADJ}straights?"), _setter("longest_straight_m")),
    (
        _rx(rf"{_FREE}{_q('q')} (?:{_WIDE} )?(?:{CORR}|(?:{LAP} )?width)|{_q('p')} {_WIDE} {LAP}"),
        lambda m, c, f: f.set("corridor_width_m", _qty(m, "q" if m["q"] else "p"), _span(c, m)),
    ),
    (
        _rx(
            rf"{_FREE}{_NOT_LAP_COUNT}{_q('q')} (?:long )?{LAP}(?: length)?|{_q('p')} (?:per|a|each) lap"
            rf"|{_q('t')} (?:in )?(?:total|overall)(?: (?:{LAP} )?{_LENGTHN})?"
        ),
        lambda m, c, f: f.set("lap_length_m", _qty(m, next(g for g in "qpt" if m[g])), _span(c, m)),
    ),
    # -- noun then quantity
    (_rx(rf"{_MINR}{_RKIND}radius (?:{FILL}){_q('q')}{_QEND}"), _setter("min_radius_m")),
    (
        _rx(rf"{alt('tightest', 'smallest', 'sharpest')} {_TURNS} (?:{FILL}){_q('q')}(?: radius)?{_QEND}"),
        _setter("min_radius_m"),
    ),
    (_rx(rf"{_STRAIGHT_ADJ}straights? (?:{FILL}){_q('q')}(?: long| in length)?{_QEND}"), _setter("longest_straight_m")),
    (_rx(rf"(?:(?:{CORR}|{LAP}) )?width (?:{FILL}){_q('q')}{_QEND}"), _setter("corridor_width_m")),
    (
        _rx(rf"(?:{CORR}|{LAP}) (?:{FILL}){_q('q')} {_WIDE}|{CORR} (?:{FILL}){_q('p')}{_QEND}"),
        lambda m, c, f: f.set("corridor_width_m", _qty(m, "q" if m["q"] else "p"), _span(c, m)),
    ),
    (_rx(rf"(?:(?:{LAP}|total|overall) )?(?:{LAP} )?{_LENGTHN} (?:{FILL}){_q('q')}{_QEND}"), _setter("lap_length_m")),
    (_rx(rf"{LAP} (?:{FILL}){_q('q')}(?: {_LONG}| around| round)?{_QEND}"), _setter("lap_length_m")),
    # -- value before field: "six metres is the longest straight", "25 metres of lap"
    (_rx(rf"{_FREE}{_q('q')} {_CONN}{_STRAIGHT_ADJ}straights?"), _setter("longest_straight_m")),
    (_rx(rf"{_FREE}{_q('q')} {_CONN}{_MINR}{_RKIND}radius"), _setter("min_radius_m")),
    (_rx(rf"{_FREE}{_q('q')} {_CONN}(?:{CORR}|(?:{LAP} )?width)"), _setter("corridor_width_m")),
    (_rx(rf"{_FREE}{_NOT_LAP_COUNT}{_q('q')} {_CONN}{LAP}(?: {_LENGTHN})?"), _setter("lap_length_m")),
    # -- bare fallbacks: "60 metres long", "1.5 m wide"
    (_rx(rf"{_q('q')} (?:{_LONG}|around|round)"), _setter("lap_length_m")),
    (_rx(rf"{_q('q')} {_WIDE}"), _setter("corridor_width_m")),
]


# -- name ------------------------------------------------------------------------------
_NAME_KEY = re.compile(
    r"\b(?:called|named|titled|entitled|call(?:\s+(?:it|this|the\s+(?:track|circuit|map|layout)))?"
    r"|(?:its |the |with the )?name(?:\s+(?:it|is|of|should be|this|the\s+(?:track|circuit|map|layout)))?\s*[:=]?)\s+",
    re.IGNORECASE,
)
_QUOTED = re.compile(r"[\"“'‘]([^\"”’]+?)[\"”'’](?=\W|$)")
_NAME_STOP = (
    "with|in|for|and|that|which|having|featuring|where|has|is|at|on|to|inside|using|driven|"
    "running|going|containing|including|plus|a|an|the|of|clockwise|anticlockwise|counterclockwise|"
    "counter|anti|cw|ccw|fitting|fits|lap|measuring|then|but|please|it"
)
_UNQUOTED = re.compile(rf"[A-Za-z0-9][\w'’-]*(?:[ \t]+(?!(?:{_NAME_STOP})\b)[A-Za-z0-9][\w'’-]*)*", re.IGNORECASE)


def _find_name(text: str, f: Found) -> tuple[int, int, int] | None:
    """(keyword start, name start, name end) of a "called X" / "named 'X'" clause."""
    for k in _NAME_KEY.finditer(text):
        rest = k.end()
        q = _QUOTED.match(text, rest)
        if q is not None:
            name, s, e = q.group(1).strip(), q.start(1), q.end(1)
            end = q.end()
        else:
            u = _UNQUOTED.match(text, rest)
            if u is None:
                continue
            name, s, e = u.group(), u.start(), u.end()
            end = e
        if not name:
            continue
        f.set("name", name, (s, e))
        return k.start(), s, end
    return None


def _direction(c: Canon, f: Found) -> None:
    found: dict[str, list[tuple[int, int]]] = {}
    for k, t in enumerate(c.tokens):
        if c.used[k] or t.canon not in ("cw", "ccw"):
            continue
        sense = t.canon
        start = k
        back = [c.tokens[j].canon for j in range(max(0, k - 2), k)]
        if any(w in ("not", "n't", "never") or w.endswith("n't") for w in back):
            sense = "ccw" if sense == "cw" else "cw"  # "not clockwise": only two senses exist
            start = next(
                j
                for j in range(max(0, k - 2), k)
                if c.tokens[j].canon in ("not", "never") or c.tokens[j].canon.endswith("n't")
            )
        for j in range(start, k + 1):
            c.consume_token(j)
        found.setdefault(sense, []).append((c.tokens[start].start, t.end))
    if len(found) > 1:
        raise RequestParseError(
            "contradictory driving directions: the request says both clockwise and counter-clockwise"
        )
    for sense, spans in found.items():
        for sp in spans:
            f.set("direction", "clockwise" if sense == "cw" else "counterclockwise", sp)


_QUALIFIERS = {
    "min_radius_m": {"tightest", "smallest", "sharpest", "minimum", "min", "lowest", "least", "radius"},
    "longest_straight_m": {"longest", "straight", "straights"},
    "max_straight_m": {"longest", "straight", "straights"},
    "corridor_width_m": {"width", "wide"},
}


def _qualifiers(c: Canon, f: Found) -> None:
    """Words that only qualify a stated field ("the tightest corner ... radius of 2 m")."""
    for name, words in _QUALIFIERS.items():
        if name in f.values:
            for k, t in enumerate(c.tokens):
                if not c.used[k] and t.canon in words:
                    c.consume_token(k)


def _unparsed(text: str, c: Canon) -> tuple[Fragment, ...]:
    frags: list[list[int]] = []
    for k, t in enumerate(c.tokens):
        after_number = k > 0 and c.tokens[k - 1].kind == "num" and not c.used[k - 1] and t.kind == "word"
        if c.used[k] or t.kind == "punct" or (t.kind == "word" and t.canon in FILLER and not after_number):
            continue
        if t.kind == "unit":
            continue  # a unit on its own ("metres") says nothing
        if frags and frags[-1][-1] == k - 1:
            frags[-1].append(k)
        else:
            frags.append([k])
    out = []
    for ks in frags:
        s, e = c.tokens[ks[0]].start, c.tokens[ks[-1]].end
        out.append(Fragment(text[s:e], s, e))
    return tuple(out)


def _refuse_ranges(text: str, c: Canon) -> None:
    m = _RANGE.search(c.text)
    if m is not None:
        s, e = c.span(m.start(), m.end())
        raise RequestParseError(
            f"the request gives a range, {quote(text, s, e)} (characters {s}-{e}); a TrackSpec field takes one value: state one"
        )


_SCALE = _rx(rf"(?P<a>{NUM}) (?::|/) (?P<b>{NUM})(?P<s> scale[ds]?)?")


def _scale(text: str, c: Canon) -> None:
    """ "1:10 scale": the arena's fixed scale, explained; any other scale is refused."""
    for m in _SCALE.finditer(c.text):
        one_tenth = float(m["a"]) == 1 and float(m["b"]) == 10
        if one_tenth:
            c.consume(m.start(), m.end())
        elif m["s"]:
            s, e = c.span(m.start(), m.end())
            raise RequestParseError(
                f"{quote(text, s, e)} (characters {s}-{e}): RoboRacer Arena builds 1:10-scale tracks only"
            )


def _is_pronoun(text: str, c: Canon, k: int) -> bool:
    """ "one" as a pronoun ("a track, one with a chicane"), not a quantity."""
    t = c.tokens[k]
    nxt = c.tokens[k + 1] if k + 1 < len(c.tokens) else None
    return text[t.start : t.end].lower() == "one" and (nxt is None or nxt.kind != "unit")


def _leftover_numbers(text: str, c: Canon, f: Found) -> list[Fragment]:
    """Numbers no rule attributed. A lone length (number + unit) is the lap when the lap is
    not stated: a track request has no other bare length."""
    left = [k for k, t in enumerate(c.tokens) if t.kind == "num" and not c.used[k] and not _is_pronoun(text, c, k)]
    lengths = [k for k in left if k + 1 < len(c.tokens) and c.tokens[k + 1].kind == "unit"]
    if "lap_length_m" not in f.values and len(lengths) == 1:
        k = lengths[0]
        value = to_metres(float(c.tokens[k].value or 0.0), c.tokens[k + 1].canon)
        f.set("lap_length_m", value, (c.tokens[k].start, c.tokens[k + 1].end))
        c.consume_token(k)
        c.consume_token(k + 1)
        left.remove(k)
    out = []
    for k in left:
        t = c.tokens[k]
        end = c.tokens[k + 1].end if k + 1 < len(c.tokens) and c.tokens[k + 1].kind == "unit" else t.end
        out.append(Fragment(text[t.start : end], t.start, end))  # left unconsumed: still "unparsed"
    return out


def _listing(numbers: list[Fragment], shown: int = 5) -> str:
    out = ", ".join(f"{quote(n.text, 0, len(n.text))} (characters {n.start}-{n.end})" for n in numbers[:shown])
    return out + (f" and {len(numbers) - shown} more" if len(numbers) > shown else "")


def refuse_numbers(text: str, numbers: list[Fragment]) -> None:
    """Refuse a request with numbers no field explains (the "nothing silently defaulted" rule)."""
    if not numbers:
        return
    listing = _listing(numbers)
    raise RequestParseError(
        f"the request states {listing}, which no TrackSpec field explains; say what it is "
        "(e.g. 'a 45 m lap', '2 hairpins') or ignore it with --lenient (lenient=True)"
    )


def ignored_note(numbers: list[Fragment]) -> str:
    """The lenient-mode warning for unexplained numbers."""
    listing = _listing(numbers)
    return f"lenient: ignored {listing}, which no TrackSpec field explains; the fields they may have meant keep their defaults"


def parse_rules(text: str, *, lenient: bool = False, max_chars: int | None = MAX_REQUEST_CHARS) -> ParseResult:
    """Parse ``text`` with the rules backend.

    Raises :class:`RequestParseError` on an empty or over-long request
    (:data:`.limits.MAX_REQUEST_CHARS`; ``max_chars=None`` lifts the cap), a range, a
    contradiction, a value outside its field's range, a number no field explains (unless
    ``lenient``: then it is ignored with a warning), or stated values that do not form a
    valid TrackSpec.
    """
    check_length(text, max_chars)
    f = Found(text)
    c = Canon(tokenize(text))
    _refuse_ranges(text, c)
    _scale(text, c)
    named = _find_name(text, f)
    if named is not None:
        c.consume_source(named[0], named[2])
    for rx, handle in RULES:
        for m in rx.finditer(c.text):  # a handler consumes only its own match
            handle(m, c, f)
            c.consume(m.start(), m.end())
    _direction(c, f)
    parse_features(c, f)
    _qualifiers(c, f)
    hedges = read_hedges(c, f.spans)
    straight_caps(f, hedges)
    notes = apply_hedges(text, {k: v for k, v in hedges.items() if k in f.values})
    stray = _leftover_numbers(text, c, f)
    if stray and not lenient:
        refuse_numbers(text, stray)
    if stray:
        notes.append(ignored_note(stray))
    result = finish(text, f, _unparsed(text, c), backend="rules")
    return result.replace(
        warnings=tuple(notes),
        hedges={k: h for k, (h, _) in hedges.items() if k in result.stated},
        ignored=tuple(stray),
    )


def finish(text: str, f: Found, unparsed: tuple[Fragment, ...], backend: str) -> ParseResult:
    """Validate the found values as a TrackSpec and package the result."""
    try:
        spec = TrackSpec.from_dict(dict(f.values), source="request")
    except SpecError as e:
        raise RequestParseError(f"the request's stated values do not form a valid TrackSpec: {e}") from e
    stated = tuple(k for k in FIELDS if k in f.values)
    spans = {k: tuple(sorted(set(f.spans[k]))) for k in stated}
    return ParseResult(text=text, spec=spec, stated=stated, spans=spans, unparsed=unparsed, backend=backend)
