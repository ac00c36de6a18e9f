"""Request text -> canonical tokens, each remembering the characters it came from.

Canonical forms make the rules short: every number (digits or words) becomes its decimal
value ("twenty-five" -> ``25``), every unit its symbol ("metres" -> ``m``), both
spellings of the driving sense ``cw`` / ``ccw``, and feature synonyms their TrackSpec
noun ("sweeping bends" -> ``sweepers``). :class:`Canon` joins the tokens with single
spaces so the rules can be regular expressions, and maps a match back to tokens and to
character spans of the original request.
"""

from __future__ import annotations

import bisect
import math
import re
from dataclasses import dataclass

from ..errors import RequestParseError
from .limits import quote
from .numbers import read_number
from .units import canonical_unit
from .vocab import FILLER

# A number is read whole: thousands separators ("4,000"), decimals and exponents ("6e1",
# "1e308"); a sign or a range dash is decided from its neighbours in :func:`_raw_items`.
_RAW = re.compile(
    r"(?P<num>\d{1,3}(?:,\d{3})+(?![\d,])(?:\.\d+)?|(?:\d+(?:\.\d+)?|\.\d+)(?:[eE][-+]?\d+)?)"
    # "f1tenth", "F1", "ROS2" are names, one word; "x15" in "20x15m" is "x" then 15
    r"|(?P<word>[xX](?=\d)|[A-Za-z]+(?:\d+[A-Za-z]+)*(?:\d+\b)?(?:['’][A-Za-z]+)?)"
    r"|(?P<other>[^\sA-Za-z\d])"
)
_GLUED = re.compile(r"([a-z]+)(\d+)$")
_DASHES = {"-", "–", "—", "‐", "−"}  # join words ("twenty-five"); a sign or a range between numbers
#: Canonical token of a range dash ("40-50 m" reads as "40 to 50 m").
RANGE_WORD = "to"

# Multi-word phrases -> one canonical token (longest first). "s" plural is kept.
_PHRASES: list[tuple[tuple[str, ...], str]] = [
    (("counter", "clock", "wise"), "ccw"),
    (("anti", "clock", "wise"), "ccw"),
    (("clock", "wise"), "cw"),
    (("counter", "clockwise"), "ccw"),
    (("anti", "clockwise"), "ccw"),
    (("counterclockwise",), "ccw"),
    (("anticlockwise",), "ccw"),
    (("ccw",), "ccw"),
    (("clockwise",), "cw"),
    (("cw",), "cw"),
    (("hair", "pin"), "hairpin"),
    (("hair", "pins"), "hairpins"),
    (("u", "turn"), "hairpin"),
    (("u", "turns"), "hairpins"),
    (("s", "bend"), "chicane"),
    (("s", "bends"), "chicanes"),
    (("s", "curve"), "chicane"),
    (("s", "curves"), "chicanes"),
    (("sports", "hall"), "hall"),
    (("sports", "halls"), "hall"),
    (("centre", "line"), "centreline"),
    (("center", "line"), "centreline"),
    (("centerline",), "centreline"),
    (("straightaway",), "straight"),
    (("straightaways",), "straights"),
    (("radii",), "radius"),
]
_NEGATED_BASE = {"can't": "can", "won't": "will", "shan't": "shall"}
_FEATURE_TAIL = {"bend", "bends", "turn", "turns", "corner", "corners", "curve", "curves"}
_FEATURES = {"hairpin", "hairpins", "chicane", "chicanes", "sweeper", "sweepers"}


@dataclass
class Tok:
    """One canonical token: its text, kind, numeric value (numbers) and source span."""

    canon: str
    kind: str  # "num" | "unit" | "word" | "punct"
    start: int
    end: int
    value: float | None = None
    hedge: str | None = None  # "approximately" for a number written "45-ish"


def _fmt(v: float) -> str:
    if float(v).is_integer() and abs(v) < 1e15:
        return str(int(v))
    return repr(float(v))


