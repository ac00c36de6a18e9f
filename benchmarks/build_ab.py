#!/usr/bin/env python3
"""A/B of ``python -m benchmarks build`` between two builds of the package, interleaved
(A, B, A, B, ...) so that load drifts hit both alike; prints a Markdown table of CPU
seconds per build (the least load-sensitive figure) and USD sizes.

    # each DIR holds a roboracer_arena package with its compiled _core (e.g. a worktree's
    # python/ with the _core.abi3.so of its release wheel copied in)
    python -m benchmarks.build_ab --a /work/wt/before/python --b /work/wt/after/python \\
        --out runs/ --rounds 3 --sizes columbia gbr vegas "Spa x1.64"
    python -m benchmarks.build_ab --out runs/ --summarise   # the table from saved runs
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

from benchmarks import CHECKOUT


def run(side: str, pythonpath: str, out: Path, i: int, sizes: list[str], repeat: int) -> None:
    # The side's package first, then this checkout (for the benchmarks package itself).
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([pythonpath, str(CHECKOUT)])}
    cmd = [sys.executable, "-m", "benchmarks", "build"]
    cmd += [
        "--sizes",
        *sizes,
        "--repeat",
        str(repeat),
        "--json",
        str(out / f"build-ab-{side}-{i}.json"),
    ]
    subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL)


def summarise(out: Path) -> str:
    cpu: dict[tuple[str, str], list[float]] = {}
    usd: dict[tuple[str, str], int] = {}
    loads = []
    for f in sorted(out.glob("build-ab-*-*.json")):
        side = f.stem.split("-")[2]
        d = json.loads(f.read_text())
        loads.append(
            d.get("load_average", [0])[0] if isinstance(d.get("load_average"), list) else d.get("load_average")
        )
        for r in d["rows"]:
            cpu.setdefault((r["label"], side), []).append(r["cpu_seconds"])
            usd[(r["label"], side)] = r["usd_bytes"]
    lines = ["| map | A CPU s (runs) | B CPU s (runs) | B / A (means) | USD bytes A → B |", "|---|---|---|---:|---|"]
    for label in dict.fromkeys(k[0] for k in cpu):
        a, b = cpu.get((label, "a"), []), cpu.get((label, "b"), [])
        if not a or not b:
            continue
        ratio = statistics.mean(b) / statistics.mean(a)
        fmt = " / ".join
        lines.append(
            f"| {label} | {fmt(f'{x:.3f}' for x in a)} | {fmt(f'{x:.3f}' for x in b)} | {ratio:.2f} "
            f"| {usd[(label, 'a')]:,} → {usd[(label, 'b')]:,} |"
        )
    lines.append(f"\nload average during the runs: {min(loads):.1f}–{max(loads):.1f}")
    return "\n".join(lines)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--a", help="PYTHONPATH of build A (before)")
    p.add_argument("--b", help="PYTHONPATH of build B (after)")
    p.add_argument("--out", type=Path, required=True, help="folder for the per-run JSON")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--sizes", nargs="+", default=["columbia", "gbr", "vegas", "Spa x1.64"])
    p.add_argument("--summarise", action="store_true", help="only print the table from --out")
    args = p.parse_args()
    if not args.summarise:
        if not (args.a and args.b):
            p.error("--a and --b are required unless --summarise")
        args.out.mkdir(parents=True, exist_ok=True)
        for i in range(1, args.rounds + 1):
            for side, path in (("a", args.a), ("b", args.b)):
                run(side, path, args.out, i, args.sizes, args.repeat)
    print(summarise(args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
