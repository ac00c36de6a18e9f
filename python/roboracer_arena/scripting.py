"""What a script built on the package (``examples/*.py``) needs to behave like the CLI:
the ``--sources`` flag and the same one-line errors and exit codes.

    p = argparse.ArgumentParser(); add_sources_argument(p); args = p.parse_args()
    apply_sources(args.sources)            # --sources, else $ROBORACER_ARENA_SOURCES, else beside a checkout
    sys.exit(run_script("train_es.py", lambda: main(args)))
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable
from pathlib import Path

from .cli import EXIT_BAD_INPUT, EXIT_INTERNAL
from .errors import ArenaError, InternalError
from .foundation.paths import SOURCES_ENV, default_sources_dir, sources_dir


def add_sources_argument(parser: argparse.ArgumentParser) -> None:
    """Add ``--sources DIR`` (the track-sources folder recorded maps are read from)."""
    parser.add_argument(
        "--sources",
        type=Path,
        default=None,
        metavar="DIR",
        help=f"track-sources folder for recorded maps (default: ${SOURCES_ENV}, or ../shared/track-sources "
        "beside a source checkout)",
    )


def apply_sources(explicit: str | os.PathLike[str] | None) -> None:
    """Make ``explicit`` (checked to be a folder) the track-sources folder of this process,
    as the CLI's ``--sources`` does. Without it, the default (``$ROBORACER_ARENA_SOURCES``
    or the checkout's) is checked only when a recorded map is needed."""
    if explicit is not None:
        os.environ[SOURCES_ENV] = str(sources_dir(explicit).resolve())
    elif default_sources_dir() is not None:  # set: the same folder for worker processes
        os.environ.setdefault(SOURCES_ENV, str(default_sources_dir()))


def run_script(prog: str, body: Callable[[], int | None]) -> int:
    """Run ``body`` and map the package's errors to one line on stderr and the CLI's exit
    codes (2 bad input, 1 internal error, 130 interrupted)."""
    try:
        return int(body() or 0)
    except InternalError as e:
        print(f"{prog}: {e}", file=sys.stderr)
        return EXIT_INTERNAL
    except ArenaError as e:
        print(f"{prog}: error: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
