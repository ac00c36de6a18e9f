#!/usr/bin/env python3
"""Regenerate every figure in README.md and BENCHMARKS.md that a script produces, from the
current build (``make docs-figures``), and check the docs against their data.

    python scripts/docs_figures.py                 # run everything, write data, pictures and doc blocks
    python scripts/docs_figures.py --list          # every figure: its blocks, data file and how CI holds it
    python scripts/docs_figures.py --only es       # only the README's ES figures (about a minute)
    python scripts/docs_figures.py --check         # docs blocks == their committed data (no training)

Each figure has a data file (docs/learning/ for the learning runs, docs/figures/ for the
``bench`` commands: their JSON wrapped with the command, build, machine and the load
average sampled while it ran), maybe a picture, and one or more blocks in a doc between
``<!-- docs-figures:BLOCK ... -->`` and ``<!-- /docs-figures:BLOCK -->`` rendered from the
data alone (never edit inside a block). tests/docs/test_docs_figures.py checks every block
against its data, and reruns the figures whose deterministic part takes seconds (``ci``
"rerun") or that are learning runs (es, generalisation) and compares; "long" figures
(minutes: sweeps, Table 3's DE, PhysX laps) are rerun only here; "measured" figures are
timings, which no rerun reproduces.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))
sys.path.insert(1, str(ROOT))  # the benchmarks package (a checkout's, not in the wheel)
from figures_bench import BENCH_FIGURES  # noqa: E402  (a sibling module of this script)

LEARNING = ROOT / "docs" / "learning"
ES_TRACK = "gym-berlin"


def _timed(body: Callable[[], Any]) -> tuple[Any, dict[str, float]]:
    load = os.getloadavg()[0]
    t0, c0 = time.perf_counter(), time.process_time()
    out = body()
    timing = {
        "wall_seconds": round(time.perf_counter() - t0, 1),
        "cpu_seconds": round(time.process_time() - c0, 1),
        "load_average": round((load + os.getloadavg()[0]) / 2, 1),
    }
    return out, timing


def _added_timing(a: dict[str, float], b: dict[str, float]) -> dict[str, float]:
    """The timing of two runs that make one figure: wall and CPU added, load weighted by wall."""
    w = a["wall_seconds"] + b["wall_seconds"]
    load = (a["load_average"] * a["wall_seconds"] + b["load_average"] * b["wall_seconds"]) / max(w, 1e-9)
    return {
        "wall_seconds": round(w, 1),
        "cpu_seconds": round(a["cpu_seconds"] + b["cpu_seconds"], 1),
        "load_average": round(load, 1),
    }


# ---------------------------------------------------------------- ES on Berlin (README)
def es_data(profile: str = "") -> dict[str, Any]:
    """``examples/train_es.py`` with its defaults on gym-berlin: curve, lap, parameters."""
    from roboracer_arena.learn import ESConfig, evaluate_laps, train

    cfg = ESConfig()
    result, timing = _timed(lambda: train(ES_TRACK, cfg))
    doc = result.summary()
    doc["laps"] = evaluate_laps(result.theta, ES_TRACK, cfg)
    doc["timing"] = timing
    doc["theta"] = [float(x) for x in result.theta]
    return doc


def es_deterministic(doc: dict[str, Any]) -> dict[str, Any]:
    """What must reproduce exactly on the same build: the curve (timings dropped) and the laps."""
    return {
        "curve": [{k: r[k] for k in ("generation", "mean_return", "max_return", "env_steps")} for r in doc["curve"]],
        "laps": doc["laps"],
    }


def es_picture(doc: dict[str, Any]) -> None:
    from roboracer_arena.learn.curve import plot_curve

    secs = doc["timing"]["wall_seconds"]
    plot_curve(
        doc["curve"], LEARNING / "es_berlin.png", f"ES on {ES_TRACK}: {doc['env_steps']} env-steps, {secs:.0f} s"
    )


def es_block(doc: dict[str, Any]) -> str:
    lap = doc["laps"][0]
    t, gens = doc["timing"], len(doc["curve"])
    verdict = (
        f"the policy lapped Berlin cleanly from the grid start in {lap['lap_time']:.2f} s"
        if lap["clean_lap"]
        else f"the policy did not lap Berlin cleanly ({lap['progress']:.1f} m from the grid start)"
    )
    return (
        f"{gens} generations ({doc['env_steps'] / 1e3:.0f}k env-steps, default reward) took {t['wall_seconds']:.0f} s "
        f"of wall time ({t['cpu_seconds']:.0f} s CPU) on the shared 2-core machine (load average about "
        f"{t['load_average']:.1f}), and {verdict}:\n\n"
        f"![ES learning curve on Berlin](docs/learning/es_berlin.png)\n"
    )


# ---------------------------------------------------------------- generalisation (BENCHMARKS)
POLICIES = LEARNING / "policies"  # the benchmark's policy files, kept: the PhysX figure drives them
#: The headline comparison (one track against the default recipe) gets 10 seeds: with 5 its
#: intervals were too wide to separate rates of 0.81 and 0.97 (2026-11-28 run).
HEADLINE_SEEDS = {"single": 10, "pool_rand": 10}
PHYSX_SEEDS = 4  # pool_rand policy files driven in PhysX (about 9 min each on 2 cores)


def generalisation_data(profile: str = "") -> dict[str, Any]:
    """``python -m benchmarks generalisation --policies docs/learning/policies --seeds-for single=10 pool_rand=10``."""
    from benchmarks import generalisation

    reuse, before = None, None
    if os.environ.get("DOCS_FIGURES_REUSE") and (LEARNING / "generalisation.json").is_file():
        # Add seeds to the committed run instead of retraining it (training is deterministic).
        before = json.loads((LEARNING / "generalisation.json").read_text())
        runs = [
            {**r, "policy_file": str(ROOT / r["policy_file"]) if r.get("policy_file") else None} for r in before["runs"]
        ]
        fields = {k: v for k, v in before.items() if k != "timing"}
        reuse = generalisation.GeneralisationResult.model_validate({**fields, "runs": runs})
    res, timing = _timed(lambda: generalisation.run(policies=POLICIES, seeds_for=HEADLINE_SEEDS, reuse=reuse))
    if before is not None:  # the whole figure's cost: the reused run's and this one's
        timing = _added_timing(before["timing"], timing)
    doc = res.model_dump(mode="json")
    for r in doc["runs"]:  # relative to the checkout, so the data does not name this machine
        if r["policy_file"]:
            r["policy_file"] = str(Path(r["policy_file"]).resolve().relative_to(ROOT))
    doc["timing"] = timing
    return doc


def generalisation_deterministic(doc: dict[str, Any]) -> dict[str, Any]:
    keep = ("condition", "seed", "env_steps", "final_mean_return", "clean_laps", "laps")
    return {"runs": [{k: r[k] for k in keep} for r in doc["runs"]]}


def _ci(i: dict[str, Any] | None, pct: bool = False) -> str:
    if i is None:
        return "–"
    k, d = (100, 1) if pct else (1, 3)
    return f"{i['mean'] * k:.{d}f} [{i['low'] * k:.{d}f}, {i['high'] * k:.{d}f}]"


def generalisation_block(doc: dict[str, Any]) -> str:
    t, s = doc["timing"], doc["summary"]
    per_cond = ", ".join(f"{k} {v['clean_lap_rate']['n']}" for k, v in s.items())
    rows = [
        f"| {v['description']} | **{_ci(v['clean_lap_rate'], True)}** | {_ci(v['lap_time_ratio'])} | "
        f"{_ci(v.get('racing_ratio'))} | {v['train_wall_seconds']:.0f} s | {v['train_cpu_seconds']:.0f} s |"
        for v in s.values()
    ]
    missed = []
    for k, v in s.items():
        n_seeds = v["clean_lap_rate"]["n"]
        low = {m: n for m, n in v["clean_laps_per_track"].items() if n < n_seeds}
        missed.append(f"{k}: " + (", ".join(f"{m} {n}/{n_seeds}" for m, n in low.items()) or "every map, every seed"))
    refs = ", ".join(f"{m} {'–' if r is None else f'{r:.2f} s'}" for m, r in doc["reference_laps"].items())
    racing = ", ".join(f"{m} {'–' if r is None else f'{r:.2f} s'}" for m, r in doc.get("racing_laps", {}).items())
    return (
        f"`python -m benchmarks generalisation --policies docs/learning/policies --seeds-for single=10 pool_rand=10`: "
        f"{doc['generations']} ES generations "
        f"x {2 * doc['pairs']} envs x <= {doc['episode_steps']} steps per run; seeds per condition: {per_cond}; pool "
        f"of {doc['pool_size']} catalog tracks; {len(doc['held_out'])} held-out recorded maps, one lap each per "
        f"policy. Whole command: {t['wall_seconds'] / 60:.1f} min wall, {t['cpu_seconds'] / 60:.1f} min CPU on "
        f"the shared 2-core machine (load average about {t['load_average']:.1f}; pool start-up included). "
        f"Intervals are 95 % Student-t over seeds.\n\n"
        f"| condition | clean laps % [95 % CI] | lap time / reference lap [95 % CI] | lap time / racing driver's "
        f"flying lap [95 % CI] | train wall | train CPU |\n"
        f"|---|---:|---:|---:|---:|---:|\n" + "\n".join(rows) + "\n\n"
        f"Held-out maps: {', '.join(doc['held_out'])}.\n\n"
        f"Maps not lapped cleanly by every seed: {'; '.join(missed)}.\n\n"
        f"Reference pure-pursuit laps (`roboracer-arena drive`): {refs}.\n\n"
        f"Racing driver's flying laps (`tracks/racelines.json`, `drive --raceline`; the yardstick of how fast "
        f"a map can be driven, from a rolling start): {racing}.\n"
    )


def generalisation_readme_block(doc: dict[str, Any]) -> str:
    s, n = doc["summary"], len(doc["held_out"])
    per_cond = ", ".join(f"{k} {v['clean_lap_rate']['n']}" for k, v in s.items())
    rows = [
        f"| {v['description']} | {_ci(v['clean_lap_rate'], True)} % | {_ci(v['lap_time_ratio'])} |" for v in s.values()
    ]
    return (
        f"On {n} held-out recorded maps, one lap each from the grid start, "
        f"training seeds per condition: {per_cond} "
        f"(95 % intervals over seeds; lap time divided by the reference pure pursuit's on the "
        f"same map; training about {s.get('pool_rand', next(iter(s.values())))['train_wall_seconds']:.0f} s "
        f"per policy on the shared 2-core machine, plus about half a minute to load the pool):\n\n"
        f"| condition | clean laps | lap time / reference |\n|---|---:|---:|\n" + "\n".join(rows) + "\n"
    )


def physx_policies_data(profile: str = "") -> dict[str, Any]:
    """The first PHYSX_SEEDS default-recipe policy files of the generalisation figure on the
    PhysX car (``drive --engine physx --policy``), every held-out map. With
    DOCS_FIGURES_REUSE set, files already in the committed data keep their runs (the laps
    are deterministic) and only the others are driven; the timing adds up both."""
    from benchmarks import generalisation

    files = [(POLICIES / f"pool_rand-seed{k}.npz").relative_to(ROOT) for k in range(PHYSX_SEEDS)]
    data = LEARNING / "generalisation_physx.json"
    before = json.loads(data.read_text()) if os.environ.get("DOCS_FIGURES_REUSE") and data.is_file() else None
    kept = {r["file"]: r for r in (before or {}).get("runs", [])}
    todo = [f for f in files if str(f) not in kept]
    res, timing = _timed(lambda: generalisation.physx_runs([ROOT / f for f in todo]))
    fresh = {str(f): r.model_copy(update={"file": str(f)}).model_dump(mode="json") for r, f in zip(res.runs, todo)}
    if before is not None:
        timing = _added_timing(before["timing"], timing)
    doc = {
        "files": [str(f) for f in files],
        "held_out": res.held_out,
        "runs": [kept.get(str(f)) or fresh[str(f)] for f in files],
        "timing": timing,
    }
    return doc


def physx_policies_readme_block(doc: dict[str, Any]) -> str:
    clean = sum(lap["clean"] for r in doc["runs"] for lap in r["laps"])
    total = sum(len(r["laps"]) for r in doc["runs"])
    ratios = ", ".join(f"{r['mean_ratio_to_ours']:.3f}" for r in doc["runs"])
    return (
        f"On the PhysX car (`drive --engine physx --policy`, PhysX's own lidar raycasts), the first "
        f"{len(doc['runs'])} default-recipe policy files lap **{clean}/{total}** held-out maps cleanly; their "
        f"PhysX lap times are {ratios} × their laps in our engine.\n"
    )


def physx_policies_deterministic(doc: dict[str, Any]) -> dict[str, Any]:
    return {"files": doc["files"], "clean": [[lap["clean"] for lap in f["laps"]] for f in doc["runs"]]}


def physx_policies_block(doc: dict[str, Any]) -> str:
    t = doc["timing"]
    rows = []
    for r in doc["runs"]:
        clean = sum(lap["clean"] for lap in r["laps"])
        rows.append(f"| `{Path(r['file']).name}` | **{clean}/{len(r['laps'])}** | {r['mean_ratio_to_ours']:.3f} |")
    failed = [f"{Path(r['file']).name}: {lap['track']}" for r in doc["runs"] for lap in r["laps"] if not lap["clean"]]
    return (
        f"`python -m benchmarks generalisation --physx-files {' '.join(doc['files'])}`: {t['wall_seconds'] / 60:.1f} min wall on the shared 2-core "
        f"machine (load average about {t['load_average']:.1f}).\n\n"
        f"| policy file | clean laps in PhysX | PhysX lap time / our lap time |\n|---|---:|---:|\n"
        + "\n".join(rows)
        + "\n\n"
        + ("Not clean in PhysX: " + "; ".join(failed) + ".\n" if failed else "Every map clean in PhysX.\n")
    )


# ---------------------------------------------------------------- the registry
FIGURES: dict[str, dict[str, Any]] = {
    "es": {
        "data": LEARNING / "es_berlin.json",
        "run": es_data,
        "picture": es_picture,
        "deterministic": es_deterministic,
        "blocks": [("README.md", "es-berlin", es_block)],
        "about": "examples/train_es.py defaults on gym-berlin: curve, env-steps, lap (README)",
        "ci": "rerun",
    },
    "generalisation": {
        "data": LEARNING / "generalisation.json",
        "run": generalisation_data,
        "picture": None,
        "deterministic": generalisation_deterministic,
        "blocks": [
            ("BENCHMARKS.md", "generalisation", generalisation_block),
            ("README.md", "generalisation-readme", generalisation_readme_block),
        ],
        "about": "bench generalisation: policies on one track vs the pool, held-out recorded maps (about 30 min)",
        "ci": "long",
    },
    "generalisation-physx": {
        "data": LEARNING / "generalisation_physx.json",
        "run": physx_policies_data,
        "picture": None,
        "deterministic": physx_policies_deterministic,
        "blocks": [
            ("BENCHMARKS.md", "generalisation-physx", physx_policies_block),
            ("README.md", "generalisation-physx-readme", physx_policies_readme_block),
        ],
        "about": "the generalisation figure's default-recipe policy files on the PhysX car (about 20 min)",
        "ci": "long",
    },
    **BENCH_FIGURES,
}


def _block_re(name: str) -> re.Pattern[str]:
    return re.compile(rf"(<!-- docs-figures:{name} [^\n]*-->\n)(.*?)(<!-- /docs-figures:{name} -->)", re.S)


def read_data(key: str) -> dict[str, Any]:
    return json.loads(Path(FIGURES[key]["data"]).read_text())


def check(keys: list[str] | None = None) -> list[str]:
    """Problems: a doc block missing, or different from the rendering of its committed data."""
    problems = []
    for key in keys or list(FIGURES):
        if not Path(FIGURES[key]["data"]).is_file():
            problems.append(
                f"{Path(FIGURES[key]['data']).relative_to(ROOT)}: missing (make docs-figures FIGURES='--only {key}')"
            )
            continue
        doc = read_data(key)
        for file, name, render in FIGURES[key]["blocks"]:
            m = _block_re(name).search((ROOT / file).read_text())
            if m is None:
                problems.append(f"{file}: no docs-figures:{name} block")
            elif m.group(2) != render(doc):
                problems.append(
                    f"{file}: block {name} differs from {FIGURES[key]['data'].name} (run make docs-figures)"
                )
    return problems


def write_blocks(key: str, doc: dict[str, Any]) -> None:
    from roboracer_arena.foundation.fileio import atomic_write_text

    for file, name, render in FIGURES[key]["blocks"]:
        path = ROOT / file
        body = render(doc)
        text, n = _block_re(name).subn(lambda m, body=body: m.group(1) + body + m.group(3), path.read_text())
        if n != 1:
            raise SystemExit(f"docs_figures.py: {file} needs exactly one docs-figures:{name} block, found {n}")
        atomic_write_text(path, text)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--only", choices=list(FIGURES), action="append", help="only these figures (repeatable)")
    p.add_argument("--check", action="store_true", help="only compare the doc blocks with the committed data")
    p.add_argument("--list", action="store_true", help="list the figures, their blocks and how CI holds them")
    p.add_argument(
        "--blocks-only",
        action="store_true",
        help="rewrite the doc blocks from the committed data without rerunning anything (e.g. after a merge)",
    )
    p.add_argument(
        "--build",
        default=os.environ.get("DOCS_FIGURES_BUILD", "unstated"),
        help="the build profile to record with the measurements (make docs-figures: release)",
    )
    args = p.parse_args(argv)
    keys = args.only or list(FIGURES)
    if args.list:
        for key in keys:
            fig = FIGURES[key]
            blocks = ", ".join(f"{f}:{b}" for f, b, _ in fig["blocks"])
            print(f"{key:<16} ci={fig['ci']:<9} {Path(fig['data']).relative_to(ROOT)}  [{blocks}]  {fig['about']}")
        return 0
    if args.blocks_only:
        for key in keys:
            write_blocks(key, read_data(key))
        return 0
    if args.check:
        problems = check(keys)
        for line in problems:
            print(f"docs_figures.py: {line}", file=sys.stderr)
        return 1 if problems else 0
    from roboracer_arena.foundation.fileio import atomic_write_text

    for key in keys:
        fig = FIGURES[key]
        print(f"== {key}", flush=True)
        doc = fig["run"](args.build)
        Path(fig["data"]).parent.mkdir(parents=True, exist_ok=True)
        atomic_write_text(fig["data"], json.dumps(doc, indent=1) + "\n")
        if fig.get("picture"):
            fig["picture"](doc)
        write_blocks(key, doc)
        timing = doc.get("timing") or doc["measured"]
        print(f"   {fig['data'].relative_to(ROOT)}: {json.dumps(timing)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
