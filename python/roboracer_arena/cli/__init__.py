"""``roboracer-arena`` command line. One module per subcommand in this package; each
exposes ``register(subparsers)`` which adds its parser and sets ``func``.

Exit codes: 0 success, 2 bad input (any :class:`~roboracer_arena.errors.ArenaError`),
3 request rejected by the screen, 4 generation failure, 5 the car did not finish
(``drive``: a collision, or fewer laps than asked in the time allowed), 6 the stage does
not hold in PhysX (``physx-check``), 1 unexpected internal error.
"""

from __future__ import annotations

import argparse
import signal
import sys
import threading
from collections.abc import Sequence
from importlib import import_module

from .._core import __version__
from ..errors import ArenaError, InternalError
from ._common import check_numeric_flags, check_outputs, raise_interrupt_on_sigterm

# Subcommand modules, in the order `--help` lists them.
COMMANDS: list[str] = [
    "bench",
    "build",
    "circuits",
    "drive",
    "generate",
    "parse",
    "physx_check",
    "preview",
    "raceline",
    "ros2",
    "tracks",
    "train",
    "validate",
]

EXIT_OK, EXIT_INTERNAL, EXIT_BAD_INPUT, EXIT_REJECTED, EXIT_GENERATION_FAILURE = 0, 1, 2, 3, 4
EXIT_LAP_FAILED = 5


def make_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="roboracer-arena",
        description=(
            "Any ROS occupancy map to a physics-ready 3D environment, requirement-generated "
            "tracks, and fast parallel RoboRacer simulation."
        ),
        epilog="Run 'roboracer-arena COMMAND --help' for the options of a command.",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMANDS:
        import_module(f"{__name__}.{name}").register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = make_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return EXIT_BAD_INPUT
    previous = signal.getsignal(signal.SIGTERM)
    try:
        raise_interrupt_on_sigterm()
        check_numeric_flags(args)
        check_outputs(args)
        return int(args.func(args) or 0)
    except InternalError as e:  # a caught core panic: a bug, not bad input
        print(f"roboracer-arena {args.command}: {e}", file=sys.stderr)
        return EXIT_INTERNAL
    except ArenaError as e:
        print(f"roboracer-arena {args.command}: error: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # e.g. `roboracer-arena ... --json | head`
        sys.stderr.close()
        return EXIT_OK
    finally:
        if threading.current_thread() is threading.main_thread() and previous is not None:
            signal.signal(signal.SIGTERM, previous)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
