"""Feature counts and feature order: "two hairpins", "no chicanes or sweepers", "a pair
of sweeping bends", "two sweepers then a hairpin", "first a chicane, followed by ...",
"a chicane after two hairpins", "hairpin, chicane and sweeper, in that order".

A *mention* is one feature noun with what counts it: a number ("2 hairpins"), a single
("a", "another"), a zero ("no", "without"), a reference ("the hairpins") or nothing (a
bare noun). Counts add up over mentions, except that a numbered count repeating one
already given, with no order word between them and no "more"/"another"/"extra", restates
it: equal, it is the same count; different, the request is refused. Mentions linked by
order words form an ordered run, which becomes ``feature_order``; a request with no order
words leaves it empty.
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass

from ..errors import RequestParseError
from .found import Found
from .lexer import Canon
from .limits import check_range, quote
from .vocab import FEATURE_ADJ, FEATURE_NOUN, FEATURE_RE, NUM, ORDER_FORWARD, ORDER_REVERSE, ORDER_START

_B, _E = r"(?<![^ ])", r"(?![^ ])"
_ADJS = rf"(?:{FEATURE_ADJ} ){{0,4}}"  # bounded: no regex backtracking over long runs
_F = rf"(?P<f>{FEATURE_RE})"
_ZERO_LIST = re.compile(
    _B
    + rf"(?:no|zero|without(?: any)?) {_ADJS}{FEATURE_RE}(?: (?:or|nor|and|,) (?:(?:no|any) )?{_ADJS}{FEATURE_RE})*"
    + _E
)
_FEATURE_WORD = re.compile(_B + FEATURE_RE + _E)
_COUNTED = [
    re.compile(_B + rf"(?P<n>{NUM})(?: x)? {_ADJS}{_F}" + _E),
    re.compile(_B + rf"(?P<one>a single|single|another|a|an) {_ADJS}{_F}" + _E),
    re.compile(_B + rf"{_F} (?::|=|x) (?P<n>{NUM})" + _E),
]
_EACH = re.compile(
    _B + rf"(?P<n>\d+) {_ADJS}(?P<f1>{FEATURE_RE})(?: ,)? each (?:followed by|then|leading into|with|before) "
    rf"(?P<m>a|an|a single|\d+) {_ADJS}(?P<f2>{FEATURE_RE})" + _E
)
_REF = re.compile(_B + rf"(?:the|both|these|those|each|every|its|their|all|said)(?: \d+)? {_ADJS}{_F}" + _E)
_BARE = re.compile(_B + rf"{_ADJS}{_F}" + _E)
_IN_ORDER = re.compile(_B + r"in (?:(?:that|this|the|exactly|strict|given|listed|following) )*(?:order|sequence)" + _E)
_ADDITIVE = {"more", "extra", "additional", "another", "further"}
_ORDER_GLUE = {"by", "comes", "come", "order", "sequence", "that", "this", "which", "it", "them", "and", "then"}


@dataclass
class Mention:
    feature: str  # "hairpin" | "chicane" | "sweeper"
    kind: str  # "count" | "zero" | "ref" | "bare"
    count: int
    first: int  # token indices [first, last]
    last: int
    span: tuple[int, int]
    block: list[str] | None = None  # "2 hairpins, each followed by a chicane": h c h c
    absorbed: bool = False  # the "chicane" of that phrase: counted, ordered by ``block``
    restated: bool = False  # a numbered count without "more"/"another"/...: a restatement if repeated


def _feature(word: str) -> str:
    return word.rstrip("s")


def _collect(c: Canon, text: str) -> list[Mention]:
    out: list[Mention] = []

    def add(m: re.Match[str], feature: str, kind: str, count: int, group: str | int = 0) -> None:
        r = c.token_range(m.start(group), m.end(group))
        out.append(Mention(feature, kind, count, r.start, r.stop - 1, c.span(m.start(group), m.end(group))))

    for m in _EACH.finditer(c.text):
        n, k = int(m["n"]), (1 if not m["m"][0].isdigit() else int(m["m"]))
        f1, f2 = _feature(m["f1"]), _feature(m["f2"])
        add(m, f1, "count", n, "f1")
        out[-1].block = ([f1] + [f2] * k) * n
        add(m, f2, "count", n * k, "f2")
        out[-1].absorbed = True
        out[-1].span = out[-2].span = c.span(m.start(), m.end())
        c.consume(m.start(), m.end())
    for m in _ZERO_LIST.finditer(c.text):
        for fm in _FEATURE_WORD.finditer(m.group()):
            r = c.token_range(m.start() + fm.start(), m.start() + fm.end())
            out.append(Mention(_feature(fm.group()), "zero", 0, r.start, r.stop - 1, c.span(m.start(), m.end())))
        c.consume(m.start(), m.end())
    for rx in _COUNTED:
        for m in rx.finditer(c.text):
            if m.groupdict().get("one"):
                n = 1
            else:
                value = float(m["n"])
                if not value.is_integer():
                    s0, e0 = c.span(m.start(), m.end())
                    raise RequestParseError(
                        f"a feature count must be a whole number: {quote(text, s0, e0)} (characters {s0}-{e0})"
                    )
                n = int(value)
            add(m, _feature(m["f"]), "zero" if n == 0 else "count", n)
            out[-1].restated = m.groupdict().get("n") is not None and not _ADDITIVE & set(m.group().split())
            c.consume(m.start(), m.end())
    refs = list(_REF.finditer(c.text))
    ref_nouns = {r.start("f") for r in refs}
    for m in refs:
        add(m, _feature(m["f"]), "ref", 0)
    for m in _BARE.finditer(c.text):
        if m.start("f") in ref_nouns:
            continue  # the noun of a reference ("the hairpins")
        add(m, _feature(m["f"]), "bare-plural" if m["f"].endswith("s") else "bare", 0)
    out.sort(key=lambda x: x.first)
    return out


def _link(c: Canon, a: Mention, b: Mention) -> str:
    """How mention ``a`` leads to ``b``: "forward", "reverse", "list" or "break"."""
    words = [t.canon for t in c.tokens[a.last + 1 : b.first]]
    for k, w in enumerate(words):
        nxt = words[k + 1] if k + 1 < len(words) else ""
        if w == "followed" or (w in ORDER_FORWARD and w != "preceding"):
            return "forward"
        if (
            w == "preceded"
            or w == "preceding"
            or (w in ORDER_REVERSE and nxt not in ("that", "which", "this", "it", "those"))
        ):
            return "reverse"
        if w == "after":  # "after that": forward
            return "forward"
    if any(w in (".", ";", "!", "?") for w in words):
        return "break"
    return "list"


def _runs(c: Canon, ms: list[Mention]) -> list[tuple[list[Mention], list[str]]]:
    runs: list[tuple[list[Mention], list[str]]] = []
    for k, m in enumerate(ms):
        if k == 0:
            runs.append(([m], []))
            continue
        link = _link(c, ms[k - 1], m)
        if link == "break":
            runs.append(([m], []))
        else:
            runs[-1][0].append(m)
            runs[-1][1].append(link)
    return runs


def _is_ordered(c: Canon, run: list[Mention], links: list[str], next_first: int) -> tuple[bool, list[int]]:
    """Whether a run orders its features, and the tokens of its order words."""
    glue: list[int] = []
    ordered = any(link in ("forward", "reverse") for link in links)
    before = range(max(0, run[0].first - 4), run[0].first)
    if any(c.tokens[j].canon in ORDER_START or c.tokens[j].canon == "order" for j in before):
        ordered = True
    end_tok = next_first if next_first >= 0 else len(c.tokens)
    end_pos = c.start_of(end_tok) if end_tok < len(c.tokens) else len(c.text)
    m = _IN_ORDER.search(c.text, c.start_of(run[-1].last), end_pos)  # bounded: linear over all runs
    if m is not None and c.token_at(m.start()) < end_tok:
        ordered = True
        glue += list(c.token_range(m.start(), m.end()))
    if ordered:
        lo = max(0, run[0].first - 4)
        for j in range(lo, run[-1].last + 1):
            w = c.tokens[j].canon
            if not c.used[j] and (w in ORDER_FORWARD or w in ORDER_REVERSE or w in ORDER_START or w in _ORDER_GLUE):
                glue.append(j)
    return ordered, glue


def parse_features(c: Canon, f: Found) -> None:
    """Find feature counts and order in ``c``; record them in ``f``; consume their tokens."""
    ms = _collect(c, f.text)
    counted = {m.feature for m in ms if m.kind == "count"}
    counts: Counter[str] = Counter()
    zero: dict[str, Mention] = {}
    for i, m in enumerate(ms):
        if m.kind == "bare":  # a bare singular noun: a reference, or one item of a list
            listed = (i > 0 and _link(c, ms[i - 1], m) != "break") or (
                i + 1 < len(ms) and _link(c, m, ms[i + 1]) != "break"
            )
            if m.feature in counted:
                m.kind = "ref"
            elif listed:
                m.kind, m.count = "count", 1
        if m.kind == "bare-plural" and m.feature in counted:
            m.kind = "ref"
    _restated_counts(c, f, ms)
    for m in ms:
        field = FEATURE_NOUN[m.feature]
        if m.kind == "count":
            counts[m.feature] += m.count
            f.spans.setdefault(field, []).append(m.span)
        elif m.kind == "zero":
            zero[m.feature] = m
            f.spans.setdefault(field, []).append(m.span)
        if m.kind in ("count", "ref"):
            for j in range(m.first, m.last + 1):
                c.consume_token(j)
    for feat, zm in zero.items():
        if counts[feat] > 0:
            raise RequestParseError(
                f"contradictory {FEATURE_NOUN[feat]}: {f.text[zm.span[0] : zm.span[1]]!r} but also {counts[feat]} stated"
            )
        f.values[FEATURE_NOUN[feat]] = 0
    for feat, n in counts.items():
        spans = f.spans[FEATURE_NOUN[feat]]
        check_range(FEATURE_NOUN[feat], n, f.text, (min(a for a, _ in spans), max(b for _, b in spans)))
        f.values[FEATURE_NOUN[feat]] = n
    _order(c, f, [m for m in ms if m.kind in ("count", "ref")], counts)


def _restated_counts(c: Canon, f: Found, ms: list[Mention]) -> None:
    """ "a dozen chicanes? No, just two chicanes": a numbered count of a feature already
    counted, with no "more"/"another"/"extra" and no order word between them ("3 hairpins,
    then a chicane, then 2 hairpins" adds up), restates the count. An equal restatement is a
    reference; a different one is a contradiction (a correction is not guessed)."""
    ordered_before = [0]  # ordered links among ms[0..k]
    for a, b in zip(ms, ms[1:]):
        ordered_before.append(ordered_before[-1] + (_link(c, a, b) in ("forward", "reverse")))
    first: dict[str, int] = {}
    for k, m in enumerate(ms):
        if m.kind != "count" or m.absorbed:
            continue
        j = first.setdefault(m.feature, k)
        if j == k or not m.restated or ordered_before[k] > ordered_before[j]:
            continue
        if m.count == ms[j].count:
            m.kind = "ref"
            continue
        sa, sb = ms[j].span, m.span
        raise RequestParseError(
            f"the request states {FEATURE_NOUN[m.feature]} twice with different counts: "
            f"{quote(f.text, *sa)} (characters {sa[0]}-{sa[1]}) and {quote(f.text, *sb)} (characters {sb[0]}-{sb[1]}); "
            "say 'more' or 'another' to add"
        )


def _order(c: Canon, f: Found, ms: list[Mention], counts: Counter[str]) -> None:
    runs = _runs(c, ms)
    ordered_runs = []
    for k, (run, links) in enumerate(runs):
        next_first = runs[k + 1][0][0].first if k + 1 < len(runs) else -1
        ok, glue = _is_ordered(c, run, links, next_first)
        if ok and len(run) >= 2:
            ordered_runs.append((run, links, glue))
    if not ordered_runs:
        _first_or_last(c, f, ms, counts)
        return
    if len(ordered_runs) > 1:
        raise RequestParseError("the request gives two separate feature orders; state one sequence")
    run, links, glue = ordered_runs[0]
    seq: list[list[str]] = []
    for k, m in enumerate(run):
        if m.absorbed:
            continue
        if m.block is not None:
            seq.append(m.block)
            continue
        n = m.count if m.kind == "count" else counts[m.feature]
        if n == 0:
            raise RequestParseError(f"the feature order names {m.feature}s but the request gives no count for them")
        item = [m.feature] * n
        if k > 0 and links[k - 1] == "reverse":
            seq.insert(len(seq) - 1, item)
        else:
            seq.append(item)
    order = [x for item in seq for x in item]
    if Counter(order) != +counts:
        want = ", ".join(f"{n} {feat}(s)" for feat, n in sorted(counts.items()) if n)
        raise RequestParseError(
            f"the feature order ({' → '.join(order)}) does not list every requested feature ({want}) exactly once"
        )
    for j in glue:
        c.consume_token(j)
    f.values["feature_order"] = order
    f.spans["feature_order"] = [m.span for m in run]


_FIRST_LAST = {"first": "first", "last": "last", "start": "first", "end": "last"}


def _first_or_last(c: Canon, f: Found, ms: list[Mention], counts: Counter[str]) -> None:
    """ "two hairpins and a chicane, the chicane first": with two kinds of feature, naming
    one kind first (or last) orders the lap."""
    kinds = [k for k, n in counts.items() if n > 0]
    if len(kinds) != 2:
        return
    for m in ms:
        after = range(m.last + 1, min(len(c.tokens), m.last + 5))
        for j in after:
            w = c.tokens[j].canon
            if w in (",", ".", ";") or (c.tokens[j].kind != "word"):
                break
            if w in _FIRST_LAST and not c.used[j]:
                lead = m.feature if _FIRST_LAST[w] == "first" else next(k for k in kinds if k != m.feature)
                other = next(k for k in kinds if k != lead)
                f.values["feature_order"] = [lead] * counts[lead] + [other] * counts[other]
                f.spans["feature_order"] = [(m.span[0], c.tokens[j].end)]
                for k in range(m.last + 1, j + 1):
                    if c.tokens[k].canon in _ORDER_GLUE | {
                        "comes",
                        "come",
                        "should",
                        "must",
                        "go",
                        "goes",
                        "at",
                        "the",
                        w,
                    }:
                        c.consume_token(k)
                return
