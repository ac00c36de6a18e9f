"""Re-measure every map a sweep wrote (``bench constructors --sweep --maps DIR``) with
the independent measurement, and print how many are independently valid.

Usage: python tests/generate/remeasure_dir.py DIR"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from independent_measure import problems

from roboracer_arena.spec import TrackSpec


def main(root: Path) -> int:
    folders = sorted(p for p in root.iterdir() if (p / "map.yaml").is_file())
    bad = 0
    for f in folders:
        found = problems(TrackSpec.from_file(f / "spec.json"), f / "map.yaml")
        if found:
            bad += 1
            print(f"{f.name}: {'; '.join(found)}")
    print(f"{len(folders) - bad}/{len(folders)} written maps independently valid")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1])))
