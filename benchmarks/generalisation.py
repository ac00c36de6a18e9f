"""``python -m benchmarks generalisation``: do policies trained on the library drive
recorded maps they have never seen? Every condition trains ``--seeds`` policy files with
``roboracer_arena.learn.trainer.train_policy`` (what ``roboracer-arena train`` runs) and
drives one lap from the grid start of each held-out recorded map
(``roboracer_arena.learn.recipe.HELD_OUT``: whole families of recorded maps, none in any
training pool), as ``drive --policy`` does. The conditions:

* ``single``: the default recipe on one track (``--single``, the recorded Berlin map);
* ``pool``: the default recipe's pool (every catalog track but the held-out maps),
  without domain randomisation;
* ``pool_rand``: the default recipe (pool and randomisation: friction, mass, lags, lidar
  noise and dropout, actuation delay 0-2 steps);
* ``plain``: the same pool and randomisation, but a plain MLP with no base controller
  (the recipe of the project's earlier rounds), to show what the residual buys.

Reported per condition over the seeds: the clean-lap rate (a lap completed without a
contact or driving the wrong way) with a 95 % Student-t interval over seeds; the lap
time of clean laps relative to the reference pure-pursuit driver's lap on the same map
(``roboracer-arena drive``), with its interval; training wall and CPU seconds. With
``--physx-seeds K`` the first K ``pool_rand`` policy files also drive every held-out map
on the PhysX car (``drive --engine physx``, PhysX's own lidar raycasts).
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import replace
from pathlib import Path

from roboracer_arena.bench.output import BenchModel, add_bench_parser, write_json

SINGLE = "gym-berlin"
CONDITIONS = ("single", "pool", "pool_rand", "plain")


class HeldOutLap(BenchModel):
    """One lap from the grid start of a held-out map."""

    track: str
    clean_lap: bool
    lap_time: float | None
    progress: float
    reference_lap_time: float | None
    ratio: float | None  # lap_time / reference_lap_time, clean laps only


class TrainingRun(BenchModel):
    """One (condition, seed): its training cost and its laps on the held-out maps."""

    condition: str
    seed: int
    generations: int
    env_steps: int
    train_seconds: float
    cpu_seconds: float
    final_mean_return: float
    clean_laps: int
    laps: list[HeldOutLap]
    policy_file: str | None = None
    physx_clean_laps: int | None = None
    physx_laps: list[dict] | None = None


class Interval(BenchModel):
    """Mean over seeds with a two-sided 95 % Student-t interval."""

    mean: float
    low: float
    high: float
    n: int


class ConditionSummary(BenchModel):
    """One condition over its seeds; see :func:`summarise`."""

    description: str
    clean_lap_rate: Interval
    lap_time_ratio: Interval | None
    racing_ratio: Interval | None = None
    train_wall_seconds: float
    train_cpu_seconds: float
    env_steps: int
    clean_laps_per_track: dict[str, int]
    physx_clean_lap_rate: Interval | None = None


class GeneralisationResult(BenchModel):
    """``generalisation``: the budget, the maps, the summaries and every run."""

    generations: int
    pairs: int
    episode_steps: int
    single: str
    pool_size: int
    held_out: list[str]
    reference_laps: dict[str, float | None]
    racing_laps: dict[str, float | None] = {}
    seeds: int
    summary: dict[str, ConditionSummary]
    runs: list[TrainingRun]


_T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262, 10: 2.228}


def interval(values: list[float]) -> Interval:
    """Mean and 95 % Student-t interval of ``values`` (independent seeds)."""
    n = len(values)
    mean = sum(values) / n
    if n < 2:
        return Interval(mean=round(mean, 4), low=round(mean, 4), high=round(mean, 4), n=n)
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    half = _T95.get(n - 1, 1.96) * sd / math.sqrt(n)
    return Interval(mean=round(mean, 4), low=round(mean - half, 4), high=round(mean + half, 4), n=n)


def register(kinds) -> None:
    p = add_bench_parser(
        kinds, "generalisation", "policies trained on the library, laps on held-out recorded maps", __doc__
    )
    p.add_argument("--seeds", type=int, default=5, help="training seeds per condition (default 5)")
    p.add_argument("--generations", type=int, default=None, help="ES generations per run (default: the recipe's)")
    p.add_argument(
        "--seeds-for",
        nargs="+",
        default=[],
        metavar="COND=N",
        help="per-condition seeds instead of --seeds, e.g. single=10 pool_rand=10",
    )
    p.add_argument("--reuse", type=Path, metavar="JSON", help="take the runs of an earlier --json result as they are")
    p.add_argument("--conditions", nargs="+", choices=CONDITIONS, default=list(CONDITIONS), help="which conditions")
    p.add_argument("--single", default=SINGLE, help=f"the one training track (default {SINGLE})")
    p.add_argument("--policies", type=Path, metavar="DIR", help="keep every trained policy file in DIR")
    p.add_argument("--physx-seeds", type=int, default=0, help="pool_rand policies also driven in PhysX (default 0)")
    p.add_argument(
        "--physx-files",
        nargs="+",
        type=Path,
        metavar="FILE",
        help="only drive these policy files on every held-out map, in PhysX and in our engine (no training)",
    )
    p.set_defaults(func=_run_cli)


def racing_laps(held_out: list[str]) -> dict[str, float | None]:
    """The racing driver's flying lap on each map (``tracks/racelines.json``; None: none
    recorded or not clean). A standing lap from the grid cannot beat it by much: it is
    the yardstick of how fast a map can be driven (issue 35)."""
    from roboracer_arena.library.raceline_index import load_index

    index = load_index()
    out: dict[str, float | None] = {}
    for tid in held_out:
        rec = index.get(tid) if index is not None else None
        d = rec.driver if rec is not None else None
        out[tid] = d.driven_s if d is not None and d.clean else None
    return out


def reference_laps(held_out: list[str]) -> dict[str, float | None]:
    """The reference pure-pursuit driver's lap time on each map (None: no clean lap)."""
    from roboracer_arena.drivers import drive_laps

    out: dict[str, float | None] = {}
    for tid in held_out:
        r = drive_laps(tid)
        out[tid] = r.lap_times[0] if r.completed else None
    return out


