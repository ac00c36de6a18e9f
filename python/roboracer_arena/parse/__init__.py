"""Natural-language requests -> :class:`~roboracer_arena.spec.TrackSpec`.

:func:`parse_request` is the one entry point. Backends:

* ``"rules"`` (default): the embedded deterministic parser (:mod:`.rules`); no server,
  no download, a few milliseconds; reports the words it cannot explain.
* ``"ollama"``: a local model through the official ``ollama`` client (:mod:`.ollama_backend`).
* ``"auto"``: rules first; if words stay unexplained and an Ollama server answers, ask
  the model and keep, for every field the rules read, the rules' value.

Every backend's output passes the grounding guard (:mod:`.grounding`): a value that
cannot be traced to the request is an invented constraint.

**Nothing silently defaulted.** A number in the request that no field explains ("a 45 m
lap with 3 hairpins in 10 minutes": the 10) is refused with its span, for every backend;
``lenient=True`` (CLI ``--lenient``) ignores it with a warning instead. The result lists
``stated`` and ``defaulted`` fields side by side.

**Numbers** are read whole ("6e1 m" is 60 m, "4,000 cm" is 40 m, "twenty-five",
"two and a half", "a dozen", "forty five") or refused: a negative value, a value outside
the field's range (:data:`.limits.FIELD_RANGES`, e.g. a lap of 1 to 2000 m) or a number
too large to be finite names the field, the span and the allowed range. A request longer
than :data:`.limits.MAX_REQUEST_CHARS` (10 000) characters is refused; the rules parser is
linear in the request's length below that.

**Ranges** ("between 40 and 50 m", "40-50 m", "from 40 to 50", "2 or 3 hairpins") are
refused: a field takes one value, and picking one for the user would be a silent default.

**Hedges** (:mod:`.hedges`): "about/around/roughly/approximately ... or so" keep the value
as the target. "at most/no more than/up to/under" and "at least/no less than/over" on a
floor (minimum radius, longest straight) are its meaning ("at least"), or refused ("at
most"); on a hall size they read as that size; on the lap, the corridor width or a
feature count they read as a target equal to the bound, with a warning.

**Bare quantities**: a lone length with a unit, when no lap is stated, is the lap ("five
hairpins, 45 metres"); a bare "W by H", "W x H m" or "W×H" is the hall.
"""

from __future__ import annotations

from ..errors import BackendError, InvalidArgumentError
from ..spec import TrackSpec
from .grounding import Grounded, ground, unexplained_numbers
from .limits import FIELD_RANGES, MAX_REQUEST_CHARS, check_length, check_range
from .ollama_backend import DEFAULT_MODEL, DEFAULT_TIMEOUT_S, ask_ollama, reachable
from .result import DEFAULTS, FIELDS, Fragment, ParseResult
from .rules import ignored_note, parse_rules, refuse_numbers

BACKENDS = ("rules", "ollama", "auto")


def _from_model(text: str, g: Grounded, unparsed: tuple[Fragment, ...] = ()) -> ParseResult:
    dump = g.spec.model_dump()
    stated = tuple(k for k in FIELDS if dump[k] != DEFAULTS[k])
    for k in stated:
        if k in FIELD_RANGES:
            check_range(k, float(dump[k]), text, g.spans[k][0] if g.spans.get(k) else None)
    return ParseResult(
        text=text,
        spec=g.spec,
        stated=stated,
        spans={k: g.spans[k] for k in stated if k in g.spans},
        unparsed=unparsed,
        warnings=tuple(g.warnings),
        backend="ollama",
    )


