"""The track catalog (``tracks/catalog.json``), read: the floor below ``envs`` that names
tracks. The jobs that build, verify and sweep the catalog live a floor above, in
:mod:`roboracer_arena.library`.

* :func:`load_catalog`, :class:`Catalog` -- the catalog file and its entries.
* :func:`resolve` -- catalog id or selection (``"circuits"``, ``"recorded"``,
  ``"generated"``, ``"all"``) to map YAML paths.
* :func:`resolve_tracks` -- the same to simulator tracks named by id (the env's ``track=``).
"""

from .catalog_file import KINDS, SELECTIONS, Catalog, default_tracks_dir, load_catalog, resolve
from .entry_tracks import resolve_tracks

__all__ = ["KINDS", "SELECTIONS", "Catalog", "default_tracks_dir", "load_catalog", "resolve", "resolve_tracks"]
