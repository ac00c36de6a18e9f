"""``roboracer-arena train``: train a lidar driving policy with evolution strategies on a
track pool and write a policy file (numpy .npz with a JSON header; see
``roboracer_arena.learn.policy_file``) that ``drive --policy``, ``ros2 --policy`` and
``roboracer_arena.load_policy`` read.

The default recipe is a residual on the reference pure pursuit, trained on every catalog
track except the held-out recorded maps, with friction, mass, lag, lidar and actuation-
delay randomisation (``roboracer_arena.learn.recipe``). A progress bar shows the learning
curve; checkpoints are written atomically every few generations, so Ctrl-C (or SIGTERM)
leaves the last whole checkpoint, and ``--resume`` continues it exactly.

Exit codes: 0 trained, 2 bad input, 130 interrupted (the last checkpoint is kept)."""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

from ..errors import InvalidArgumentError, PolicyFileError
from ._common import add_json_flag, print_json


def register(sub) -> None:
    p = sub.add_parser(
        "train",
        help="train a lidar policy on a track pool and write a policy file",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument(
        "--tracks",
        nargs="+",
        metavar="TRACK",
        help="training tracks: catalog ids, patterns ('generated:*'), selections ('circuits') or map YAMLs "
        "(default: every catalog track except the held-out maps)",
    )
    p.add_argument("--out", type=Path, default=Path("policy.npz"), help="policy file to write (default policy.npz)")
    p.add_argument("--resume", action="store_true", help="continue the checkpoint in --out (same settings)")
    p.add_argument("--generations", type=int, default=None, help="ES generations (default 40)")
    p.add_argument("--minutes", type=float, default=None, help="stop after this much wall time (a checkpoint is kept)")
    p.add_argument("--pairs", type=int, default=None, help="antithetic pairs per generation (default 16)")
    p.add_argument("--seed", type=int, default=0, help="training seed (default 0)")
    p.add_argument(
        "--recipe",
        choices=("residual", "plain"),
        default="residual",
        help="residual: an MLP correcting the reference pure pursuit (default); plain: an MLP alone",
    )
    p.add_argument("--no-randomise", action="store_true", help="train without domain randomisation")
    p.add_argument(
        "--checkpoint-every",
        type=int,
        default=5,
        metavar="N",
        help="write a checkpoint every N generations (default 5)",
    )
    p.add_argument("--curve", type=Path, metavar="OUT.png", help="learning-curve picture (default: beside --out)")
    p.add_argument("--no-eval", action="store_true", help="skip the laps on the held-out maps after training")
    add_json_flag(p)
    p.set_defaults(func=run)


def _recipe(args: argparse.Namespace):
    from ..learn.recipe import Recipe

    r = Recipe(base="pure_pursuit" if args.recipe == "residual" else "none", seed=args.seed)
    if args.no_randomise:
        r = replace(r, randomise=False)
    for flag, lo, hi in (("generations", 1, 100_000), ("pairs", 1, 4096)):
        v = getattr(args, flag)
        if v is not None:
            if not lo <= v <= hi:
                raise InvalidArgumentError(f"--{flag} must be in [{lo}, {hi}], got {v}")
            r = replace(r, **{flag: v})
    if not 1 <= args.checkpoint_every <= 100_000:
        raise InvalidArgumentError(f"--checkpoint-every must be in [1, 100000], got {args.checkpoint_every}")
    if args.minutes is not None and not 0 < args.minutes <= 1e6:
        raise InvalidArgumentError(f"--minutes must be > 0, got {args.minutes}")
    return r


def default_pool() -> list[str]:
    """Every catalog track id except the held-out maps."""
    from ..catalog.catalog_file import load_catalog
    from ..learn.recipe import HELD_OUT

    return [e.id for e in load_catalog().entries if e.id not in HELD_OUT]


def run(args: argparse.Namespace) -> int:
    from ..learn.evaluate import evaluate_policy
    from ..learn.policy_file import load_policy
    from ..learn.recipe import HELD_OUT
    from ..learn.trainer import make_env, train_policy

    recipe = _recipe(args)
    resume = None
    if args.resume:
        if not args.out.exists():
            raise PolicyFileError(f"{args.out}: --resume needs a checkpoint there (none exists)")
        resume = load_policy(args.out)
    tracks = args.tracks or default_pool()
    say = (lambda *a: None) if args.json else (lambda *a: print(*a, file=sys.stderr, flush=True))
    say(f"loading {len(tracks)} training track(s) ...")
    env = make_env(tracks, recipe)
    bar, last = None, {}
    if not args.json:
        from tqdm import tqdm

        start = 0 if resume is None else int(resume.training.get("generation", 0))
        bar = tqdm(total=recipe.generations, initial=start, desc="training", unit="gen", file=sys.stderr)

    def progress(row: dict[str, float]) -> None:
        last.update(row)
        if bar is not None:
            bar.set_postfix_str(f"mean return {row['mean_return']:.1f}, best {row['max_return']:.1f}", refresh=False)
            bar.update(1)

    try:
        policy = train_policy(
            tracks,
            recipe,
            out=args.out,
            resume=resume,
            max_seconds=None if args.minutes is None else 60.0 * args.minutes,
            progress=progress,
            env=env,
            checkpoint_every=args.checkpoint_every,
        )
    except KeyboardInterrupt:
        if bar is not None:
            bar.close()
        kept = "no checkpoint yet" if not args.out.exists() else f"the last checkpoint is in {args.out}"
        print(
            f"interrupted after generation {last.get('generation', -1) + 1}: {kept} (--resume continues it)",
            file=sys.stderr,
        )
        raise
    finally:
        env.close()
    if bar is not None:
        bar.close()
    curve_path = args.curve or args.out.with_suffix(".curve.png")
    from ..learn.curve import plot_curve

    plot_curve(policy.training["curve"], curve_path, f"train: {args.recipe}, {len(tracks)} track(s), seed {args.seed}")
    summary = {
        "policy": str(args.out),
        "curve": str(curve_path),
        "generations": policy.training["generation"],
        "env_steps": policy.training["env_steps"],
        "seconds": policy.training["seconds"],
        "final_mean_return": policy.training["curve"][-1]["mean_return"],
    }
    if not args.no_eval:
        held = [t for t in HELD_OUT if t not in tracks]
        laps = evaluate_policy(policy, held) if held else []
        summary["held_out"] = laps
        summary["held_out_clean_laps"] = sum(lap["clean_lap"] for lap in laps)
    if args.json:
        print_json(summary)
        return 0
    curve = policy.training["curve"]
    every = max(1, len(curve) // 8)
    print("generation  mean return  best return  env-steps  seconds")
    for row in curve[::every] + ([curve[-1]] if (len(curve) - 1) % every else []):
        print(
            f"{row['generation']:>10}  {row['mean_return']:>11.1f}  {row['max_return']:>11.1f}  {row['env_steps']:>9}  {row['seconds']:>7.1f}"
        )
    print(f"wrote {args.out} ({summary['env_steps']} env-steps, {summary['seconds']:.0f} s) and {curve_path}")
    if "held_out" in summary:
        laps = summary["held_out"]
        print(f"held-out maps: {summary['held_out_clean_laps']}/{len(laps)} clean laps from the grid start")
        for lap in laps:
            t = f"{lap['lap_time']:.2f} s" if lap["lap_time"] is not None else f"stopped at {lap['progress']:.1f} m"
            print(f"  {lap['track']:<28} {'clean' if lap['clean_lap'] else 'FAILED':<7} {t}")
    return 0
