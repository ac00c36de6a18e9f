"""What every benchmark's CLI shares: its subcommand (help, the module doc as description,
a ``--json FILE`` flag) and writing its results to that file."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from ..fileio import atomic_write_text


def add_bench_parser(kinds: Any, name: str, help: str, doc: str | None) -> argparse.ArgumentParser:
    """The ``bench NAME`` subcommand with ``doc`` as its description (layout kept) and ``--json FILE``."""
    p: argparse.ArgumentParser = kinds.add_parser(
        name, help=help, description=doc, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    p.add_argument("--json", metavar="FILE", type=Path, help="write the results to FILE as JSON")
    return p


def write_json(path: Path | None, result: Any) -> None:
    """Write ``result`` to ``path`` as indented JSON (atomically) and say so; nothing without a path."""
    if path:
        atomic_write_text(path, json.dumps(result, indent=2, default=str) + "\n")
        print(f"wrote {path}")
