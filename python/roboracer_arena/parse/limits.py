"""What a request may state: the input-length cap and each field's plausible range.

The ranges are the TrackSpec schema's (one owner): a request for a 1:10 RoboRacer track
indoors that states a 1e308 m lap or 10 000 hairpins is a typo or hostile input, refused
with the field and its range named rather than handed on to the generator.
"""

from __future__ import annotations

import math

from ..errors import RequestParseError
from ..spec import TrackSpec
from .result import Span

#: Longest request accepted, in characters. A request is a sentence or a paragraph (the
#: paper's and our bench sets stay under 300); the parser is linear, the cap keeps its
#: work and any error message bounded.
MAX_REQUEST_CHARS = 10_000


def _field_ranges() -> dict[str, tuple[float, float]]:
    """(lowest, highest) of every numeric TrackSpec field, from the schema itself."""
    out = {}
    for name, info in TrackSpec.model_fields.items():
        if info.annotation not in (int, float, float | None):
            continue
        lo = next((getattr(m, k) for m in info.metadata for k in ("ge", "gt") if getattr(m, k, None) is not None), 0)
        hi = next(m.le for m in info.metadata if getattr(m, "le", None) is not None)
        out[name] = (lo, hi)
    return out


#: field -> (lowest, highest) value a request may state: the TrackSpec schema's own ranges
#: (one owner; a spec file is held to the same).
FIELD_RANGES: dict[str, tuple[float, float]] = _field_ranges()


def check_length(text: object, max_chars: int | None = MAX_REQUEST_CHARS) -> None:
    """Refuse a non-string, an empty request or one longer than ``max_chars`` characters
    (default :data:`MAX_REQUEST_CHARS`; ``None``: no cap)."""
    if not isinstance(text, str):
        raise RequestParseError(f"the request must be text, got {type(text).__name__}")
    if not text.strip():
        raise RequestParseError("the request is empty")
    if max_chars is not None and len(text) > max_chars:
        raise RequestParseError(
            f"the request is {len(text)} characters long; the parser accepts at most {max_chars} "
            "(a request is a sentence or a paragraph)"
        )


def quote(text: str, start: int, end: int, limit: int = 60) -> str:
    """``repr`` of ``text[start:end]``, shortened in the middle beyond ``limit`` characters
    (error messages stay one readable line whatever the request)."""
    piece = text[start:end]
    if len(piece) > limit:
        piece = piece[: limit // 2] + " … " + piece[-limit // 2 :]
    return repr(piece)


def _fmt(v: float) -> str:
    return f"{v:g}"


def check_range(name: str, value: float, text: str, span: Span | None) -> None:
    """Refuse a stated value outside the field's range, naming the span and the range."""
    lo, hi = FIELD_RANGES[name]
    try:
        value = float(value)  # a summed count may be an int beyond float range
    except OverflowError:
        value = math.inf
    if math.isfinite(value) and lo <= value <= hi:
        return
    where = f" ({quote(text, *span)} at characters {span[0]}-{span[1]})" if span else ""
    unit = " m" if name.endswith("_m") else ""
    raise RequestParseError(
        f"{name} = {_fmt(value)}{unit}{where} is outside the range a request may state: {_fmt(lo)} to {_fmt(hi)}{unit}"
    )
