"""``roboracer-arena generate``: a TrackSpec (``--spec FILE``) or a natural-language
REQUEST (parsed first, see ``roboracer-arena parse``) to a validated map, a proven
rejection (exit 3) or a generation failure (exit 4, also when ``--timeout`` runs out).
A generation failure lists the nearest specs that did build, one field changed at a
time, each with the seed that built it ("try: lap_length_m = 48 (built with seed 2)";
a bounded search of its own, at most 20 s; ``--no-suggest`` skips it).

OUTDIR appears whole or not at all, and replaces an earlier generate output there (so no
stale stage is left when ``--build`` is not given); an OUTDIR that is a file or holds
other files is refused (exit 2). ``--build`` also builds the USD stage, ``--drive``
drives the reference car one lap on the map (exit 5 if it does not finish).

Example: roboracer-arena generate "a 60 m lap with two hairpins in a 20 by 15 m hall" -o out/t1 --build --drive"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..drivers import drive_laps
from ..errors import InvalidArgumentError
from ..generate import Acceptance, Rejection, generate_track, write_outputs
from ..generate.nearest import DEFAULT_SUGGEST_TIMEOUT_S, DISCLAIMER
from ..generate.outputs import output_folder
from ..generate.pipeline import DEFAULT_TIMEOUT_S, check_timeout
from ..spec import TrackSpec
from . import EXIT_GENERATION_FAILURE, EXIT_LAP_FAILED, EXIT_OK, EXIT_REJECTED
from ._common import add_json_flag, print_json
from .parse import add_backend_args, parse_from_args, print_result


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
    p.add_argument(
        "--constructor",
        choices=["lattice", "de", "random"],
        default="lattice",
        help="lattice (default); de / random, the paper's baselines, moved to python -m benchmarks (exit 2)",
    )
    p.add_argument("--build", action="store_true", help="also build the USD environment through the builder")
    p.add_argument(
        "--drive", action="store_true", help="then drive the reference car one lap on the map (exit 5 if it fails)"
    )
    p.add_argument(
        "--no-suggest",
        action="store_true",
        help="on a generation failure, skip the search for the nearest specs that build",
    )
    add_backend_args(p)
    _share_timeout(p)
    add_json_flag(p)
    p.set_defaults(func=run, output_dirs=("out",))


_MODEL_TIMEOUT_DEFAULT = "_model_timeout_default"


def _share_timeout(p: argparse.ArgumentParser) -> None:
    """``--timeout SECONDS`` (from the parser options) bounds the track search too."""
    action = next(a for a in p._actions if a.dest == "timeout")
    p.set_defaults(**{_MODEL_TIMEOUT_DEFAULT: action.default})
    action.default = None
    action.metavar = "SECONDS"
    action.help = f"time budget of the track search (default 60 s; exit 4 when it runs out) and of an Ollama model call (default {p.get_default(_MODEL_TIMEOUT_DEFAULT):g} s)"


def _spec_from_args(args: argparse.Namespace):
    """The TrackSpec to generate, and the ParseResult when it came from a request."""
    if args.spec is not None and args.request:
        raise InvalidArgumentError("give either a REQUEST or --spec SPEC.json, not both")
    if args.spec is not None:
        return TrackSpec.from_file(args.spec), None
    if args.request:
        model_timeout = getattr(args, _MODEL_TIMEOUT_DEFAULT) if args.timeout is None else args.timeout
        parsed = parse_from_args(argparse.Namespace(**{**vars(args), "timeout": model_timeout}), args.request)
        return parsed.spec, parsed
    raise InvalidArgumentError("give a natural-language REQUEST or a TrackSpec with --spec SPEC.json")


def run(args: argparse.Namespace) -> int:
    if args.seed < 0 or args.seed >= 2**64:
        raise InvalidArgumentError(f"--seed must be in [0, 2**64), got {args.seed}")
    timeout = check_timeout(DEFAULT_TIMEOUT_S if args.timeout is None else args.timeout, "--timeout")
    _check_outdir(args.out)
    spec, parsed = _spec_from_args(args)
    if parsed is not None and not args.json:
        print_result(parsed, file=sys.stderr)
    outcome = generate_track(
        spec,
        seed=args.seed,
        constructor=args.constructor,
        timeout=timeout,
        suggest_timeout=None if args.no_suggest else DEFAULT_SUGGEST_TIMEOUT_S,
    )
    summary: dict = {"outcome": outcome.kind, "name": spec.name, "seconds": round(outcome.seconds, 4)}
    if parsed is not None:
        summary["parse"] = parsed.to_dict()
    if isinstance(outcome, Acceptance):
        summary.update(
            candidates_tried=outcome.candidates_tried,
            files=_write_folder(outcome, args),
            **outcome.report.model_dump(mode="json", include={"checks", "features"}),
        )
        code = EXIT_OK
        if args.drive:
            code = _drive(Path(summary["files"]["map_yaml"]), args, summary)
    elif isinstance(outcome, Rejection):
        summary.update(violations=outcome.violations, screen=outcome.screen.model_dump(mode="json"))
        code = EXIT_REJECTED
    else:
        summary.update(candidates_tried=outcome.candidates_tried, reasons=outcome.reasons, stopped=outcome.stopped)
        if outcome.nearest is not None:
            summary["nearest"] = {**outcome.nearest.model_dump(mode="json"), "note": DISCLAIMER}
        code = EXIT_GENERATION_FAILURE
    if args.json:
        print_json(summary)
    else:
        print(outcome.summary(), file=sys.stderr if code in (EXIT_REJECTED, EXIT_GENERATION_FAILURE) else sys.stdout)
        if isinstance(outcome, Acceptance):
            for c in outcome.report.checks:
                print(f"  {c.line()}")
            print(f"wrote {args.out}/")
            if "drive" in summary:
                d = summary["drive"]
                verdict = "completed" if d["completed"] else ("COLLIDED" if d["collided"] else "did not finish")
                print(f"drove 1 lap: {verdict}" + (f" in {d['lap_times'][0]:.2f} s" if d["lap_times"] else ""))
    return code


def _check_outdir(out: Path) -> None:
    """Refuse a bad -o before any work (the same rule :func:`output_folder` applies)."""
    if out.exists() and not out.is_dir():
        raise InvalidArgumentError(
            f"-o {out}: exists and is not a directory; give a new or an earlier generate output directory"
        )


def _write_folder(acc, args: argparse.Namespace) -> dict[str, str]:
    """Every output (and the stage with --build) into a temporary folder that then
    replaces OUTDIR whole; returns the final paths."""
    final = Path(args.out)
    with output_folder(final) as tmp:
        paths = write_outputs(acc, tmp)
        if args.build:
            _build_stage(paths["map_yaml"], tmp, final, args)
            paths["usd"] = tmp / "track.usda"
    return {k: str(final / v.name) for k, v in paths.items()}


def _build_stage(map_yaml: Path, tmp: Path, final: Path, args: argparse.Namespace) -> None:
    try:
        from ..builder import build_environment
        from ..maps.occupancy import load_map
    except ImportError as e:
        raise InvalidArgumentError(f"--build needs the USD builder, which this installation lacks ({e})") from e
    # The stage records where its source map lives: the final folder, not the temporary one
    # (the checksums are of the staged copy, which becomes that file).
    build_environment(load_map(map_yaml), tmp / "track.usda", record_source_as=final / map_yaml.name)


def _drive(map_yaml: Path, args: argparse.Namespace, summary: dict) -> int:
    res = drive_laps(str(map_yaml), 1, progress=False)
    summary["drive"] = res.to_dict()
    return EXIT_OK if res.completed else EXIT_LAP_FAILED
