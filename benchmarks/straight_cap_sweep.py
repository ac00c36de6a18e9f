"""How often a straight cap builds: every sweep spec the generator accepts, asked again
with ``max_straight_m`` at a share of the longest straight it got uncapped (issue 28).

For each accepted spec of the shipped 360-spec sweep (its own seed, index mod 3) whose
uncapped longest straight is at least 2 m, the same spec with a cap of ``SHARE`` × that
straight is generated with the same seed (default candidate cap and budget, no
suggestion search). An acceptance passed the validator's ``max_straight`` check, so its
longest straight respects the cap; the script re-checks that from the measurements.

Usage: ``python -m benchmarks.straight_cap_sweep [SHARE] [--every N]`` (default 0.8, every
spec). (Not in the wheel.)
"""

from __future__ import annotations

import sys
import time
from collections import Counter

from benchmarks.constructor_sweep import fill_band, load_sweep_file
from roboracer_arena.generate import Acceptance, derived_geometry, generate_track


def main(argv: list[str]) -> int:
    share = float(argv[0]) if argv and not argv[0].startswith("--") else 0.8
    every = int(argv[argv.index("--every") + 1]) if "--every" in argv else 1
    tried, built, by_band = 0, 0, Counter()
    tot_band: Counter[str] = Counter()
    t0 = time.perf_counter()
    for i, spec in enumerate(load_sweep_file()):
        if i % every:
            continue
        base = generate_track(spec, seed=i % 3, suggest_timeout=None)
        if not isinstance(base, Acceptance) or base.report.measurements is None:
            continue
        straight = base.report.measurements.longest_straight_m
        if straight < 2.0:
            continue
        cap = round(share * straight, 2)
        out = generate_track(spec.model_copy(update={"max_straight_m": cap}), seed=i % 3, suggest_timeout=None)
        band = fill_band(spec.lap_length_m / derived_geometry(spec).l_max)
        tried += 1
        tot_band[band] += 1
        if isinstance(out, Acceptance):
            assert out.report.measurements is not None and out.report.measurements.longest_straight_m <= cap
            built += 1
            by_band[band] += 1
    print(
        f"cap = {share:g} × uncapped longest straight: {built}/{tried} accepted "
        f"({100 * built / max(tried, 1):.1f} %), {time.perf_counter() - t0:.0f} s"
    )
    print("  by fill: " + "  ".join(f"{b}: {by_band[b]}/{tot_band[b]}" for b in sorted(tot_band)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
