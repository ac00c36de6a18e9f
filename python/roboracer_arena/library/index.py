"""Building ``tracks/catalog.json`` from the circuit reports (``tracks/circuits``), the
generated sweep (``tracks/generated``) and an assessment of every recorded map in the
sources directory."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from .._core import __version__
from ..catalog.catalog_file import SCHEMA, Catalog, count_kinds, provenance, sha256_file
from ..catalog.directions import annotate_directions
from ..catalog.entry import CatalogMeta, LeftOut, Raster, Source, TrackEntry
from ..circuits.report import CircuitReport
from ..errors import MapFormatError
from ..foundation.fileio import StagedFile, atomic_write_text, file_lock, read_json
from ..foundation.worker_pool import Progress
from ..maps.occupancy import load_map
from .generated import generate_into, staged_generated
from .open_maps import open_maps
from .recorded import assess_all, recorded_entry
from .spec_sweep_report import GeneratedSweepSummary

PROJECT = {"repository": "roboracer-arena (this project)", "licence": "MIT"}


def _circuit_entries(tracks: Path, sources: Path) -> list[TrackEntry]:
    out = []
    for f in sorted((tracks / "circuits").glob("*/circuit.json")):
        r = CircuitReport.model_validate_json(f.read_bytes())
        folder = r.source_file.split("/")[0]
        prov = provenance(sources, folder)
        notes = [f"width: {r.width_note}"]
        if r.grade_separated:
            notes.append(
                "grade-separated crossing: the centreline crosses itself (a bridge); the planar map "
                "overlaps there and the raster length check does not apply"
            )
        if r.narrowed_fraction > 0:
            notes.append(
                f"narrowed where sections would merge: {100 * r.narrowed_fraction:.1f} % of the lap "
                f"(never below 60 % of nominal)"
            )
        if r.meta.get("differs_from"):
            notes.append(f"layout differs from TUM '{r.meta['differs_from']['tum']}'")
        out.append(
            TrackEntry(
                id=r.id,
                name=r.name,
                kind="circuit",
                source=Source(
                    **prov,
                    path=r.source_file,
                    derived="scaled 1:10, periodic cubic spline, rasterised by roboracer-arena",
                ),
                scale=r.scale,
                resolution_m=r.resolution_m,
                lap_length_m=r.lap_length_m,
                width_mean_m=r.width_mean_m,
                width_min_m=r.width_min_m,
                min_radius_m=r.min_radius_m,
                raster=Raster(width_px=r.raster.width_px, height_px=r.raster.height_px),
                sha256=r.map_sha256,
                map=f"circuits/{r.map_yaml}",
                centreline=f"circuits/{r.id}/centreline.csv",
                grade_separated=r.grade_separated,
                narrowed_fraction=r.narrowed_fraction,
                length_error=r.length_error,
                notes=notes,
            )
        )
    return out


def _generated_entries(tracks: Path, folder: Path | None = None) -> list[TrackEntry]:
    """Entries of the generated tracks in ``folder`` (default ``tracks/generated``; a stage
    of it before the swap), named as ``generated/<id>/...`` relative to ``tracks``."""
    out = []
    for spec_f in sorted((folder or tracks / "generated").glob("*/spec.json")):
        d = spec_f.parent
        try:  # the one JSON reader (bounded); a file of another shape names itself
            out.append(_generated_entry(d, read_json(spec_f, "generated spec"), read_json(d / "report.json", "report")))
        except (KeyError, TypeError, AttributeError, ValueError, ValidationError) as e:
            raise MapFormatError(
                f"{d}: spec.json / report.json do not describe a generated track ({type(e).__name__}: {str(e)[:120]})"
            ) from None
    return out


def _generated_entry(d: Path, spec: Any, rep: Any) -> TrackEntry:
    """One generated track's entry from its folder ``d`` and its spec and report."""
    meas = rep["measurements"]  # the validator's numbers (its checks' text is for people)
    m = load_map(d / "map.yaml")
    h, w = m.shape
    feats = f"{spec['hairpins']} hairpin(s), {spec['chicanes']} chicane(s), {spec['sweepers']} sweeper(s)"
    return TrackEntry(
        id=d.name,
        name=spec["name"],
        kind="generated",
        source=Source(
            **PROJECT,
            path=f"generated/{d.name}/spec.json",
            derived=f"generate_track(spec, seed={rep['seed']}) with the {rep['constructor']} constructor",
        ),
        # Rounded as the validator reports them (cm for lengths, mm for widths).
        scale=1.0,
        resolution_m=m.resolution,
        lap_length_m=round(meas["lap_length_m"], 2),
        width_mean_m=round(meas["width_mean_m"], 3),
        width_min_m=round(meas["width_min_m"], 3),
        min_radius_m=round(meas["min_radius_m"], 2),
        raster=Raster(width_px=w, height_px=h),
        sha256=sha256_file(m.image_path),
        map=f"generated/{d.name}/map.yaml",
        centreline=f"generated/{d.name}/centreline.csv",
        spec=f"generated/{d.name}/spec.json",
        seed=rep["seed"],
        notes=[
            f"{spec['lap_length_m']:g} m lap, {spec['corridor_width_m']:g} m wide, {spec['direction']}, {feats}, "
            f"in a {spec['hall_x_m']:g} x {spec['hall_y_m']:g} m hall"
        ],
    )


