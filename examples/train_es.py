#!/usr/bin/env python3
"""Train a lidar driving policy with numpy-only evolution strategies, then drive a lap.

    python examples/train_es.py                       # gym-berlin, about a minute on 2 cores
    python examples/train_es.py --track generated:gen-l040-* --generations 40
    python examples/train_es.py --png curve.png --json result.json
    python examples/train_es.py --ray auto --ray-actors 2   # rollouts in Ray actors ([ray] extra)
    python examples/train_es.py --sources DIR         # recorded maps (gym-berlin) from an installed wheel

The trainer (roboracer_arena.learn.es) is ~200 lines of numpy: a 56 -> 32 -> 2 MLP on 54
lidar beams (clipped to 10 m, scaled to [0, 1]) plus speed and steer, antithetic ES on
one native vector env (or, with --ray, a RayVectorEnv: the same environments split over
Ray actors, each holding one native batch; same seeds, same curve) (autoreset DISABLED, each +/- pair started at the same pose with
reset(options={"track_ids", "poses"})), centred ranks, Adam. After training it drives the
mean policy from the grid start and reports the lap.
"""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import replace

from roboracer_arena.learn import ESConfig, evaluate_laps, train
from roboracer_arena.scripting import add_sources_argument, apply_sources, run_script


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--track", default="gym-berlin", help="any track= value: catalog id, pattern, map YAML")
    p.add_argument("--generations", type=int, default=ESConfig.generations)
    p.add_argument("--pairs", type=int, default=ESConfig.pairs, help="antithetic pairs (2x envs)")
    p.add_argument("--episode-steps", type=int, default=ESConfig.episode_steps)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--png", help="write the learning curve here (PNG)")
    p.add_argument("--json", help="write curve and lap result here (JSON)")
    p.add_argument("--no-lap", action="store_true", help="skip the final lap evaluation")
    p.add_argument("--ray", metavar="ADDRESS", help="roll out in Ray actors: auto, local or HOST:PORT")
    p.add_argument("--ray-actors", type=int, default=2, metavar="N", help="Ray actors (2 x pairs must divide by N)")
    add_sources_argument(p)
    args = p.parse_args(argv)
    return run_script("train_es.py", lambda: _run(args))


def _run(args: argparse.Namespace) -> int:
    apply_sources(args.sources)
    cfg = replace(
        ESConfig(), generations=args.generations, pairs=args.pairs, episode_steps=args.episode_steps, seed=args.seed
    )

    def show(row: dict) -> None:
        print(
            f"gen {row['generation']:3d}  mean return {row['mean_return']:7.2f}  best {row['max_return']:7.2f}"
            f"  env-steps {row['env_steps']:8d}  {row['seconds']:6.1f} s",
            flush=True,
        )

    env = None
    if args.ray:
        from roboracer_arena.distributed.ray_cluster import connect
        from roboracer_arena.learn.es import make_training_env

        connect(args.ray)
        env = make_training_env(args.track, cfg, ray_actors=args.ray_actors)
    result = train(args.track, cfg, progress=show, env=env)
    if env is not None:
        env.close()
    rate = result.env_steps / max(result.seconds, 1e-9)
    print(f"trained: {result.env_steps} env-steps in {result.seconds:.1f} s ({rate:,.0f} env-steps/s)")
    out = result.summary()
    if not args.no_lap:
        laps = evaluate_laps(result.theta, args.track, cfg)
        for lap in laps:
            verdict = (
                f"clean lap in {lap['lap_time']:.2f} s"
                if lap["clean_lap"]
                else f"no clean lap ({lap['progress']:.1f} m)"
            )
            print(f"lap on {lap['track']}: {verdict}")
        out["laps"] = laps
    if args.png:
        from roboracer_arena.learn.curve import plot_curve

        plot_curve(result.curve, args.png, f"ES on {args.track}: {result.env_steps} env-steps, {result.seconds:.0f} s")
    if args.json:
        from roboracer_arena.foundation.fileio import atomic_write_text

        atomic_write_text(args.json, json.dumps(out, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
