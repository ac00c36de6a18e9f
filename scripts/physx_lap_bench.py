"""PhysX vs our simulator: one pure-pursuit lap on a recorded map (f1tenth-gym berlin), a
circuit (Monaco at 1:10) and a generated track, each built with ``build --car`` and driven
through ovphysx on the CPU (issue #23). Prints a Markdown table and writes the rows as JSON.

    nice -n 10 .venv/bin/python scripts/physx_lap_bench.py [--sources DIR] [--out rows.json]

Needs the ``physx`` extra. Lap time, mean and worst distance from the centreline, and
physics steps per second: PhysX's ``step_sync`` time alone (CPU, one thread) against our
env's whole step (rapier world, vehicle model and the 1,081-beam lidar).
"""

from __future__ import annotations

import argparse
import json
import tempfile
import warnings
from pathlib import Path


def _tracks(sources: Path, work: Path) -> dict[str, Path]:
    from roboracer_arena import TrackSpec, generate_track
    from roboracer_arena.cli import main
    from roboracer_arena.generate import write_outputs

    assert main(["circuits", "--sources", str(sources), "-o", str(work), "--only", "monaco", "--jobs", "1"]) == 0
    gen = write_outputs(generate_track(TrackSpec(lap_length_m=40.0), seed=3), work / "generated")
    return {
        "berlin (recorded, f1tenth-gym)": sources / "f1tenth-gym" / "maps" / "berlin.yaml",
        "monaco (circuit, 1:10)": work / "monaco" / "map.yaml",
        "generated (40 m, seed 3)": gen["map_yaml"],
    }


def main() -> None:
    from roboracer_arena import build_environment
    from roboracer_arena.foundation.paths import default_sources_dir
    from roboracer_arena.physx.check import track_of_stage
    from roboracer_arena.physx.drive import drive_native_lap, drive_physx_lap

    warnings.simplefilter("ignore")
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sources", type=Path, default=default_sources_dir())
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for name, map_yaml in _tracks(args.sources, work).items():
            stage = work / f"{len(rows)}.usdc"
            build_environment(map_yaml, stage, car=True)
            track = track_of_stage(stage)
            physx = drive_physx_lap(stage, track, max_seconds=240.0)
            ours = drive_native_lap(track, max_seconds=240.0)
            rows.append(
                {"track": name, "length_m": track.length, "physx": physx.to_json_dict(), "ours": ours.to_json_dict()}
            )
    print("| track | lap (m) | engine | lap time (s) | mean / max deviation (m) | physics steps/s |")
    print("|---|---:|---|---:|---:|---:|")
    for r in rows:
        for key in ("ours", "physx"):
            run = r[key]
            lap = f"{run['lap_time_s']:.2f}" if run["completed"] else "no lap"
            print(
                f"| {r['track']} | {r['length_m']:.1f} | {run['engine']} | {lap} | "
                f"{run['mean_deviation_m']:.3f} / {run['max_deviation_m']:.3f} | {run['steps_per_second']:,.0f} |"
            )
    if args.out:
        args.out.write_text(json.dumps(rows, indent=1) + "\n")


if __name__ == "__main__":
    main()
