"""The track library: one catalog (``tracks/catalog.json``) of real circuits at 1:10,
recorded third-party maps (referenced, never copied) and requirement-generated tracks.

* :func:`resolve` -- catalog id or selection (``"circuits"``, ``"recorded"``,
  ``"generated"``, ``"all"``) to map YAML paths.
* :func:`resolve_tracks` -- the same to simulator tracks named by id (the env's ``track=``).
* :func:`load_catalog`, :class:`Catalog` -- the catalog itself.
* ``roboracer-arena tracks list|show|build|verify|sheet|catalog`` -- the CLI.
"""

from .catalog import KINDS, SELECTIONS, Catalog, default_tracks_dir, load_catalog, resolve
from .tracks import resolve_tracks  # the gymnasium env's ``track=`` hook (envs.tracks.resolve_catalog)

__all__ = ["KINDS", "SELECTIONS", "Catalog", "default_tracks_dir", "load_catalog", "resolve", "resolve_tracks"]
