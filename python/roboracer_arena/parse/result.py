"""What a parse returns: the TrackSpec, which fields the request stated, where in the
request each stated value came from, and what the parser could not explain."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any, NamedTuple

from ..spec import TrackSpec

Span = tuple[int, int]


class Fragment(NamedTuple):
    """A piece of the request: its text and character span ``[start, end)``."""

    text: str
    start: int
    end: int


#: Field order of TrackSpec (the schema's order), used for display.
FIELDS: tuple[str, ...] = tuple(TrackSpec.model_fields)
DEFAULTS: dict[str, Any] = TrackSpec().model_dump()


@dataclass(frozen=True)
class ParseResult:
    """The outcome of :func:`roboracer_arena.parse.parse_request`.

    * ``spec`` -- the TrackSpec; unstated fields hold their documented defaults.
    * ``stated`` -- the fields the request stated, in TrackSpec order.
    * ``spans`` -- for each stated field, the character spans of ``text`` it came from
      (several for a count summed over mentions, e.g. "a hairpin ... another hairpin").
    * ``unparsed`` -- words the parser could not explain (reported, never guessed).
    * ``warnings`` -- e.g. values the grounding guard reset in non-strict mode, a bound
      read as a target, numbers ignored in lenient mode.
    * ``backend`` -- which parser produced the values ("rules" or "ollama").
    * ``hedges`` -- stated fields whose value was hedged: "approximately", "at most" or
      "at least" (see :mod:`roboracer_arena.parse.hedges`).
    * ``ignored`` -- numbers no field explains, ignored in lenient mode (refused otherwise).
    * ``defaulted`` (property) -- the fields the request did not state, which hold defaults.
    """

    text: str
    spec: TrackSpec
    stated: tuple[str, ...]
    spans: dict[str, tuple[Span, ...]] = field(default_factory=dict)
    unparsed: tuple[Fragment, ...] = ()
    warnings: tuple[str, ...] = ()
    backend: str = "rules"
    hedges: dict[str, str] = field(default_factory=dict)
    ignored: tuple[Fragment, ...] = ()

    @property
    def defaulted(self) -> tuple[str, ...]:
        """The fields the request did not state (they hold their documented defaults)."""
        return tuple(k for k in FIELDS if k not in self.stated)

    def replace(self, **changes: Any) -> ParseResult:
        """A copy with ``changes`` applied (the result is frozen)."""
        return replace(self, **changes)

    def span(self, name: str) -> Span | None:
        """The hull of the spans of field ``name`` (``None`` if it was not stated)."""
        spans = self.spans.get(name)
        if not spans:
            return None
        return min(s for s, _ in spans), max(e for _, e in spans)

    def source_text(self, name: str) -> str | None:
        """The request text field ``name`` came from (spans joined by " … ")."""
        spans = self.spans.get(name)
        if not spans:
            return None
        return " … ".join(self.text[s:e] for s, e in spans)

    def highlight(self, name: str, mark: tuple[str, str] = ("[", "]")) -> str:
        """The request with the spans of ``name`` bracketed (for the CLI)."""
        out, pos = [], 0
        for s, e in sorted(self.spans.get(name, ())):
            out += [self.text[pos:s], mark[0], self.text[s:e], mark[1]]
            pos = e
        out.append(self.text[pos:])
        return "".join(out)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready summary (used by ``roboracer-arena parse --json``)."""
        return {
            "text": self.text,
            "backend": self.backend,
            "spec": self.spec.model_dump(),
            "stated": list(self.stated),
            "defaulted": list(self.defaulted),
            "hedges": dict(self.hedges),
            "sources": {
                k: [{"start": s, "end": e, "text": self.text[s:e]} for s, e in v] for k, v in self.spans.items()
            },
            "unparsed": [f._asdict() for f in self.unparsed],
            "ignored": [f._asdict() for f in self.ignored],
            "warnings": list(self.warnings),
        }
