"""The track library's jobs: build the catalog (``tracks/catalog.json``) of real circuits
at 1:10, recorded third-party maps (referenced, never copied) and requirement-generated
tracks; verify it (drive laps, build USD); sweep the generator into a library; draw its
contact sheet. They sit a floor above ``envs``; reading the catalog is a floor below, in
:mod:`roboracer_arena.catalog`, whose public names this package re-exports.

* :func:`resolve` -- catalog id or selection (``"circuits"``, ``"recorded"``,
  ``"generated"``, ``"all"``) to map YAML paths.
* :func:`resolve_tracks` -- the same to simulator tracks named by id (the env's ``track=``).
* :func:`load_catalog`, :class:`Catalog` -- the catalog itself.
* ``roboracer-arena tracks list|show|build|verify|sheet|catalog`` -- the CLI.
"""

from ..catalog import KINDS, SELECTIONS, Catalog, default_tracks_dir, load_catalog, resolve, resolve_tracks

__all__ = ["KINDS", "SELECTIONS", "Catalog", "default_tracks_dir", "load_catalog", "resolve", "resolve_tracks"]