def _recipe(condition: str, generations: int | None):
    from roboracer_arena.learn.recipe import Recipe

    r = Recipe()
    if generations is not None:
        r = replace(r, generations=generations)
    if condition == "pool":
        r = replace(r, randomise=False)
    if condition == "plain":
        r = replace(r, base="none")
    return r


def run(
    seeds: int = 5,
    generations: int | None = None,
    conditions: list[str] | tuple[str, ...] = CONDITIONS,
    single: str = SINGLE,
    policies: Path | None = None,
    physx_seeds: int = 0,
    verbose: bool = True,
    held_out: list[str] | None = None,
    seeds_for: dict[str, int] | None = None,
    reuse: GeneralisationResult | None = None,
) -> GeneralisationResult:
    """Train every condition for every seed and drive the held-out maps; see the module
    docstring. ``seeds_for``: a per-condition number of seeds instead of ``seeds``.
    ``reuse``: an earlier result of the same settings whose runs (condition, seed) are
    taken as they are, not retrained (training is deterministic: the same seed gives the
    same policy), so more seeds can be added to a finished run."""
    from roboracer_arena.cli.train import default_pool
    from roboracer_arena.errors import ConfigError
    from roboracer_arena.learn.evaluate import evaluate_policy
    from roboracer_arena.learn.recipe import HELD_OUT
    from roboracer_arena.learn.trainer import make_env, train_policy

    held = list(held_out or HELD_OUT)
    if seeds < 1 or (generations is not None and generations < 1) or physx_seeds < 0:
        raise ConfigError("generalisation: --seeds and --generations must be >= 1, --physx-seeds >= 0")
    if single in held:
        raise ConfigError(f"generalisation: the training track {single!r} is held out")
    pool = default_pool()
    refs = reference_laps(held)
    racing = racing_laps(held)
    if verbose:
        print(f"reference pure-pursuit laps: {refs}", flush=True)
    runs: list[TrainingRun] = []
    envs: dict[tuple, object] = {}
    counts = {c: (seeds_for or {}).get(c, seeds) for c in conditions}
    done = {(r.condition, r.seed): r for r in (reuse.runs if reuse is not None else [])}
    if reuse is not None and (
        reuse.held_out != held or reuse.generations != _recipe("pool_rand", generations).generations
    ):
        raise ConfigError("generalisation: --reuse needs a result with the same held-out maps and budget")
    for cond in conditions:
        recipe = _recipe(cond, generations)
        tracks = [single] if cond == "single" else pool
        key = (cond == "single", recipe.randomise)
        for seed in range(counts[cond]):
            if (cond, seed) in done:
                runs.append(done[(cond, seed)])
                continue
            if key not in envs:
                envs[key] = make_env(tracks, recipe)  # the pool's ~155 tracks load once per env config
            r = replace(recipe, seed=seed)
            c0, t0 = time.process_time(), time.perf_counter()
            policy = train_policy(tracks, r, env=envs[key])
            train_wall, train_cpu = time.perf_counter() - t0, time.process_time() - c0
            path = None
            if policies is not None:
                policies.mkdir(parents=True, exist_ok=True)
                path = policy.save(policies / f"{cond}-seed{seed}.npz")
            laps = []
            for lap in evaluate_policy(policy, held):
                ref = refs.get(lap["track"])
                ratio = lap["lap_time"] / ref if lap["clean_lap"] and ref else None
                laps.append(
                    HeldOutLap(
                        track=lap["track"],
                        clean_lap=lap["clean_lap"],
                        lap_time=None if lap["lap_time"] is None else round(lap["lap_time"], 3),
                        progress=lap["progress"],
                        reference_lap_time=ref,
                        ratio=None if ratio is None else round(ratio, 4),
                    )
                )
            run_ = TrainingRun(
                condition=cond,
                seed=seed,
                generations=int(policy.training["generation"]),
                env_steps=int(policy.training["env_steps"]),
                train_seconds=round(train_wall, 1),
                cpu_seconds=round(train_cpu, 1),
                final_mean_return=float(policy.training["curve"][-1]["mean_return"]),
                clean_laps=sum(lap.clean_lap for lap in laps),
                laps=laps,
                policy_file=None if path is None else str(path),
            )
            if cond == "pool_rand" and seed < physx_seeds:
                run_ = _with_physx(run_, policy, held)
            runs.append(run_)
            if verbose:
                px = "" if run_.physx_clean_laps is None else f", PhysX {run_.physx_clean_laps}/{len(held)}"
                print(
                    f"  {cond:9s} seed {seed}: {run_.clean_laps}/{len(held)} clean laps{px} "
                    f"({run_.env_steps} env-steps, {run_.train_seconds} s)",
                    flush=True,
                )
    for env in envs.values():
        env.close()  # type: ignore[attr-defined]
    return GeneralisationResult(
        generations=_recipe("pool_rand", generations).generations,
        pairs=_recipe("pool_rand", generations).pairs,
        episode_steps=_recipe("pool_rand", generations).episode_steps,
        single=single,
        pool_size=len(pool),
        held_out=held,
        reference_laps=refs,
        seeds=max(counts.values()),
        summary=summarise(runs, single, racing),
        runs=runs,
        racing_laps=racing,
    )


