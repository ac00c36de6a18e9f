"""The values a rules pass has found so far, with their source spans; a second,
different value for the same field is a contradiction."""

from __future__ import annotations

from typing import Any

from ..errors import RequestParseError
from .limits import FIELD_RANGES, check_range, quote
from .result import Span


class Found:
    """Field -> value and the request spans that stated it."""

    def __init__(self, text: str):
        self.text = text
        self.values: dict[str, Any] = {}
        self.spans: dict[str, list[Span]] = {}

    def set(self, name: str, value: Any, span: Span) -> None:
        """Record ``name = value`` from ``span``; raise on a value outside the field's range
        (:data:`.limits.FIELD_RANGES`) or one contradicting an earlier value."""
        if name in FIELD_RANGES:
            check_range(name, float(value), self.text, span)
        if name in self.values and self.values[name] != value:
            (s0, e0), (s1, e1) = self.spans[name][0], span
            raise RequestParseError(
                f"the request states {name} twice with different values: "
                f"{self.values[name]!r} from {quote(self.text, s0, e0)} (characters {s0}-{e0}) and {value!r} "
                f"from {quote(self.text, s1, e1)} (characters {s1}-{e1})"
            )
        self.values[name] = value
        self.spans.setdefault(name, []).append(span)
