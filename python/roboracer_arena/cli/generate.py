"""``roboracer-arena generate``: a TrackSpec (``--spec FILE``) or a natural-language
REQUEST (parsed first, see ``roboracer-arena parse``) to a validated map, a proven
rejection (exit 3) or a generation failure (exit 4).

Example: roboracer-arena generate "a 60 m lap with two hairpins in a 20 by 15 m hall" -o out/t1"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import EXIT_GENERATION_FAILURE, EXIT_OK, EXIT_REJECTED
from ._common import add_json_flag, print_json
from .parse import add_backend_args, parse_from_args, print_result
from ..errors import InvalidArgumentError, MapIOError
from ..spec import TrackSpec


def register(sub) -> None:
    p = sub.add_parser(
        "generate",
        help="requirements → validated occupancy map (or a rejection / generation failure)",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("request", nargs="?", help="natural-language request (or use --spec)")
    p.add_argument("--spec", type=Path, metavar="SPEC.json", help="TrackSpec JSON file")
    p.add_argument("--seed", type=int, default=0, help="seed of the candidate ordering (default 0)")
    p.add_argument("-o", "--out", type=Path, default=Path("out/generated"), metavar="OUTDIR", help="output directory")
    p.add_argument("--constructor", choices=["lattice", "de", "random"], default="lattice")
    p.add_argument("--build", action="store_true", help="also build the USD environment through the builder")
    add_backend_args(p)
    add_json_flag(p)
    p.set_defaults(func=run)


def _spec_from_args(args: argparse.Namespace):
    """The TrackSpec to generate, and the ParseResult when it came from a request."""
    if args.spec is not None and args.request:
        raise InvalidArgumentError("give either a REQUEST or --spec SPEC.json, not both")
    if args.spec is not None:
        return TrackSpec.from_file(args.spec), None
    if args.request:
        parsed = parse_from_args(args, args.request)
        return parsed.spec, parsed
    raise InvalidArgumentError("give a natural-language REQUEST or a TrackSpec with --spec SPEC.json")


def run(args: argparse.Namespace) -> int:
    from ..generate import Acceptance, Rejection, generate_track, write_outputs

    if args.seed < 0:
        raise InvalidArgumentError(f"--seed must be ≥ 0, got {args.seed}")
    if args.out.exists() and not args.out.is_dir():
        raise MapIOError(f"{args.out}: exists and is not a directory; -o names the output folder")
    spec, parsed = _spec_from_args(args)
    if parsed is not None and not args.json:
        print_result(parsed, file=sys.stderr)
    outcome = generate_track(spec, seed=args.seed, constructor=args.constructor)
    summary: dict = {"outcome": outcome.kind, "name": spec.name, "seconds": round(outcome.seconds, 4)}
    if parsed is not None:
        summary["parse"] = parsed.to_dict()
    if isinstance(outcome, Acceptance):
        paths = write_outputs(outcome, args.out)
        summary.update(
            candidates_tried=outcome.candidates_tried,
            files={k: str(v) for k, v in paths.items()},
            checks=outcome.report["checks"],
            features=outcome.report["features"],
        )
        if args.build:
            try:
                from ..builder import build_environment  # type: ignore[import-not-found]
                from ..maps import load_map  # type: ignore[import-not-found]
            except ImportError as e:
                raise InvalidArgumentError(f"--build needs the USD builder, which this installation lacks ({e}); the map was written to {args.out}") from e
            usd = args.out / "track.usda"
            build_environment(load_map(paths["map_yaml"]), usd)
            summary["files"]["usd"] = str(usd)
        code = EXIT_OK
    elif isinstance(outcome, Rejection):
        summary.update(violations=outcome.violations, screen=outcome.screen)
        code = EXIT_REJECTED
    else:
        summary.update(candidates_tried=outcome.candidates_tried, reasons=outcome.reasons)
        code = EXIT_GENERATION_FAILURE
    if args.json:
        print_json(summary)
    else:
        print(outcome.summary(), file=sys.stdout if code == EXIT_OK else sys.stderr)
        if code == EXIT_OK:
            for c in outcome.report["checks"]:
                print(f"  {'ok ' if c['passed'] else 'BAD'} {c['name']:<17} {c['measured']:<34} {c['bound']}")
            print(f"wrote {args.out}/")
    return code