def _raw_items(text: str) -> list[tuple[str, int, int, float | None]]:
    """(word, start, end, number value or None) for each raw piece of ``text``.

    A dash right before a number is a minus sign unless a number precedes it, in which
    case it is a range ("40-50", "40 - 50"); any other dash only joins words and is dropped.
    """
    ms = list(_RAW.finditer(text))
    out: list[tuple[str, int, int, float | None]] = []
    negate_at: int | None = None  # index of a dash that is a minus sign
    for i, m in enumerate(ms):
        w = m.group()
        if m.lastgroup == "num":
            value = float(w.replace(",", ""))
            start = m.start()
            if negate_at is not None and i - 1 == negate_at:
                value, start = -value, ms[i - 1].start()
            out.append((w, start, m.end(), _finite(text, start, m.end(), value)))
            continue
        if w in _DASHES:
            nxt = ms[i + 1] if i + 1 < len(ms) else None
            prev_num = _ends_quantity(out, text, m.start())
            if nxt is not None and nxt.lastgroup == "num":
                if prev_num:
                    out.append((RANGE_WORD, m.start(), m.end(), None))
                elif nxt.start() == m.end():
                    negate_at = i
            continue
        lw = w.lower().replace("’", "'")
        glued = _GLUED.match(lw)
        if glued is not None and (glued[1] in FILLER or canonical_unit(glued[1]) is not None):
            # "lap45": a known word and a number run together, not a name like "F1"
            cut = m.start() + len(glued[1])
            out.append((w[: len(glued[1])], m.start(), cut, None))
            out.append((glued[2], cut, m.end(), _finite(text, cut, m.end(), float(glued[2]))))
            continue
        if lw.endswith("n't") and len(lw) > 3:  # "shouldn't" -> "should" + "not"
            out.append((_NEGATED_BASE.get(lw, w[:-3]), m.start(), m.end() - 3, None))
            out.append(("not", m.end() - 3, m.end(), None))
        else:
            out.append((w, m.start(), m.end(), None))
    return out


def _finite(text: str, start: int, end: int, value: float) -> float:
    if not math.isfinite(value):
        raise RequestParseError(
            f"the number {quote(text, start, end, 24)} at characters {start}-{end} is too large to be a length or a count"
        )
    return value


def _ends_quantity(items: list[tuple[str, int, int, float | None]], text: str, pos: int) -> bool:
    """Whether the pieces so far end in a number or "number unit", then only spaces up to ``pos``."""
    if not items or text[items[-1][2] : pos].strip():
        return False
    if items[-1][3] is not None:
        return True
    return len(items) > 1 and items[-2][3] is not None and canonical_unit(items[-1][0]) is not None


def tokenize(text: str) -> list[Tok]:
    """Split ``text`` into canonical tokens (see the module docstring).

    Raises :class:`RequestParseError` for a number too large to be finite.
    """
    raw = _raw_items(text)
    words = [r[0].lower().replace("’", "'") for r in raw]
    out: list[Tok] = []
    i = 0
    while i < len(raw):
        w, s, _, numv = raw[i]
        lw = words[i]
        if numv is not None:
            out.append(Tok(_fmt(numv), "num", s, raw[i][2], numv))
            i += 1
            continue
        if lw == "ish" and out and out[-1].kind == "num":  # "45-ish"
            out[-1].hedge = "approximately"
            out[-1].end = raw[i][2]
            i += 1
            continue
        if lw[0].isalpha():
            num = read_number(words, i)
            if num is not None:
                value, used = num
                out.append(Tok(_fmt(value), "num", s, raw[i + used - 1][2], value))
                i += used
                continue
            unit = canonical_unit(lw)
            if unit is not None and out and out[-1].kind == "num":
                out.append(Tok(unit, "unit", s, raw[i][2]))
                i += 1
                continue
            phrase = _match_phrase(words, i)
            if phrase is not None:
                canon, used = phrase
                out.append(Tok(canon, "word", s, raw[i + used - 1][2]))
                i += used
                continue
            # "sweeping bends" -> sweepers; "hairpin turn" -> hairpin
            if lw == "sweeping" and i + 1 < len(words) and words[i + 1] in _FEATURE_TAIL:
                plural = words[i + 1].endswith("s")
                out.append(Tok("sweepers" if plural else "sweeper", "word", s, raw[i + 1][2]))
                i += 2
                continue
            if out and out[-1].canon in _FEATURES and lw in _FEATURE_TAIL and out[-1].end == s - 1:
                prev = out[-1]
                base = prev.canon.rstrip("s")
                prev.canon = base + ("s" if lw.endswith("s") else "")
                prev.end = raw[i][2]
                i += 1
                continue
            out.append(Tok(lw, "word", s, raw[i][2]))
            i += 1
            continue
        out.append(Tok("x" if w == "×" else w, "punct", s, raw[i][2]))
        i += 1
    return _declared_units(out)


