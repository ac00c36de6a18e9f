"""``python -m benchmarks constructors``: the paper's Table "Constructor comparison".

Every constructor gets the same specifications and seeds. How trials are counted:

* A spec the admissibility screen rejects (e.g. the 200 m lap in a 20 × 15 m hall) is a
  *correct rejection*, reported on its own line, and is **not a trial**: no constructor
  runs on it. The paper's 30 trials are 10 admissible specs × 3 seeds; ``benchmarks/data/specs.jsonl``
  holds 11 specs of which one is screen-rejected, so it gives the same 30.
* A trial is one (admissible spec, seed, constructor). *Built*: the constructor emitted a
  centreline, it was rasterised (Eq. 3) and the ROS map was written to disk. *Valid*: that
  map, read back from its PNG + YAML, passed the raster validator (the same for every
  constructor). Seconds per trial cover construction, rasterisation, map writing and the
  external validation (the paper's "construction, map writing, and validation").

Constructors:

* ``lattice`` — Algorithm 1 as shipped (``generate_track``): at most 800 candidates (the
  lattice's, with every third from the ring constructor), each rasterised and validated, the
  first valid map returned. Built ⇒ passed the raster
  validator inside the loop, so valid/built re-checks the written file.
* ``lattice-raw`` — the paper's protocol for this table: the constructor (lattice + ring) alone,
  emitting the first candidate that passes its *own analytic* checks (hall fit,
  self-clearance, curvature feature counts on the analytic curve), with no raster
  validation in the loop. Its valid/built says how well the constructor predicts the
  raster validator.
* ``de`` / ``random`` — the scipy baselines of :mod:`benchmarks.baselines`.

``--sweep`` runs a different benchmark: Algorithm 1's acceptance on the stratified sweep of
admissible specs (:mod:`benchmarks.constructor_sweep`).
"""

from __future__ import annotations

import argparse
import json
import platform
import statistics
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path
from typing import Any

from tqdm import tqdm

from roboracer_arena import _core
from roboracer_arena.bench.output import BenchModel, add_bench_parser, write_json
from roboracer_arena.config.constructor import ConstructorConfig
from roboracer_arena.errors import SpecError
from roboracer_arena.generate import Acceptance, generate_track, rasterise, screen, validate_map
from roboracer_arena.maps.occupancy import load_map
from roboracer_arena.spec import TrackSpec

from . import bench_data
from .baselines import construct_baseline

CONSTRUCTOR_CHOICES = ("lattice", "lattice-raw", "de", "random")
# The paper's Table "Constructor comparison": (valid, built, trials, seconds per trial).
PAPER = {"lattice": (21, 21, 30, 3.7), "de": (15, 27, 30, 5.1), "random": (11, 30, 30, 11.2)}
QUICK_SPECS = ("paper-teaser-3h1c-20x15", "paper-200m-in-20x15", "narrow-1.2m-small-hall")


class Trial(BenchModel):
    """One (spec, seed, constructor): built, candidates tried, valid and the failed checks
    (or why nothing was built), and its seconds."""

    spec: str
    seed: int
    constructor: str
    built: bool
    candidates: int
    valid: bool
    failed_checks: list[str]
    not_built_reason: str | None = None
    seconds: float


class ConstructorSummary(BenchModel):
    """One constructor over its trials."""

    constructor: str
    trials: int
    built: int
    valid: int
    seconds_per_trial_mean: float
    seconds_per_trial_median: float
    candidates_median: int | float
    candidates_max: int
    failed_checks: dict[str, int]
    not_built: dict[str, int]


class ScreenRejection(BenchModel):
    """A spec the admissibility screen rejected (not a trial), with its violations."""

    spec: str
    violations: list[str]


class ConstructorsResult(BenchModel):
    """``bench constructors``: spec counts, seeds, screen rejections, summaries, every trial."""

    specs: int
    admissible_specs: int
    seeds: list[int]
    screen_rejections: list[ScreenRejection]
    summary: list[ConstructorSummary]
    trials: list[Trial]
    machine: str


def default_specs_path() -> Path:
    """The spec set in this checkout (``benchmarks/data/specs.jsonl``)."""
    return bench_data("specs.jsonl")


