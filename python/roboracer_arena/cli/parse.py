"""``roboracer-arena parse "REQUEST"``: a natural-language request to a TrackSpec, showing
where in the request each stated value came from, which fields keep their defaults and
which words were not understood.

A number no field explains, a range, a contradiction or an out-of-range value is refused
(exit 2, naming the text and its characters); --lenient ignores unexplained numbers with
a warning instead.

Example: roboracer-arena parse "a 38 m lap for a small 15 by 12 hall"
"""

from __future__ import annotations

import argparse
import sys

from ..parse import BACKENDS, DEFAULT_MODEL, parse_request
from ..parse.result import FIELDS
from ._common import add_json_flag, print_json

_COLOURS = ("\x1b[1;32m", "\x1b[0m")  # bold green
_UNPARSED_COLOURS = ("\x1b[1;33m", "\x1b[0m")  # bold yellow


def add_backend_args(p: argparse.ArgumentParser) -> None:
    """``--backend``, ``--ollama-host``, ``--model``, ``--timeout``, ``--lenient`` (shared with generate)."""
    g = p.add_argument_group("request parser")
    g.add_argument("--backend", choices=BACKENDS, default="rules", help="parser backend (default: rules, no server)")
    g.add_argument("--ollama-host", metavar="URL", help="Ollama server (default: $OLLAMA_HOST or 127.0.0.1:11434)")
    g.add_argument("--model", default=DEFAULT_MODEL, help=f"Ollama model (default {DEFAULT_MODEL})")
    g.add_argument(
        "--timeout", type=float, default=120.0, metavar="S", help="seconds to wait for the model (default 120)"
    )
    g.add_argument(
        "--lenient",
        action="store_true",
        help="ignore numbers no field explains and reset values the grounding guard cannot trace "
        "to the request, each with a warning (default: refuse the request, exit 2)",
    )


def parse_from_args(args: argparse.Namespace, text: str):
    """Run :func:`parse_request` with the backend options of ``args``."""
    return parse_request(
        text,
        backend=args.backend,
        ollama_host=args.ollama_host,
        model=args.model,
        timeout=args.timeout,
        strict=not args.lenient,
        lenient=args.lenient,
    )


def register(sub) -> None:
    p = sub.add_parser(
        "parse",
        help="natural-language request → TrackSpec, with the source of every value",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("request", help='the request, e.g. "a 38 m lap for a small 15 by 12 hall"')
    add_backend_args(p)
    add_json_flag(p)
    p.set_defaults(func=run)


def _marked(result, colour: bool) -> str:
    """The request with stated spans marked [..] and unparsed words marked ?..?."""
    on, off = _COLOURS if colour else ("[", "]")
    uon, uoff = _UNPARSED_COLOURS if colour else ("?", "?")
    marks = []
    for spans in result.spans.values():
        marks += [(s, e, on, off) for s, e in spans]
    marks += [(u.start, u.end, uon, uoff) for u in result.unparsed]
    out, pos = [], 0
    for s, e, a, b in sorted(set(marks)):
        if s < pos:
            continue  # overlapping spans: keep the first
        out += [result.text[pos:s], a, result.text[s:e], b]
        pos = e
    out.append(result.text[pos:])
    return "".join(out)


def print_result(result, file=None) -> None:
    """Human-readable TrackSpec with the source of each value (on ``file``, default stdout)."""
    file = file or sys.stdout
    colour = file.isatty()
    values = result.spec.model_dump()
    print(f"request: {_marked(result, colour)}", file=file)
    print(f"backend: {result.backend}", file=file)
    for name in FIELDS:
        shown = repr(values[name]) if isinstance(values[name], str) else str(values[name])
        if name in result.stated:
            spans = result.spans.get(name, ())
            where = "; ".join(f"{result.text[s:e]!r} @{s}-{e}" for s, e in spans) or "(model)"
            hedge = f" ({result.hedges[name]})" if name in result.hedges else ""
            print(f"  {name:<19} {shown:<28} ← {where}{hedge}", file=file)
        else:
            print(f"  {name:<19} {shown:<28}   (default)", file=file)
    print("stated: " + (", ".join(result.stated) or "(none)"), file=file)
    print("defaulted: " + (", ".join(result.defaulted) or "(none)"), file=file)
    if result.unparsed:
        print("not understood: " + ", ".join(repr(u.text) for u in result.unparsed), file=file)
    for w in result.warnings:
        print(f"warning: {w}", file=file)


def run(args: argparse.Namespace) -> int:
    result = parse_from_args(args, args.request)
    if args.json:
        print_json(result.to_dict())
    else:
        print_result(result)
    return 0