def physx_laps(policy, held: list[str]) -> list[dict]:
    """``policy`` on the PhysX car on every map of ``held`` (``drive --engine physx``)."""
    from roboracer_arena.envs.env_config import EnvConfig
    from roboracer_arena.learn import policy_env_kwargs
    from roboracer_arena.learn.runner import policy_controller
    from roboracer_arena.physx.laps import physx_lap

    config = EnvConfig.build(policy_env_kwargs(policy))
    lid = config.sim.lidar
    laps = []
    for tid in held:
        lap = physx_lap(
            tid,
            lambda track: policy_controller(policy, track, lid.num_beams, lid.fov, config),
            config.sim,
            config.control_rate_hz,
            name="policy",
        )
        laps.append(lap.to_json_dict() | {"clean": lap.clean})
    return laps


def _with_physx(run_: TrainingRun, policy, held: list[str]) -> TrainingRun:
    """``run_`` with its policy's laps on the PhysX car."""
    laps = physx_laps(policy, held)
    return run_.model_copy(update={"physx_laps": laps, "physx_clean_laps": sum(x["clean"] for x in laps)})


class PhysxPolicyRun(BenchModel):
    """One policy file on the PhysX car and in our engine, every held-out map."""

    file: str
    laps: list[dict]
    ours: list[dict]
    mean_ratio_to_ours: float


