"""Where the package finds its data: the one place that resolves these directories.

* :func:`tracks_dir` -- the track catalog and the maps the project derives (circuits at
  1:10, generated tracks). Shipped inside the package (``roboracer_arena/tracks``), so an
  installed wheel has them; ``$ROBORACER_ARENA_TRACKS`` points elsewhere.
* :func:`sources_dir` -- the public third-party track data the recorded maps are read
  from (never copied into the package): ``--sources`` when a command has it, else
  ``$ROBORACER_ARENA_SOURCES``, else, when running from a source checkout,
  ``../shared/track-sources`` beside the checkout. An installed wheel has no default:
  commands that need the sources say to set ``ROBORACER_ARENA_SOURCES``.
"""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import InvalidArgumentError, MapIOError

SOURCES_ENV = "ROBORACER_ARENA_SOURCES"
TRACKS_ENV = "ROBORACER_ARENA_TRACKS"
#: The ``roboracer_arena`` package folder (this module sits one below it).
PACKAGE_DIR = Path(__file__).resolve().parents[1]


def checkout_dir() -> Path | None:
    """The source checkout this package is imported from (editable install), else None."""
    root = PACKAGE_DIR.parents[1]
    if PACKAGE_DIR.parent.name == "python" and (root / "pyproject.toml").is_file() and (root / "crates").is_dir():
        return root
    return None


def tracks_dir() -> Path:
    """``$ROBORACER_ARENA_TRACKS``, else the catalog shipped in the package."""
    env = os.environ.get(TRACKS_ENV)
    return Path(env) if env else PACKAGE_DIR / "tracks"


def writable_tracks_dir(explicit: str | os.PathLike[str] | None, flag: str) -> Path:
    """Where a command that (re)builds the catalog writes: ``explicit`` (its ``flag``),
    else, in a source checkout, :func:`tracks_dir`. An installed package is never written
    into: without ``flag`` it raises :class:`InvalidArgumentError` asking for one."""
    if explicit is not None:
        return Path(explicit)
    if os.environ.get(TRACKS_ENV) or checkout_dir() is not None:
        return tracks_dir()
    raise InvalidArgumentError(
        f"{flag} DIR is required: the installed track catalog is package data and is not "
        f"written into (it would change the installed package)"
    )


def default_sources_dir() -> Path | None:
    """``$ROBORACER_ARENA_SOURCES``, else ``../shared/track-sources`` beside a source
    checkout, else None (an installed wheel outside the checkout)."""
    env = os.environ.get(SOURCES_ENV)
    if env:
        return Path(env)
    root = checkout_dir()
    return (root.parent / "shared" / "track-sources").resolve() if root is not None else None


def sources_dir(explicit: str | os.PathLike[str] | None = None, need: str = "this command") -> Path:
    """The track-sources directory: ``explicit`` (a ``--sources`` flag), else
    :func:`default_sources_dir`. Raises :class:`MapIOError` naming the setting when there
    is none or it does not exist; ``need`` says what wanted it."""
    if explicit is not None:
        d, how = Path(explicit), "--sources"
    else:
        found = default_sources_dir()
        if found is None:
            raise MapIOError(
                f"{need} needs the public track data (the track-sources folder, see its SOURCES.md): "
                f"set {SOURCES_ENV} to that folder"
            )
        d, how = found, (f"${SOURCES_ENV}" if os.environ.get(SOURCES_ENV) else "the default beside the checkout")
    if not d.is_dir():
        raise MapIOError(f"{d}: track-sources folder not found ({how}); set {SOURCES_ENV} to the track-sources folder")
    return d


__all__ = [
    "SOURCES_ENV",
    "TRACKS_ENV",
    "checkout_dir",
    "default_sources_dir",
    "sources_dir",
    "tracks_dir",
    "writable_tracks_dir",
]
