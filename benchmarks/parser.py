"""``python -m benchmarks parser``: the paper's Table 2 ("Local parser evaluation") for
our backends -- exact parses on the parse set, invention-audit passes over repeated
calls, median latency per call and, where known, memory.

A request line (JSONL) holds ``id``, ``set`` ("parse", "audit" or "refuse"), ``text``
and ``expected`` (the stated fields only), optionally ``batch`` ("blind": written before
the parser work it scores; "after": written later) and, for a refusal, ``span`` (text the
error must name). *Exact*: every stated field matches and every unstated field keeps its
default. *Audit pass*: no field outside ``expected`` differs from its default (no
invented constraint); a call that errors is not a pass. *Refusal correct*: the call
raises a typed error (exit 2 in the CLI) whose message names ``span``.

Without ``--requests`` the rules backend also runs over every shipped set -- the
held-out set, the everyday set by batch, the end-to-end requests -- beside the recorded
blind score (the parser of main before this work, on the blind batch as written).
"""

from __future__ import annotations

import argparse
import json
import resource
import statistics
import time
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

from roboracer_arena.bench.output import BenchModel, add_bench_parser, write_json
from roboracer_arena.errors import ArenaError, InvalidArgumentError
from roboracer_arena.parse.result import DEFAULTS

from . import bench_data

REPO_REQUESTS = bench_data("requests.jsonl")  # benchmarks/data
#: (label, file, batch or None) of every shipped request set, in report order.
SHIPPED_SETS = [
    ("shipped (Table 2 set)", "requests.jsonl", None),
    ("held-out", "requests_heldout.jsonl", None),
    ("everyday, blind batch", "requests_everyday.jsonl", "blind"),
    ("everyday, after batch", "requests_everyday.jsonl", "after"),
    ("paper end-to-end (8)", "requests_e2e.jsonl", None),
]
BLIND_SCORE = bench_data("requests_blind_score.json")

# The paper's Table 2 (Gemma 4 31B etc. through Ollama on an RTX PRO 6000).
PAPER_ROWS = [
    ("gemma4:31b (paper)", "12/12", "51/51", "9.3 s", "19.0 GB VRAM"),
    ("qwen3.6:35b (paper)", "12/12", "51/51", "12.5 s", "23.9 GB VRAM"),
    ("gpt-oss:120b (paper)", "12/12", "51/51", "3.7 s", "65.4 GB VRAM"),
    ("mistral:7b (paper)", "12/12", "45/51", "0.8 s", "4.4 GB VRAM"),
]
_REL_TOL = 1e-3


class Miss(BenchModel):
    """A request scored wrong: its id and set, the fields that differ (or why a refusal
    missed), and the error the call raised."""

    id: str
    set: str
    fields: list[str]
    error: str | None


class ParserRow(BenchModel):
    """One backend on one request set: counts (and ``"ok/n"`` texts), latency per call,
    memory, what the grounding guard caught, and every miss."""

    parse: str
    parse_exact: int
    parse_total: int
    audit: str
    refuse: str
    refuse_correct: int
    refuse_total: int
    audit_pass: int
    audit_calls: int
    latency_median_s: float | None
    latency_max_s: float | None
    peak_rss_delta_mb: float
    inventions_caught_by_guard: int
    inventions_missed_by_guard: int
    misses: list[Miss]


class Unreachable(BenchModel):
    """A backend that could not run (its server was not reachable)."""

    status: str


class BlindFile(BenchModel):
    """The recorded blind score of one request file; ``misses``: id -> the wrong fields' values."""

    correct: int
    total: int
    parse: str
    refuse: str
    misses: dict[str, dict[str, float | int | str]]


class BlindScore(BenchModel):
    """``benchmarks/data/requests_blind_score.json``: the parser of main before this work, on
    the blind batch as written."""

    parser_commit: str
    recorded_utc: str
    note: str
    files: dict[str, BlindFile]


class ShippedSets(BenchModel):
    """The rules backend over every shipped set, with the recorded blind score."""

    sets: dict[str, ParserRow]
    blind_recorded: BlindScore


class ParserResult(BenchModel):
    """``bench parser``: the request file, audit repeats, one row per backend; without
    ``--requests`` also every shipped set (:class:`ShippedSets`)."""

    requests: str
    repeats: int
    rows: dict[str, ParserRow | Unreachable]
    sets: dict[str, ParserRow] | None = None
    blind_recorded: BlindScore | None = None

    def with_sets(self, shipped: ShippedSets) -> ParserResult:
        """This result with the shipped sets added."""
        return self.model_copy(update={"sets": shipped.sets, "blind_recorded": shipped.blind_recorded})