class PhysxPolicies(BenchModel):
    """``generalisation --physx-files``: each file's laps in PhysX beside ours."""

    files: list[str]
    held_out: list[str]
    runs: list[PhysxPolicyRun]


def physx_runs(files: list[Path], held_out: list[str] | None = None, verbose: bool = True) -> PhysxPolicies:
    """Drive each policy file on every held-out map in PhysX and in our engine."""
    from roboracer_arena.learn import evaluate_policy, load_policy
    from roboracer_arena.learn.recipe import HELD_OUT

    held = list(held_out or HELD_OUT)
    runs = []
    for f in files:
        policy = load_policy(f)
        laps, ours = physx_laps(policy, held), evaluate_policy(policy, held)
        ratios = [
            p["lap_time_s"] / o["lap_time"]
            for p, o in zip(laps, ours)
            if p["clean"] and o["clean_lap"] and o["lap_time"]
        ]
        runs.append(
            PhysxPolicyRun(
                file=str(f),
                laps=laps,
                ours=ours,
                mean_ratio_to_ours=round(sum(ratios) / len(ratios), 4) if ratios else float("nan"),
            )
        )
        if verbose:
            print(f"  {f}: {sum(x['clean'] for x in laps)}/{len(held)} clean laps in PhysX", flush=True)
    return PhysxPolicies(files=[str(f) for f in files], held_out=held, runs=runs)


_DESCRIPTIONS = {
    "single": "residual, one track ({single}), randomised",
    "pool": "residual, pool, no randomisation",
    "pool_rand": "residual, pool, randomised (default recipe)",
    "plain": "plain MLP, pool, randomised",
}


def summarise(
    runs: list[TrainingRun], single: str = SINGLE, racing: dict[str, float | None] | None = None
) -> dict[str, ConditionSummary]:
    """Per condition: clean-lap rate and lap-time ratios to the reference pure pursuit and
    (with ``racing``) to the racing driver's flying lap (means of per-seed means, 95 % t
    intervals over seeds), mean training cost, clean laps per map out of the seeds."""
    out: dict[str, ConditionSummary] = {}
    for cond in dict.fromkeys(r.condition for r in runs):
        rs = [r for r in runs if r.condition == cond]
        rates = [r.clean_laps / len(r.laps) for r in rs]
        ratios, racing_ratios = [], []
        for r in rs:
            vals = [lap.ratio for lap in r.laps if lap.ratio is not None]
            if vals:
                ratios.append(sum(vals) / len(vals))
            fast = [
                lap.lap_time / racing[lap.track]
                for lap in r.laps
                if racing and lap.clean_lap and lap.lap_time and racing.get(lap.track)
            ]
            if fast:
                racing_ratios.append(sum(fast) / len(fast))
        per_track: dict[str, int] = {}
        for r in rs:
            for lap in r.laps:
                per_track[lap.track] = per_track.get(lap.track, 0) + int(lap.clean_lap)
        px = [r.physx_clean_laps / len(r.laps) for r in rs if r.physx_clean_laps is not None]
        out[cond] = ConditionSummary(
            description=_DESCRIPTIONS[cond].format(single=single),
            clean_lap_rate=interval(rates),
            lap_time_ratio=interval(ratios) if ratios else None,
            racing_ratio=interval(racing_ratios) if racing_ratios else None,
            train_wall_seconds=round(sum(r.train_seconds for r in rs) / len(rs), 1),
            train_cpu_seconds=round(sum(r.cpu_seconds for r in rs) / len(rs), 1),
            env_steps=round(sum(r.env_steps for r in rs) / len(rs)),
            clean_laps_per_track=per_track,
            physx_clean_lap_rate=interval(px) if px else None,
        )
    return out


