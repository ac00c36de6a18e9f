"""Number words: "three", "twenty-five", "forty five", "one hundred and twenty", "two
thousand", "one point five", "two and a half", "a pair of", "a couple of", "a dozen",
"half a dozen", "two dozen".

The lexer hands :func:`read_number` a list of lower-case words (hyphenated words already
split); it returns the value and how many words it used, or ``None``. Bare "a"/"an"/"one"
as a *count* of features is handled by the feature rules, not here: "a 38 m lap" must not
read as "1 38 m lap".
"""

from __future__ import annotations

from collections.abc import Sequence

UNITS: dict[str, int] = {
    "zero": 0, "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7,
    "eight": 8, "nine": 9, "ten": 10, "eleven": 11, "twelve": 12, "thirteen": 13,
    "fourteen": 14, "fifteen": 15, "sixteen": 16, "seventeen": 17, "eighteen": 18,
    "nineteen": 19,
}  # fmt: skip
TENS: dict[str, int] = {
    "twenty": 20, "thirty": 30, "forty": 40, "fifty": 50, "sixty": 60, "seventy": 70,
    "eighty": 80, "ninety": 90,
}  # fmt: skip
DIGIT_WORDS = {w: v for w, v in UNITS.items() if v < 10}


def _below_hundred(words: Sequence[str], i: int) -> tuple[int, int] | None:
    """``twenty five`` / ``twenty`` / ``seven`` at ``i`` -> (value, words used)."""
    if i >= len(words):
        return None
    w = words[i]
    if w in TENS:
        if i + 1 < len(words) and words[i + 1] in DIGIT_WORDS and DIGIT_WORDS[words[i + 1]] > 0:
            return TENS[w] + DIGIT_WORDS[words[i + 1]], 2
        return TENS[w], 1
    if w in UNITS:
        return UNITS[w], 1
    return None


def _integer(words: Sequence[str], i: int) -> tuple[int, int] | None:
    """An integer in words below a million ("two thousand five hundred", "a thousand")."""
    if i + 1 < len(words) and words[i] in ("a", "one") and words[i + 1] == "thousand":
        head: tuple[int, int] | None = (1, 1)
    else:
        head = _hundreds(words, i)
    if head is None:
        return None
    j = i + head[1]
    if j < len(words) and words[j] == "thousand" and 0 < head[0] < 1000:
        value, used = head[0] * 1000, head[1] + 1
        k = i + used
        if k < len(words) and words[k] == "and":
            tail = _hundreds(words, k + 1)
            if tail is not None and tail[0] > 0:
                return value + tail[0], used + 1 + tail[1]
        tail = _hundreds(words, k)
        if tail is not None and tail[0] > 0:
            return value + tail[0], used + tail[1]
        return value, used
    return head


def _hundreds(words: Sequence[str], i: int) -> tuple[int, int] | None:
    """An integer in words, up to the hundreds ("one hundred and twenty", "a hundred")."""
    if i + 1 < len(words) and words[i] in ("a", "one") and words[i + 1] == "hundred":
        value, used = 100, 2
    else:
        head = _below_hundred(words, i)
        if head is None:
            return None
        value, used = head
        if i + used < len(words) and words[i + used] == "hundred" and 0 < value < 10:
            value, used = value * 100, used + 1
        else:
            return value, used
    # "... hundred [and] twenty five"
    j = i + used
    if j < len(words) and words[j] == "and":
        tail = _below_hundred(words, j + 1)
        if tail is not None:
            return value + tail[0], used + 1 + tail[1]
    tail = _below_hundred(words, j)
    if tail is not None and tail[0] > 0:
        return value + tail[0], used + tail[1]
    return value, used


def read_number(words: Sequence[str], i: int) -> tuple[float, int] | None:
    """Read a number written in words starting at ``words[i]``.

    Returns ``(value, words_used)`` or ``None``. Handles integers to 999, "point" decimals
    ("one point five"), "and a half", "half a", "a pair of", "a couple of", "a dozen".
    """
    n = len(words)
    w = words[i] if i < n else ""
    nxt = words[i + 1] if i + 1 < n else ""
    # "a pair of", "a couple of", "a dozen"
    if w in ("a", "an") and nxt in ("pair", "couple", "dozen"):
        value = 12.0 if nxt == "dozen" else 2.0
        used = 2 + (1 if i + 2 < n and words[i + 2] == "of" else 0)
        return value, used
    if w in ("pair", "couple") and nxt == "of":
        return 2.0, 2
    if w == "dozen":
        return 12.0, 1
    if w == "half" and nxt in ("a", "an"):
        if i + 2 < n and words[i + 2] == "dozen":
            return 6.0, 3
        return 0.5, 2
    whole = _integer(words, i)
    if whole is None:
        return None
    value = float(whole[0])
    used = whole[1]
    j = i + used
    # "one point five", "two point two five"
    if j + 1 < n and words[j] == "point" and words[j + 1] in DIGIT_WORDS:
        digits = []
        k = j + 1
        while k < n and words[k] in DIGIT_WORDS:
            digits.append(str(DIGIT_WORDS[words[k]]))
            k += 1
        return float(f"{int(value)}.{''.join(digits)}"), k - i
    # "two and a half"
    if j + 2 < n and words[j] == "and" and words[j + 1] in ("a", "an") and words[j + 2] == "half":
        return value + 0.5, used + 3
    # "two dozen"
    if j < n and words[j] == "dozen":
        return value * 12, used + 1
    return value, used