def load_specs(path: str | Path) -> list[TrackSpec]:
    """One TrackSpec JSON object per non-blank line; errors name the file and line."""
    p = Path(path)
    try:
        lines = p.read_text(encoding="utf-8").splitlines()
    except OSError as e:
        raise SpecError(f"{p}: cannot read spec file: {e.strerror or e}") from e
    specs = []
    for i, line in enumerate(lines, 1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        try:
            data = json.loads(line)
        except json.JSONDecodeError as e:
            raise SpecError(f"{p}:{i}: not valid JSON (column {e.colno}): {e.msg}") from e
        specs.append(TrackSpec.from_dict(data, source=f"{p}:{i}"))
    if not specs:
        raise SpecError(f"{p}: no specifications")
    return specs


def _build(spec: TrackSpec, seed: int, constructor: str, config: ConstructorConfig) -> tuple[Any, str, int]:
    """(OccupancyMap or None, why not built, lattice candidates tried)."""
    if constructor == "lattice":
        out = generate_track(spec, seed=seed, config=config)
        if isinstance(out, Acceptance):
            return out.map, "", out.candidates_tried
        reasons: dict[str, int] = getattr(out, "reasons", {}) or {out.kind: 1}
        return None, max(reasons, key=lambda k: reasons[k]), getattr(out, "candidates_tried", 0)
    if constructor == "lattice-raw":
        built = _core.construct_lattice(spec, config, seed)
        if built.centreline is None:
            reasons = built.reasons
            return None, max(reasons, key=lambda k: reasons[k]), built.tried
        return rasterise(built.centreline, spec, config), "", built.tried
    line = construct_baseline(spec, config, seed, constructor)
    if line is None:
        return None, "self-intersecting curve", 1
    return rasterise(line, spec, config), "", 1


def run_trial(spec: TrackSpec, seed: int, constructor: str, config: ConstructorConfig, workdir: Path) -> Trial:
    """One matched trial: build, write the map, read it back, validate it."""
    t0 = time.perf_counter()
    m, why, tried = _build(spec, seed, constructor, config)
    outcome: dict[str, Any]
    if m is None:
        outcome = {"valid": False, "failed_checks": [], "not_built_reason": why}
    else:
        yaml_path = m.save(workdir / f"{constructor}-{spec.name}-{seed}.yaml")
        report, _ = validate_map(load_map(yaml_path), spec, config)
        outcome = {"valid": report.valid, "failed_checks": [c.name for c in report.failed()]}
    return Trial(
        spec=spec.name,
        seed=seed,
        constructor=constructor,
        built=m is not None,
        candidates=tried,
        **outcome,
        seconds=time.perf_counter() - t0,
    )


def summarise(rows: list[Trial], constructor: str) -> ConstructorSummary:
    mine = [r for r in rows if r.constructor == constructor]
    n = len(mine)
    secs = sorted(r.seconds for r in mine)
    cands = sorted(r.candidates for r in mine)
    return ConstructorSummary(
        constructor=constructor,
        trials=n,
        built=sum(r.built for r in mine),
        valid=sum(r.valid for r in mine),
        seconds_per_trial_mean=sum(secs) / n if n else float("nan"),
        seconds_per_trial_median=statistics.median(secs) if n else float("nan"),
        candidates_median=statistics.median(cands) if n else 0,
        candidates_max=cands[-1] if n else 0,
        failed_checks=dict(Counter(c for r in mine for c in r.failed_checks)),
        not_built=dict(Counter(r.not_built_reason or "" for r in mine if not r.built)),
    )


def run(
    specs: list[TrackSpec],
    seeds: list[int],
    constructors: list[str],
    config: ConstructorConfig | None = None,
    progress: bool = True,
) -> ConstructorsResult:
    """Run every (admissible spec, seed, constructor) trial; returns rows and summaries."""
    config = config or ConstructorConfig()
    admissible, rejections = [], []
    for s in specs:
        sr = screen(s, config)
        if sr.passed:
            admissible.append(s)
        else:
            rejections.append(ScreenRejection(spec=s.name, violations=list(sr.violations)))
    jobs = [(s, seed, c) for c in constructors for s in admissible for seed in seeds]
    rows = []
    with tempfile.TemporaryDirectory(prefix="bench-constructors-") as tmp:
        for s, seed, c in tqdm(jobs, desc="constructor trials", unit="trial", file=sys.stderr, disable=not progress):
            rows.append(run_trial(s, seed, c, config, Path(tmp)))
    return ConstructorsResult(
        specs=len(specs),
        admissible_specs=len(admissible),
        seeds=seeds,
        screen_rejections=rejections,
        summary=[summarise(rows, c) for c in constructors],
        trials=rows,
        machine=f"{platform.machine()} {platform.processor() or ''}".strip(),
    )


def print_table(result: ConstructorsResult) -> None:
    rejected = result.screen_rejections
    print(
        f"{result.admissible_specs} admissible specs × {len(result.seeds)} seeds = trials per constructor; "
        f"{len(rejected)} spec(s) rejected by the screen (not trials)"
    )
    for r in rejected[:5]:
        print(f"  rejected {r.spec}: {'; '.join(r.violations)}")
    if len(rejected) > 5:
        print(f"  … and {len(rejected) - 5} more (see --json)")
    head = (
        f"{'constructor':<12} {'valid trials':>12} {'valid/built':>11} {'s/trial':>8} {'median s':>8}   {'paper':>22}"
    )
    print(head)
    print("-" * len(head))
    for s in result.summary:
        paper = PAPER.get(s.constructor)
        ptxt = f"{paper[0]}/{paper[2]}  {paper[0]}/{paper[1]}  {paper[3]:.1f} s" if paper else ""
        print(
            f"{s.constructor:<12} {s.valid:>5}/{s.trials:<6} {s.valid:>5}/{s.built:<5} "
            f"{s.seconds_per_trial_mean:>8.3f} {s.seconds_per_trial_median:>8.3f}   {ptxt:>22}"
        )
    for s in result.summary:
        if s.constructor.startswith("lattice"):
            print(
                f"  {s.constructor}: candidates per trial median {s.candidates_median:g}, max {s.candidates_max} (cap 800)"
            )
        if s.failed_checks or s.not_built:
            print(f"  {s.constructor}: failed checks {s.failed_checks or '{}'}; not built {s.not_built or '{}'}")


def register(kinds) -> None:
    p = add_bench_parser(kinds, "constructors", "lattice vs DE vs random sampling (the paper's Table 3)", __doc__)
    p.add_argument(
        "--specs",
        type=Path,
        default=None,
        metavar="FILE.jsonl",
        help="one TrackSpec JSON per line (default: benchmarks/data/specs.jsonl)",
    )
    p.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2], metavar="S", help="seeds (default 0 1 2)")
    p.add_argument(
        "--constructors",
        nargs="+",
        choices=CONSTRUCTOR_CHOICES,
        default=list(CONSTRUCTOR_CHOICES),
        metavar="C",
        help=f"subset of {', '.join(CONSTRUCTOR_CHOICES)} (default all)",
    )
    p.add_argument(
        "--sweep",
        action="store_true",
        help="instead: Algorithm 1's acceptance on the stratified sweep of admissible specs (benchmarks/data/sweep_specs.jsonl)",
    )
    p.add_argument("--maps", type=Path, metavar="DIR", help="with --sweep: write every accepted map under DIR")
    p.add_argument("--jobs", type=int, default=1, metavar="N", help="with --sweep: worker processes (default 1)")
    p.add_argument(
        "--suggest",
        action="store_true",
        help="with --sweep: search the nearest specs that build for every miss and run each suggestion as suggested",
    )
    p.set_defaults(func=_cli)


def _cli(args: argparse.Namespace) -> int:
    if args.sweep:
        from .constructor_sweep import load_sweep_file, print_sweep, run_sweep

        if args.jobs < 1:
            raise SpecError(f"--jobs must be ≥ 1, got {args.jobs}")
        sweep = run_sweep(load_sweep_file(), args.maps, args.jobs, suggest=args.suggest)
        print_sweep(sweep)
        write_json(args.json, sweep)
        return 0
    if any(s < 0 for s in args.seeds):
        raise SpecError(f"--seeds must be ≥ 0, got {args.seeds}")
    specs = load_specs(args.specs or default_specs_path())
    result = run(specs, args.seeds, args.constructors)
    print_table(result)
    write_json(args.json, result)
    return 0


def run_quick() -> ConstructorsResult:
    """Three specs (one screen-rejected) × seed 0, every constructor: a smoke run."""
    specs = [s for s in load_specs(default_specs_path()) if s.name in QUICK_SPECS]
    result = run(specs, [0], list(CONSTRUCTOR_CHOICES))
    print_table(result)
    return result