def _fmt(i: Interval | None, pct: bool = False) -> str:
    if i is None:
        return "-"
    k = 100 if pct else 1
    d = 1 if pct else 3
    return f"{i.mean * k:.{d}f} [{i.low * k:.{d}f}, {i.high * k:.{d}f}]"


def print_table(res: GeneralisationResult) -> None:
    print(
        f"ES: {res.generations} generations x {2 * res.pairs} envs x <= {res.episode_steps} steps; "
        f"seeds per condition: {', '.join(f'{k} {v.clean_lap_rate.n}' for k, v in res.summary.items())}; "
        f"pool: {res.pool_size} catalog tracks"
    )
    print(f"held-out recorded maps ({len(res.held_out)}): {', '.join(res.held_out)}")
    head = f"{'condition':<46}{'clean laps % [95% CI]':>26}{'lap time / reference':>28}{'train s':>9}{'CPU s':>8}"
    print(head)
    for s in res.summary.values():
        print(
            f"{s.description:<46}{_fmt(s.clean_lap_rate, True):>26}{_fmt(s.lap_time_ratio):>28}"
            f"{s.train_wall_seconds:>9.1f}{s.train_cpu_seconds:>8.1f}"
        )
    for name, s in res.summary.items():
        if s.physx_clean_lap_rate is not None:
            print(
                f"{name} in PhysX: clean laps {_fmt(s.physx_clean_lap_rate, True)} % over {s.physx_clean_lap_rate.n} policy files"
            )
    for name, s in res.summary.items():
        n = s.clean_lap_rate.n
        missed = {k: v for k, v in s.clean_laps_per_track.items() if v < n}
        print(f"  {name}: " + (", ".join(f"{k} {v}/{n}" for k, v in missed.items()) or "every map every seed"))


def _run_cli(args: argparse.Namespace) -> int:
    if args.physx_files:
        px = physx_runs(args.physx_files)
        for r in px.runs:
            print(
                f"{r.file}: {sum(x['clean'] for x in r.laps)}/{len(r.laps)} clean in PhysX, lap time x{r.mean_ratio_to_ours:.3f} ours"
            )
        write_json(args.json, px)
        return 0
    from roboracer_arena.errors import ConfigError

    seeds_for = {}
    for item in args.seeds_for:
        cond, _, n = item.partition("=")
        if cond not in CONDITIONS or not n.isdigit() or int(n) < 1:
            raise ConfigError(f"--seeds-for: expected COND=N with COND in {CONDITIONS} and N >= 1, got {item!r}")
        seeds_for[cond] = int(n)
    reuse = GeneralisationResult.model_validate_json(args.reuse.read_text()) if args.reuse else None
    res = run(
        args.seeds,
        args.generations,
        args.conditions,
        args.single,
        args.policies,
        args.physx_seeds,
        seeds_for=seeds_for,
        reuse=reuse,
    )
    print_table(res)
    write_json(args.json, res)
    return 0


def run_quick() -> GeneralisationResult:
    """``bench all``: one seed, 5 generations, the two headline conditions."""
    res = run(seeds=1, generations=5, conditions=("single", "pool_rand"))
    print_table(res)
    return res