def load_requests(path: Path) -> list[dict[str, Any]]:
    """Read a JSONL request file; errors name the file and line."""
    out = []
    for n, line in enumerate(Path(path).read_text(encoding="utf-8").splitlines(), 1):
        if not line.strip():
            continue
        try:
            d = json.loads(line)
            assert (
                d["set"] in ("parse", "audit", "refuse")
                and isinstance(d["text"], str)
                and isinstance(d["expected"], dict)
            )
        except (json.JSONDecodeError, KeyError, AssertionError) as e:
            raise InvalidArgumentError(f"{path}:{n}: not a request line ({e})") from None
        out.append(d)
    return out


def _same(a: Any, b: Any) -> bool:
    if isinstance(b, float) or isinstance(a, float):
        return abs(float(a) - float(b)) <= _REL_TOL * max(1.0, abs(float(b)))
    return a == b


def score(got: dict[str, Any] | None, expected: dict[str, Any]) -> tuple[bool, bool, list[str]]:
    """(exact, no invention, the fields that differ) for one call's spec dump."""
    if got is None:
        return False, False, ["(error)"]
    want = {**DEFAULTS, **expected}
    wrong = [k for k in want if not _same(got[k], want[k])]
    invented = [k for k in wrong if k not in expected]
    return not wrong, not invented, wrong


def _rules_call(text: str) -> dict[str, Any]:
    from roboracer_arena.parse import parse_request

    return parse_request(text, backend="rules").spec.model_dump()


def _ollama_call(host: str | None, model: str, timeout: float) -> Callable[[str], dict[str, Any]]:
    from roboracer_arena.parse.ollama_backend import ask_ollama

    def call(text: str) -> dict[str, Any]:
        spec, _ = ask_ollama(text, host=host, model=model, timeout=timeout)
        return spec.model_dump()

    return call


def evaluate(call: Callable[[str], dict[str, Any]], requests: list[dict[str, Any]], repeats: int) -> ParserRow:
    """Run the parse set once and the audit set ``repeats`` times through ``call``."""
    from roboracer_arena.parse import ground
    from roboracer_arena.spec import TrackSpec

    rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    times: list[float] = []
    parse_ok, parse_n, audit_ok, audit_n, guard_caught, guard_false = 0, 0, 0, 0, 0, 0
    refuse_ok, refuse_n = 0, 0
    misses: list[Miss] = []
    for req in requests:
        for rep in range(1 if req["set"] == "parse" else repeats):
            t0 = time.perf_counter()
            try:
                got, err = call(req["text"]), None
            except ArenaError as e:
                got, err = None, f"{type(e).__name__}: {e}"
            times.append(time.perf_counter() - t0)
            if req["set"] == "refuse":
                refuse_n += 1
                named = err is not None and str(req.get("span", "")) in err
                refuse_ok += int(named)
                if not named:
                    why = "(accepted)" if err is None else "(span not named)"
                    misses.append(Miss(id=req["id"], set="refuse", fields=[why], error=err))
                continue
            exact, clean, wrong = score(got, req["expected"])
            if got is not None and not clean:  # would the grounding guard have caught it?
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    flagged = ground(req["text"], TrackSpec(**got), strict=False, rules_reading=False).invented
                guard_caught += int(bool(flagged))
                guard_false += int(not flagged)
            if req["set"] == "parse":
                parse_n += 1
                parse_ok += int(exact)
            else:
                audit_n += 1
                audit_ok += int(clean)
            if (req["set"] == "parse" and not exact) or (req["set"] == "audit" and not clean):
                if rep == 0 or not any(m.id == req["id"] for m in misses):
                    misses.append(Miss(id=req["id"], set=req["set"], fields=wrong, error=err))
    rss1 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return ParserRow(
        parse=f"{parse_ok}/{parse_n}",
        parse_exact=parse_ok,
        parse_total=parse_n,
        audit=f"{audit_ok}/{audit_n}",
        refuse=f"{refuse_ok}/{refuse_n}",
        refuse_correct=refuse_ok,
        refuse_total=refuse_n,
        audit_pass=audit_ok,
        audit_calls=audit_n,
        latency_median_s=statistics.median(times) if times else None,
        latency_max_s=max(times) if times else None,
        peak_rss_delta_mb=round((rss1 - rss0) / 1024, 2),
        inventions_caught_by_guard=guard_caught,
        inventions_missed_by_guard=guard_false,
        misses=misses,
    )