def parse_request(
    text: str,
    backend: str = "rules",
    *,
    ollama_host: str | None = None,
    model: str = DEFAULT_MODEL,
    timeout: float = DEFAULT_TIMEOUT_S,
    strict: bool = True,
    lenient: bool = False,
) -> ParseResult:
    """Parse a natural-language track request into a :class:`ParseResult`.

    Args:
        text: the request, e.g. ``"a 38 m lap for a small 15 by 12 hall"``.
        backend: ``"rules"``, ``"ollama"`` or ``"auto"`` (see the module docstring).
        ollama_host: Ollama server URL (default ``$OLLAMA_HOST``, else ``127.0.0.1:11434``).
        model: Ollama model name (default ``gemma4:31b``, the paper's choice).
        timeout: seconds to wait for the model.
        strict: an untraceable (invented) value raises :class:`GroundingError`; with
            ``strict=False`` it is reset to its default and reported in ``warnings``.
        lenient: a number no field explains is ignored with a warning (and listed in
            ``ignored``) instead of refused.

    Raises:
        RequestParseError: empty, over-long or contradictory request (e.g. clockwise and
            counter-clockwise), a range, a number no field explains (unless ``lenient``),
            a value outside its field's range, or stated values that do not form a valid
            TrackSpec. The message names the span.
        BackendError: the Ollama backend failed (subclasses name the cause).
        GroundingError: a backend invented a value (strict mode).
    """
    if backend not in BACKENDS:
        raise InvalidArgumentError(f"unknown parser backend {backend!r}; choose one of {', '.join(BACKENDS)}")
    if backend == "rules":
        result = parse_rules(text, lenient=lenient)
        ground(text, result.spec, strict=True, rules_reading=False)  # self-check: rules never invent
        return result
    check_length(text)
    if backend == "ollama":
        spec, _ = ask_ollama(text, host=ollama_host, model=model, timeout=timeout)
        return _explained(_from_model(text, ground(text, spec, strict=strict)), lenient)
    # auto: the rules first (leniently: the model may explain what they could not)
    rules = parse_rules(text, lenient=True)
    alone = rules.replace(ignored=(), warnings=_without_ignored(rules))  # _explained re-judges
    if not (rules.unparsed or rules.ignored) or not reachable(ollama_host):
        return _explained(alone, lenient)
    try:
        spec, _ = ask_ollama(text, host=ollama_host, model=model, timeout=timeout)
    except BackendError as e:
        return _explained(_with_warning(alone, f"rules parse kept: the Ollama backend failed ({e})"), lenient)
    g = ground(text, spec, strict=strict)
    return _explained(_merge(rules, _from_model(text, g, rules.unparsed)), lenient)


def _without_ignored(r: ParseResult) -> tuple[str, ...]:
    return tuple(w for w in r.warnings if not w.startswith("lenient: ignored"))


def _explained(r: ParseResult, lenient: bool) -> ParseResult:
    """The "nothing silently defaulted" rule for model output: every number in the request
    must be explained by some field of the final spec."""
    stray = unexplained_numbers(r.text, r.spec.model_dump())
    if not stray:
        return r
    if not lenient:
        refuse_numbers(r.text, stray)
    return r.replace(ignored=tuple(stray), warnings=(*r.warnings, ignored_note(stray)))


def _with_warning(r: ParseResult, note: str) -> ParseResult:
    return r.replace(warnings=(*r.warnings, note))


def _merge(rules: ParseResult, model: ParseResult) -> ParseResult:
    """Model values for fields the rules did not read; the rules' values for the rest."""
    values = model.spec.model_dump()
    rd = rules.spec.model_dump()
    notes = list(model.warnings)
    for k in rules.stated:
        if values[k] != rd[k]:
            notes.append(f"{k}: the model said {values[k]!r}, the rules read {rd[k]!r}; kept the rules' value")
        values[k] = rd[k]
    spec = TrackSpec.from_dict(values, source="merged parse")
    stated = tuple(k for k in FIELDS if k in rules.stated or k in model.stated)
    spans = {k: rules.spans.get(k) or model.spans.get(k, ()) for k in stated}
    notes = [*_without_ignored(rules), *notes]
    return ParseResult(rules.text, spec, stated, spans, rules.unparsed, tuple(notes), "auto", rules.hedges)


__all__ = [
    "BACKENDS",
    "FIELD_RANGES",
    "MAX_REQUEST_CHARS",
    "DEFAULT_MODEL",
    "Fragment",
    "ParseResult",
    "TrackSpec",
    "ground",
    "parse_request",
    "parse_rules",
]
