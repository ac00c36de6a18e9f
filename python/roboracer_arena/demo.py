"""``make demo``: the main job on embedded defaults (no server, no model download)."""

from __future__ import annotations

import argparse
from pathlib import Path


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m roboracer_arena.demo", description=__doc__)
    p.add_argument("--out", type=Path, default=Path("out/demo"), help="output folder")
    args = p.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    import roboracer_arena

    print(f"roboracer-arena {roboracer_arena.__version__}: skeleton only, no pipeline yet")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
