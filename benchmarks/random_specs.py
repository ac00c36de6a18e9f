"""Write N random TrackSpecs (seeded) as JSONL, for robustness runs of the constructors:

    python -m benchmarks.random_specs 300 --seed 1 > /tmp/random-300.jsonl
    python -m benchmarks constructors --specs /tmp/random-300.jsonl --seeds 0 --constructors lattice

Ranges: lap 25–90 m, width 1.2/1.5/1.8/2.0 m, hall 12–26 × 10–20 m, either direction,
0–4 hairpins, 0–2 chicanes, 0–2 sweepers. Some specs fail the screen on purpose.
"""

import argparse
import json
import random


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("n", type=int)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    for i in range(args.n):
        spec = {
            "name": f"random-{args.seed}-{i:04d}",
            "lap_length_m": round(rng.uniform(25, 90), 2),
            "corridor_width_m": rng.choice([1.2, 1.5, 1.8, 2.0]),
            "hall_x_m": round(rng.uniform(12, 26), 2),
            "hall_y_m": round(rng.uniform(10, 20), 2),
            "direction": rng.choice(["clockwise", "counterclockwise"]),
            "hairpins": rng.randint(0, 4),
            "chicanes": rng.randint(0, 2),
            "sweepers": rng.randint(0, 2),
        }
        print(json.dumps(spec))


if __name__ == "__main__":
    main()
