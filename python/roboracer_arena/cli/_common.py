"""Helpers shared by the subcommands."""

from __future__ import annotations

import json
import sys
from typing import Any

from ..errors import InvalidArgumentError
from ..foundation.fileio import check_output


def add_json_flag(parser) -> None:
    parser.add_argument("--json", action="store_true", help="print a machine-readable JSON summary on stdout")


def print_json(obj: Any) -> None:
    """``obj`` (JSON types, or a typed report with ``to_json_dict``) as indented JSON on stdout."""
    if hasattr(obj, "to_json_dict"):
        obj = obj.to_json_dict()
    json.dump(obj, sys.stdout, indent=2, default=str)
    sys.stdout.write("\n")


#: Plausible range of every numeric flag, by argparse ``dest`` (inclusive; a flag whose
#: dest is not listed must still be finite). Checked once in ``main`` for every command.
FLAG_RANGES: dict[str, tuple[float, float]] = {
    "laps": (1, 1000),
    "fps": (0.1, 240),
    "max_speed": (0.01, 100),
    "max_time": (0.01, 1e6),
    "seed": (0, 2**64 - 1),
    "seeds": (0, 2**64 - 1),
    "timeout": (0.1, 86400),
    "max_px": (16, 16384),
    "resolution": (0.001, 1.0),
    "jobs": (1, 1024),
    "cars": (1, 64),
    "domain_id": (0, 232),
    "duration": (0.001, 1e7),
    "sim_time": (0.001, 1e7),
    "limit": (1, 1_000_000),
    "columns": (1, 100),
    "count": (1, 100_000),
    "close_gaps": (0.01, 20.0),
}


def check_numeric_flags(args: Any) -> None:
    """Refuse a NaN, an infinity or an out-of-range value in any numeric flag with an
    :class:`InvalidArgumentError` naming the flag and its range (the CLI exits 2)."""
    import math

    for dest, value in vars(args).items():
        values = value if isinstance(value, (list, tuple)) else [value]
        for v in values:
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                continue
            flag = "--" + dest.replace("_", "-")
            lo, hi = FLAG_RANGES.get(dest, (-math.inf, math.inf))
            if not (math.isfinite(v) and lo <= v <= hi):
                rng = f" in [{lo:g}, {hi:g}]" if dest in FLAG_RANGES else ""
                if dest in ("seed", "seeds"):
                    rng = " in [0, 2**64 - 1]"
                raise InvalidArgumentError(f"{flag} must be a finite number{rng}, got {v}")


#: Flags that name a file the command writes, by argparse ``dest``. ``out`` is a file
#: unless the command lists it in its ``output_dirs`` default (``set_defaults``).
OUTPUT_FILE_DESTS = ("out", "json", "gif", "mcap", "record", "markdown")
#: Flags that name a directory the command writes into.
OUTPUT_DIR_DESTS = ("maps",)


def check_outputs(args: Any) -> None:
    """The one output guard of the CLI, run in ``main`` before any command starts: every
    output flag is checked with :func:`~roboracer_arena.foundation.fileio.check_output` against every
    other path argument (and the files those name, e.g. a map YAML's image), so an output
    that would overwrite an input, or that cannot be written (a directory, a file as its
    parent, an unwritable place), fails at once with exit 2 and nothing written."""
    from pathlib import Path

    dirs = set(getattr(args, "output_dirs", ())) | set(OUTPUT_DIR_DESTS)
    outs = {d: v for d, v in vars(args).items() if isinstance(v, Path) and (d in OUTPUT_FILE_DESTS or d in dirs)}
    inputs: list[Path] = []
    for d, v in vars(args).items():
        for item in v if isinstance(v, (list, tuple)) else [v]:
            if d not in outs and isinstance(item, (str, Path)) and item and _is_file(item):
                inputs.append(Path(item))
    for d, path in outs.items():
        check_output(path, inputs, directory=d in dirs)


def _is_file(item: Any) -> bool:
    """Whether a text argument names an existing file (a request text is not a path: a
    name too long for the file system is not a file)."""
    from pathlib import Path

    try:
        return Path(item).is_file()
    except (OSError, ValueError):
        return False


def raise_interrupt_on_sigterm() -> None:
    """Make SIGTERM end a command the way Ctrl-C does (``KeyboardInterrupt``), so every
    job finishes or removes its outputs and cleans its temporary files on both signals."""
    import signal
    import threading

    def on_term(signum: int, frame: Any) -> None:
        raise KeyboardInterrupt(f"signal {signum}")

    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, on_term)
