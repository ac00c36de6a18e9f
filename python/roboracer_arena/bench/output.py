"""What every benchmark's CLI shares: its subcommand (help, the module doc as description,
a ``--json FILE`` flag), the base of its typed results, and writing them to that file."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from ..foundation.fileio import atomic_write_text
from ..foundation.frozen_model import FrozenModel


class BenchModel(FrozenModel):
    """A benchmark's result or row: a :class:`FrozenModel` whose JSON is what ``--json``
    writes."""


class Skipped(BenchModel):
    """``bench all``'s entry for a benchmark whose optional dependency is missing."""

    skipped: str


def add_bench_parser(kinds: Any, name: str, help: str, doc: str | None) -> argparse.ArgumentParser:
    """The ``bench NAME`` subcommand with ``doc`` as its description (layout kept) and ``--json FILE``."""
    p: argparse.ArgumentParser = kinds.add_parser(
        name, help=help, description=doc, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    p.add_argument("--json", metavar="FILE", type=Path, help="write the results to FILE as JSON")
    return p


def json_text(result: FrozenModel) -> str:
    """The text ``--json`` writes: the model's JSON, indented, with a final newline."""
    return json.dumps(result.to_json_dict(), indent=2) + "\n"


def write_json(path: Path | None, result: FrozenModel) -> None:
    """Write ``result`` to ``path`` as indented JSON (atomically) and say so; nothing without a path."""
    if path:
        atomic_write_text(path, json_text(result))
        print(f"wrote {path}")
