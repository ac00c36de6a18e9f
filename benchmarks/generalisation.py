"""``python -m benchmarks generalisation``: does training on many tracks transfer to
tracks never seen? The same ES policy (:mod:`roboracer_arena.learn.es`) and the same
budget of env-steps are spent

* on ONE track (``--single``, default the recorded f1tenth-gym Berlin map), and
* on a POOL of generated tracks plus the 1:10 F1 circuits (drawn per episode, equal
  weight to each group),

then each trained policy drives one lap from the grid start of every held-out recorded
map (``--held-out``): recorded maps from ../shared/track-sources, none of them in the
pool and none the single training track. Reported per condition over ``--seeds`` seeds:
clean-lap rate (lap completed without touching a wall) and mean lap time of the clean
laps, plus the per-track result.

CPU note: the defaults are deliberately small (the project's machine has 2 cores shared
with other work); raise ``--generations`` / ``--pairs`` for stronger policies.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

from roboracer_arena.bench.output import BenchModel, add_bench_parser, write_json

SINGLE = "gym-berlin"
POOL = {"generated": 1.0, "circuits": 1.0}
#: Recorded maps whose layouts are neither in the pool (no F1 circuit layouts) nor Berlin.
HELD_OUT = ("gym-skirk", "gym-vegas", "gym-example", "cps-torino-redraw", "cps-columbia-small")


class HeldOutLap(BenchModel):
    """One lap from the grid start of a held-out track (:func:`~roboracer_arena.learn.es.evaluate_laps`)."""

    track: str
    clean_lap: bool
    lap_time: float | None
    progress: float


class TrainingRun(BenchModel):
    """One (condition, seed): its training cost and its laps on the held-out maps."""

    condition: str
    seed: int
    env_steps: int
    train_seconds: float
    cpu_seconds: float
    wall_seconds: float
    final_mean_return: float
    laps: list[HeldOutLap]


class ConditionSummary(BenchModel):
    """One condition over its seeds; see :func:`summarise`."""

    clean_lap_rate: float
    mean_env_steps: int
    mean_lap_time_s: float | None
    clean_laps_per_track: dict[str, int]


class Budget(BenchModel):
    """The ES budget of every run."""

    generations: int
    pairs: int
    episode_steps: int


class GeneralisationResult(BenchModel):
    """``bench generalisation``: budget, the two conditions, held-out maps, summaries, runs."""

    budget: Budget
    single: str
    pool: dict[str, float]
    held_out: list[str]
    seeds: int
    summary: dict[str, ConditionSummary]
    runs: list[TrainingRun]


def register(kinds) -> None:
    p = add_bench_parser(kinds, "generalisation", "ES on one track vs on a track pool, laps on held-out maps", __doc__)
    p.add_argument("--seeds", type=int, default=3, help="training seeds per condition (default 3)")
    p.add_argument("--generations", type=int, default=40, help="ES generations per run (default 40)")
    p.add_argument("--pairs", type=int, default=16, help="antithetic pairs per generation (default 16)")
    p.add_argument("--episode-steps", type=int, default=200, help="steps per training episode (default 200)")
    p.add_argument("--single", default=SINGLE, help=f"the one training track (default {SINGLE})")
    p.add_argument("--held-out", nargs="+", default=list(HELD_OUT), help="evaluation tracks (catalog ids)")
    p.set_defaults(func=_run_cli)


def run(
    seeds: int = 3,
    generations: int = 40,
    pairs: int = 16,
    episode_steps: int = 200,
    single: str = SINGLE,
    held_out: tuple[str, ...] | list[str] = HELD_OUT,
    verbose: bool = True,
    pool: dict[str, float] | None = None,
) -> GeneralisationResult:
    """Train both conditions for every seed and evaluate on ``held_out``; see module docstring."""
    from roboracer_arena.errors import ConfigError
    from roboracer_arena.learn.es import ESConfig, evaluate_laps, make_training_env, train

    if seeds < 1 or generations < 1 or pairs < 1:
        raise ConfigError("bench generalisation: --seeds, --generations and --pairs must be >= 1")
    if single in held_out:
        raise ConfigError(f"bench generalisation: the training track {single!r} is in --held-out")
    pool = dict(POOL if pool is None else pool)
    conditions: dict[str, str | dict[str, float]] = {"single": single, "pool": pool}
    runs: list[TrainingRun] = []
    base = replace(ESConfig(), generations=generations, pairs=pairs, episode_steps=episode_steps)
    for name, track in conditions.items():
        env = make_training_env(track, base)  # once per condition: the pool has ~100 tracks to load
        for seed in range(seeds):
            cfg = replace(base, seed=seed)
            t0, c0 = time.perf_counter(), time.process_time()
            result = train(track, cfg, env=env)
            laps = evaluate_laps(result.theta, list(held_out), cfg)
            run = TrainingRun(
                condition=name,
                seed=seed,
                env_steps=result.env_steps,
                train_seconds=round(result.seconds, 1),
                cpu_seconds=round(time.process_time() - c0, 1),
                wall_seconds=round(time.perf_counter() - t0, 1),
                final_mean_return=result.curve[-1]["mean_return"],
                laps=[HeldOutLap.model_validate(lap) for lap in laps],
            )
            runs.append(run)
            if verbose:
                clean = sum(lap.clean_lap for lap in run.laps)
                print(
                    f"  {name:6s} seed {seed}: {clean}/{len(laps)} clean laps on held-out maps "
                    f"({run.env_steps} env-steps, {run.wall_seconds} s)",
                    flush=True,
                )
    return GeneralisationResult(
        budget=Budget(generations=generations, pairs=pairs, episode_steps=episode_steps),
        single=single,
        pool=pool,
        held_out=list(held_out),
        seeds=seeds,
        summary=summarise(runs),
        runs=runs,
    )


def summarise(runs: list[TrainingRun]) -> dict[str, ConditionSummary]:
    """Per condition: clean-lap rate over all (seed, track) laps, mean clean lap time,
    and per held-out track the clean laps out of the seeds."""
    out: dict[str, ConditionSummary] = {}
    for name in dict.fromkeys(r.condition for r in runs):
        laps = [lap for r in runs if r.condition == name for lap in r.laps]
        clean = [lap for lap in laps if lap.clean_lap]
        times = [lap.lap_time for lap in clean if lap.lap_time is not None]
        per_track: dict[str, int] = {}
        for lap in laps:
            per_track[lap.track] = per_track.get(lap.track, 0) + int(lap.clean_lap)
        steps = [r.env_steps for r in runs if r.condition == name]
        out[name] = ConditionSummary(
            clean_lap_rate=round(len(clean) / len(laps), 3),
            mean_env_steps=round(sum(steps) / len(steps)),
            mean_lap_time_s=round(sum(times) / len(times), 2) if times else None,
            clean_laps_per_track=per_track,
        )
    return out


def print_table(res: GeneralisationResult) -> None:
    b = res.budget
    print(
        f"ES budget per run: {b.generations} generations x {2 * b.pairs} envs x <= {b.episode_steps} steps "
        f"(episodes end at a contact); {res.seeds} seeds per condition"
    )
    print(f"held-out recorded maps: {', '.join(res.held_out)}")
    print(f"{'condition':<34}{'env-steps/run':>14}{'clean-lap rate':>16}{'mean lap time (s)':>20}")
    names = {"single": f"one track ({res.single})", "pool": "pool (" + " + ".join(res.pool) + ")"}
    for name, s in res.summary.items():
        t = "-" if s.mean_lap_time_s is None else f"{s.mean_lap_time_s:.2f}"
        print(f"{names[name]:<34}{s.mean_env_steps:>14}{s.clean_lap_rate:>16.2f}{t:>20}")
    for name, s in res.summary.items():
        per = ", ".join(f"{k} {v}/{res.seeds}" for k, v in s.clean_laps_per_track.items())
        print(f"  {name}: {per}")


def _run_cli(args: argparse.Namespace) -> int:
    res = run(args.seeds, args.generations, args.pairs, args.episode_steps, args.single, args.held_out)
    print_table(res)
    write_json(args.json, res)
    return 0


def run_quick() -> GeneralisationResult:
    """``bench all``: one seed, a small budget, three held-out maps."""
    res = run(seeds=1, generations=10, pairs=8, episode_steps=150, held_out=HELD_OUT[:3])
    print_table(res)
    return res
