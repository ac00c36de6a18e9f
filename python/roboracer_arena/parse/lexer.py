"""Request text -> canonical tokens, each remembering the characters it came from.

Canonical forms make the rules short: every number (digits or words) becomes its decimal
value ("twenty-five" -> ``25``), every unit its symbol ("metres" -> ``m``), both
spellings of the driving sense ``cw`` / ``ccw``, and feature synonyms their TrackSpec
noun ("sweeping bends" -> ``sweepers``). :class:`Canon` joins the tokens with single
spaces so the rules can be regular expressions, and maps a match back to tokens and to
character spans of the original request.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .numbers import read_number
from .units import canonical_unit

_RAW = re.compile(r"\d+(?:\.\d+)?|\.\d+|[A-Za-z]+(?:['’][A-Za-z]+)?|[^\sA-Za-z\d]")
_DROPPED = {"-", "–", "—", "‐"}  # hyphens and dashes join words; they carry no meaning

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


def _fmt(v: float) -> str:
    return str(int(v)) if float(v).is_integer() else repr(float(v))


def tokenize(text: str) -> list[Tok]:
    """Split ``text`` into canonical tokens (see the module docstring)."""
    raw = []
    for m in _RAW.finditer(text):
        w = m.group()
        if w in _DROPPED:
            continue
        lw = w.lower().replace("’", "'")
        if lw.endswith("n't") and len(lw) > 3:  # "shouldn't" -> "should" + "not"
            base = _NEGATED_BASE.get(lw, w[:-3])
            raw.append((base, m.start(), m.end() - 3))
            raw.append(("not", m.end() - 3, m.end()))
        else:
            raw.append((w, m.start(), m.end()))
    words = [r[0].lower().replace("’", "'") for r in raw]
    out: list[Tok] = []
    i = 0
    while i < len(raw):
        w, s, _ = raw[i]
        lw = words[i]
        if lw[0].isdigit() or (lw[0] == "." and len(lw) > 1):
            out.append(Tok(_fmt(float(lw)), "num", s, raw[i][2], float(lw)))
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
    offsets stay valid) and no later rule can match them.
    """

    def __init__(self, tokens: list[Tok]):
        self.tokens = tokens
        parts, self._starts = [], []
        pos = 0
        for t in tokens:
            self._starts.append(pos)
            parts.append(t.canon)
            pos += len(t.canon) + 1
        self.text = " ".join(parts)
        self.used = [False] * len(tokens)

    def token_range(self, start: int, end: int) -> range:
        """Indices of the tokens overlapping canonical characters ``[start, end)``."""
        idx = [k for k, s in enumerate(self._starts) if s < end and s + len(self.tokens[k].canon) > start]
        return range(idx[0], idx[-1] + 1) if idx else range(0)

    def span(self, start: int, end: int) -> tuple[int, int]:
        """Source character span of canonical characters ``[start, end)``."""
        r = self.token_range(start, end)
        return self.tokens[r.start].start, self.tokens[r.stop - 1].end

    def consume(self, start: int, end: int) -> None:
        for k in self.token_range(start, end):
            self.consume_token(k)

    def consume_token(self, k: int) -> None:
        self.used[k] = True
        s = self._starts[k]
        n = len(self.tokens[k].canon)
        self.text = self.text[:s] + "\x00" * n + self.text[s + n :]

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
