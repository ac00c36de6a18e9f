"""The track library's jobs: build the catalog (``tracks/catalog.json``) of real circuits
at 1:10, recorded third-party maps (referenced, never copied) and requirement-generated
tracks; verify it (drive laps, build USD); sweep the generator into a library; draw its
contact sheet (``roboracer-arena tracks list|show|build|verify|sheet|catalog``).

They sit a floor above ``envs``. Reading the catalog (``load_catalog``, ``resolve``,
``resolve_tracks``) is a floor below, in :mod:`roboracer_arena.catalog`.
"""