def _declared_units(toks: list[Tok]) -> list[Tok]:
    """A unit declared before its number ("lap length (m): 45", "width in cm: 120") moves
    behind the number, as an empty-span unit token; the declaration's tokens go."""
    out: list[Tok] = []
    i, n = 0, len(toks)
    while i < n:
        t, unit, j = toks[i], None, i
        if t.canon in ("(", "[") and i + 2 < n and toks[i + 2].canon in (")", "]"):
            unit, j = canonical_unit(toks[i + 1].canon), i + 3
        elif t.canon == "in" and i + 1 < n and toks[i + 1].kind == "word":
            unit, j = canonical_unit(toks[i + 1].canon), i + 2
        k = j + (1 if j < n and toks[j].canon in (":", "=") else 0)
        if unit is not None and k < n and toks[k].kind == "num" and not (k + 1 < n and toks[k + 1].kind == "unit"):
            out += toks[j : k + 1]
            out.append(Tok(unit, "unit", toks[k].end, toks[k].end))
            i = k + 1
            continue
        out.append(t)
        i += 1
    return out


def _match_phrase(words: list[str], i: int) -> tuple[str, int] | None:
    for seq, canon in _PHRASES:
        if tuple(words[i : i + len(seq)]) == seq:
            return canon, len(seq)
    return None


class Canon:
    """The canonical token string of a request, with consumption bookkeeping.

    ``text`` is the tokens joined by single spaces. A rule that matches marks its tokens
    consumed (:meth:`consume`); consumed tokens are blanked in ``text`` (same length, so
    offsets stay valid) and no later rule can match them. Blanking is deferred: ``text``
    is rebuilt once when next read, so a rule pass costs O(length), not O(length × matches).
    """

    def __init__(self, tokens: list[Tok]):
        self.tokens = tokens
        self._starts: list[int] = []
        self._ends: list[int] = []
        pos = 0
        for t in tokens:
            self._starts.append(pos)
            self._ends.append(pos + len(t.canon))
            pos += len(t.canon) + 1
        self._text = " ".join(t.canon for t in tokens)
        self._dirty = False
        self.used = [False] * len(tokens)

    @property
    def text(self) -> str:
        """The canonical string with consumed tokens blanked."""
        if self._dirty:
            self._text = " ".join("\x00" * len(t.canon) if u else t.canon for t, u in zip(self.tokens, self.used))
            self._dirty = False
        return self._text

    def token_range(self, start: int, end: int) -> range:
        """Indices of the tokens overlapping canonical characters ``[start, end)``."""
        lo = bisect.bisect_right(self._ends, start)
        hi = bisect.bisect_left(self._starts, end)
        return range(lo, hi) if lo < hi else range(0)

    def span(self, start: int, end: int) -> tuple[int, int]:
        """Source character span of canonical characters ``[start, end)``."""
        r = self.token_range(start, end)
        return self.tokens[r.start].start, self.tokens[r.stop - 1].end

    def consume(self, start: int, end: int) -> None:
        for k in self.token_range(start, end):
            self.consume_token(k)

    def consume_token(self, k: int) -> None:
        self.used[k] = True
        self._dirty = True

    def consume_source(self, start: int, end: int) -> None:
        """Consume every token inside source characters ``[start, end)``."""
        for k, t in enumerate(self.tokens):
            if t.start >= start and t.end <= end:
                self.consume_token(k)

    def start_of(self, k: int) -> int:
        """Canonical character offset of token ``k``."""
        return self._starts[k]

    def token_at(self, pos: int) -> int:
        """Index of the token containing canonical character ``pos``."""
        return self.token_range(pos, pos + 1).start
