"""Natural-language requests -> :class:`~roboracer_arena.spec.TrackSpec`.

:func:`parse_request` is the one entry point. Backends:

* ``"rules"`` (default): the embedded deterministic parser (:mod:`.rules`); no server,
  no download, a few milliseconds; reports the words it cannot explain.
* ``"ollama"``: a local model through the official ``ollama`` client (:mod:`.ollama_backend`).
* ``"auto"``: rules first; if words stay unexplained and an Ollama server answers, ask
  the model and keep, for every field the rules read, the rules' value.

Every backend's output passes the grounding guard (:mod:`.grounding`): a value that
cannot be traced to the request is an invented constraint.
"""

from __future__ import annotations

from ..errors import BackendError, InvalidArgumentError
from ..spec import TrackSpec
from .grounding import Grounded, ground
from .ollama_backend import DEFAULT_MODEL, DEFAULT_TIMEOUT_S, ask_ollama, reachable
from .result import DEFAULTS, FIELDS, Fragment, ParseResult
from .rules import parse_rules

BACKENDS = ("rules", "ollama", "auto")


def _from_model(text: str, g: Grounded, unparsed: tuple[Fragment, ...] = ()) -> ParseResult:
    dump = g.spec.model_dump()
    stated = tuple(k for k in FIELDS if dump[k] != DEFAULTS[k])
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

    Raises:
        RequestParseError: empty or contradictory request (e.g. clockwise and
            counter-clockwise), or stated values that do not form a valid TrackSpec.
        BackendError: the Ollama backend failed (subclasses name the cause).
        GroundingError: a backend invented a value (strict mode).
    """
    if backend not in BACKENDS:
        raise InvalidArgumentError(f"unknown parser backend {backend!r}; choose one of {', '.join(BACKENDS)}")
    if backend == "rules":
        result = parse_rules(text)
        ground(text, result.spec, strict=True, rules_reading=False)  # self-check: rules never invent
        return result
    if backend == "ollama":
        spec, _ = ask_ollama(text, host=ollama_host, model=model, timeout=timeout)
        return _from_model(text, ground(text, spec, strict=strict))
    # auto
    rules = parse_rules(text)
    if not rules.unparsed or not reachable(ollama_host):
        return rules
    try:
        spec, _ = ask_ollama(text, host=ollama_host, model=model, timeout=timeout)
    except BackendError as e:
        return _with_warning(rules, f"rules parse kept: the Ollama backend failed ({e})")
    g = ground(text, spec, strict=strict)
    return _merge(rules, _from_model(text, g, rules.unparsed))


def _with_warning(r: ParseResult, note: str) -> ParseResult:
    return ParseResult(r.text, r.spec, r.stated, r.spans, r.unparsed, (*r.warnings, note), r.backend)


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
    return ParseResult(rules.text, spec, stated, spans, rules.unparsed, tuple(notes), "auto")


__all__ = [
    "BACKENDS",
    "DEFAULT_MODEL",
    "Fragment",
    "ParseResult",
    "TrackSpec",
    "ground",
    "parse_request",
    "parse_rules",
]