def _recorded_entries(sources: Path, jobs: int, progress: Progress | None) -> tuple[list[TrackEntry], list[LeftOut]]:
    entries, left_out = [], []
    for r in assess_all(sources, jobs=jobs, progress=progress):
        if not r.usable:
            left_out.append(LeftOut(id=r.id, source_path=r.source_path, reason=r.reason or ""))
            continue
        entries.append(recorded_entry(sources, r))
    return entries, left_out


def build_catalog(sources: Path, tracks: Path, jobs: int = 1, progress: Progress | None = None) -> Catalog:
    """Assemble every entry and write ``tracks/catalog.json`` atomically."""
    cat = assemble_catalog(sources, tracks, jobs, progress)
    with file_lock(tracks / "catalog.json"):  # a verify --update-catalog meanwhile waits, then re-reads
        atomic_write_text(tracks / "catalog.json", cat.to_json())
    return cat


def build_catalog_generating(
    sources: Path,
    tracks: Path,
    count: int = 60,
    jobs: int = 1,
    progress: Progress | None = None,
    generate_progress: Progress | None = None,
    max_requests: int | None = None,
) -> tuple[GeneratedSweepSummary, Catalog]:
    """``tracks catalog --generate``: rerun the generated sweep (:mod:`.generated`) into a
    stage of ``tracks/generated`` (its first ``max_requests`` requests, default all), assemble the catalog from that stage, and swap the
    folder and ``tracks/catalog.json`` in together, signals held. An interrupt (SIGINT,
    SIGTERM) or an error at any moment leaves both as they were, and no stage behind."""
    out = StagedFile(tracks / "catalog.json")
    # the catalog's lock throughout: a verify --update-catalog meanwhile waits, then re-reads
    try:
        with file_lock(tracks / "catalog.json"), staged_generated(tracks / "generated", also=out.commit) as stage:
            summary = generate_into(stage, count, jobs, generate_progress, max_requests=max_requests)
            cat = assemble_catalog(sources, tracks, jobs, progress, generated=stage)
            out.tmp.write_text(cat.to_json(), encoding="utf-8")
    finally:
        out.discard()  # (a no-op once committed)
    return summary, cat


def assemble_catalog(
    sources: Path, tracks: Path, jobs: int = 1, progress: Progress | None = None, generated: Path | None = None
) -> Catalog:
    """Every entry of ``tracks/catalog.json`` (generated tracks read from ``generated``,
    default ``tracks/generated``), nothing written."""
    t0 = time.perf_counter()
    circuits = _circuit_entries(tracks, sources)
    generated_entries = _generated_entries(tracks, generated)
    recorded, left_out = _recorded_entries(sources, jobs, progress)
    entries = circuits + recorded + generated_entries
    ids = [e.id for e in entries]
    dup = {i for i in ids if ids.count(i) > 1}
    if dup:
        raise RuntimeError(f"duplicate catalog ids: {sorted(dup)}")
    meta = CatalogMeta(
        catalog_schema=SCHEMA,
        built_with=f"roboracer-arena {__version__}",
        sources_note="recorded maps: 'map' is relative to the sources directory (--sources / "
        "$ROBORACER_ARENA_SOURCES, default ../shared/track-sources); circuits and generated: "
        "relative to this file's directory",
        counts=count_kinds(entries),
        seconds=round(time.perf_counter() - t0, 2),
    )
    cat = Catalog(entries=entries, left_out=left_out, meta=meta, path=tracks / "catalog.json")
    cat.open_maps = open_maps(sources, left_out, jobs)
    annotate_directions(cat, sources, generated)
    return cat