def run_sets() -> ShippedSets:
    """The rules backend over every shipped set (:data:`SHIPPED_SETS`), with the recorded
    blind score; prints a table and returns the rows."""
    rows: dict[str, ParserRow] = {}
    for label, name, batch in SHIPPED_SETS:
        reqs = [r for r in load_requests(bench_data(name)) if batch is None or r.get("batch") == batch]
        rows[label] = evaluate(_rules_call, reqs, 1)
    blind = BlindScore.model_validate_json(Path(BLIND_SCORE).read_bytes())
    print(f"\nrules parser over the shipped request sets (audit once; blind = main at {blind.parser_commit}, recorded)")
    head = f"{'request set':<34} {'parse':>7} {'refusals':>9} {'audit':>7} {'all':>8}"
    print(head)
    print("-" * len(head))
    for name, b in blind.files.items():
        print(f"{'blind run: ' + name:<34} {b.parse:>7} {b.refuse:>9} {'-':>7} {f'{b.correct}/{b.total}':>8}")
    for label, r in rows.items():
        ok = r.parse_exact + r.refuse_correct + r.audit_pass
        n = r.parse_total + r.refuse_total + r.audit_calls
        print(f"{label:<34} {r.parse:>7} {r.refuse:>9} {r.audit:>7} {f'{ok}/{n}':>8}")
        for m in r.misses:
            print(f"  miss {m.id} ({m.set}): {', '.join(m.fields)}" + (f" — {m.error}" if m.error else ""))
    return ShippedSets(sets=rows, blind_recorded=blind)


def _fmt_latency(s: float | None) -> str:
    if s is None:
        return "-"
    return f"{s * 1e3:.2f} ms" if s < 1 else f"{s:.1f} s"


def run(
    requests_path: Path = REPO_REQUESTS,
    backends: tuple[str, ...] = ("rules",),
    repeats: int = 3,
    ollama_host: str | None = None,
    model: str = "gemma4:31b",
    timeout: float = 120.0,
) -> ParserResult:
    """Evaluate each backend on ``requests_path``; print the table; return the results."""
    from roboracer_arena.parse.ollama_backend import reachable, resolve_host

    requests = load_requests(requests_path)
    rows: dict[str, ParserRow | Unreachable] = {}
    for backend in backends:
        if backend == "rules":
            try:
                _rules_call(requests[0]["text"])  # warm the imports and regex caches
            except ArenaError:
                pass  # a refusal row: warmed all the same
            rows["rules"] = evaluate(_rules_call, requests, repeats)
        elif backend == "ollama":
            key = f"ollama {model}"
            if not reachable(ollama_host, timeout=2):
                rows[key] = Unreachable(status=f"not reachable at {resolve_host(ollama_host)}")
                continue
            rows[key] = evaluate(_ollama_call(ollama_host, model, timeout), requests, repeats)
        else:
            raise InvalidArgumentError(f"unknown backend {backend!r} (rules, ollama)")
    results = ParserResult(requests=str(requests_path), repeats=repeats, rows=rows)
    print_table(results)
    return results


def print_table(results: ParserResult) -> None:
    print(f"requests: {results.requests}  (audit repeated {results.repeats}×)")
    head = f"{'parser':<24} {'parse':>7} {'audit pass':>11} {'latency':>10}  memory"
    print(head)
    print("-" * len(head))
    for name, r in results.rows.items():
        if isinstance(r, Unreachable):
            print(f"{name:<24} {r.status}")
            continue
        mem = f"{r.peak_rss_delta_mb:.1f} MB peak RSS delta"
        print(f"{name:<24} {r.parse:>7} {r.audit:>11} {_fmt_latency(r.latency_median_s):>10}  {mem}")
    for row in PAPER_ROWS:
        print(f"{row[0]:<24} {row[1]:>7} {row[2]:>11} {row[3]:>10}  {row[4]}")
    for name, r in results.rows.items():
        for m in r.misses if isinstance(r, ParserRow) else []:
            print(f"  miss [{name}] {m.id} ({m.set}): {', '.join(m.fields)}" + (f" — {m.error}" if m.error else ""))


def run_quick() -> ParserResult:
    """``bench all``: the rules backend on the shipped request set, then every set."""
    return run().with_sets(run_sets())


def register(kinds) -> None:
    p = add_bench_parser(kinds, "parser", "parser evaluation (the paper's Table 2)", __doc__)
    p.add_argument(
        "--requests", type=Path, metavar="FILE.jsonl",
        help="request set (default: the shipped Table 2 set, then the rules over every shipped set)",
    )  # fmt: skip
    p.add_argument("--backend", nargs="+", default=["rules"], choices=["rules", "ollama"], help="backends to evaluate")
    p.add_argument("--repeats", type=int, default=3, help="repeats of the audit set (default 3, as in the paper)")
    p.add_argument("--ollama-host", metavar="URL", help="Ollama server (default $OLLAMA_HOST)")
    p.add_argument("--model", default="gemma4:31b", help="Ollama model (default gemma4:31b)")
    p.add_argument("--timeout", type=float, default=120.0, help="seconds per model call")
    p.set_defaults(func=_cli)


def _cli(args: argparse.Namespace) -> int:
    if args.repeats < 1:
        raise InvalidArgumentError(f"--repeats must be ≥ 1, got {args.repeats}")
    results = run(
        args.requests or REPO_REQUESTS, tuple(args.backend), args.repeats, args.ollama_host, args.model, args.timeout
    )
    if args.requests is None:
        results = results.with_sets(run_sets())
    write_json(args.json, results)
    return 0
