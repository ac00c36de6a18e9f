"""Build the circuit library: scale 1:10, smooth and resample, narrow where sections
would merge, rasterise with variable width (Eq. 3), measure the raster, write the ROS map,
the scaled centreline CSV and a per-circuit JSON report (all atomically)."""

from __future__ import annotations

import ctypes
import ctypes.util
import hashlib
import io
import json
import os
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from .. import _core
from ..errors import CorridorError
from ..foundation.fileio import atomic_update_dir, atomic_write_text, check_output
from ..foundation.worker_pool import Progress, pool_map
from ..maps.direction import direction_of
from ..maps.occupancy import OccupancyMap
from .geometry import MIN_RADIUS_SPAN_M, reduce_widths, smooth_resample
from .report import CircuitBuildSummary, CircuitFailure, CircuitRaster, CircuitReport, RasterMeasurement
from .sources import CircuitInput, circuit_inputs


@dataclass(frozen=True)
class CircuitConfig:
    """How circuits are turned into maps. Lengths in metres at vehicle scale."""

    scale: float = 0.1  # uniform 1:10
    resolution: float = 0.05  # Δ (m per cell)
    wall_thickness: float = 0.15  # t_w
    margin: float = 0.5  # unknown border around the outer wall
    spacing: float = 0.1  # resampled vertex spacing along the centreline
    tolerance_tum: float = 0.01  # spline RMS tolerance, TUM data (already smoothed, 5 m spacing)
    tolerance_geojson: float = 0.05  # spline RMS tolerance, GeoJSON (hand-traced, ~30 m spacing)
    csv_spacing: float = 0.5  # vertex spacing of the written centreline CSV (keeps the repo small)


def _csv(xy: np.ndarray, widths: np.ndarray) -> str:
    buf = io.StringIO()
    buf.write("# x_m, y_m, w_tr_right_m, w_tr_left_m\n")
    for (x, y), w in zip(xy, widths):
        buf.write(f"{x:.3f},{y:.3f},{w / 2:.3f},{w / 2:.3f}\n")
    return buf.getvalue()


def build_circuit(c: CircuitInput, outdir: str | Path, cfg: CircuitConfig = CircuitConfig()) -> CircuitReport:
    """Build one circuit into ``outdir/<id>/`` and return its report (also written as
    ``circuit.json``). Raises :class:`CorridorError` if the raster has no closed corridor."""
    t0 = time.perf_counter()
    raw = c.xy * cfg.scale
    tol = cfg.tolerance_tum if c.source == "tumftm" else cfg.tolerance_geojson
    xy, w_nom = smooth_resample(raw, c.widths * cfg.scale, cfg.spacing, tol)
    # The source lists its points in the racing direction from the start line: keep that
    # order (and the first point) all the way to centreline.csv, which the env drives.
    xy = xy - xy.mean(axis=0)
    crossing_segments, crossing_points = _core.self_intersections(xy)
    nar = reduce_widths(xy, w_nom, cfg.wall_thickness, cfg.spacing, crossing_segments)
    data, origin = _core.rasterise_centreline(xy, nar.widths, cfg.resolution, cfg.wall_thickness, cfg.margin)
    t_raster = time.perf_counter() - t0
    ref_len = _core.polyline_length(xy)
    raw_len = _core.polyline_length(raw)
    grade_separated = len(crossing_points) > 0
    try:
        mm = _core.measure_map(data, cfg.resolution, origin)
        measured = RasterMeasurement(
            corridor_components=mm.corridor_components,
            infields=mm.infields,
            raster_centreline_m=round(mm.centreline_length_m, 4),
            mean_width_m=round(mm.mean_width_m, 4),
            min_width_m=round(float(np.percentile(mm.widths, 0.5)), 4),
        )
    except CorridorError as e:
        measured = RasterMeasurement(corridor_components=0, infields=0, error=str(e))
    err = None
    if measured.raster_centreline_m is not None and not grade_separated:
        err = abs(measured.raster_centreline_m - ref_len) / ref_len
    one_corridor = measured.corridor_components == 1 and measured.infields >= 1
    if not grade_separated:
        one_corridor = one_corridor and measured.infields == 1
    # Minimum radius of the smoothed centreline (three-point circumradius over ±0.5 m).
    min_radius = _core.min_radius(xy, MIN_RADIUS_SPAN_M)

    out = Path(outdir) / c.id
    out.mkdir(parents=True, exist_ok=True)
    yaml_path = OccupancyMap(data, cfg.resolution, origin).save(out / "map.yaml")
    png = (out / "map.png").read_bytes()
    every = max(1, int(round(cfg.csv_spacing / cfg.spacing)))
    atomic_write_text(out / "centreline.csv", _csv(xy[::every], nar.widths[::every]))
    h, wpx = data.shape
    ox, oy, oyaw = origin
    report = CircuitReport(
        id=c.id,
        name=c.name,
        source=c.source,
        source_file=f"{c.path.parent.parent.name}/{c.path.parent.name}/{c.path.name}",
        scale=cfg.scale,
        resolution_m=cfg.resolution,
        width_note=c.width_note,
        full_scale_length_m=round(c.length_m, 2),
        input_length_m=round(raw_len, 4),
        lap_length_m=round(ref_len, 4),
        nominal_width_mean_m=round(float(w_nom.mean()), 4),
        nominal_width_min_m=round(float(w_nom.min()), 4),
        width_mean_m=round(float(nar.widths.mean()), 4),
        width_min_m=round(float(nar.widths.min()), 4),
        min_radius_m=round(min_radius, 3),
        narrowed_fraction=round(nar.narrowed_fraction, 4),
        unresolved_fraction=round(nar.unresolved_fraction, 4),
        min_separation_m=round(nar.min_separation_m, 3) if np.isfinite(nar.min_separation_m) else None,
        direction=direction_of(xy),
        direction_source="point order of the source centreline",
        grade_separated=grade_separated,
        crossings=[(round(float(p[0]), 2), round(float(p[1]), 2)) for p in crossing_points],
        raster=CircuitRaster(width_px=wpx, height_px=h, origin=(round(ox, 4), round(oy, 4), round(oyaw, 4))),
        measured=measured,
        length_error=None if err is None else round(err, 6),
        one_corridor=bool(one_corridor),
        map_sha256=hashlib.sha256(png).hexdigest(),
        map_yaml=f"{c.id}/{yaml_path.name}",
        seconds=round(time.perf_counter() - t0, 3),
        seconds_raster=round(t_raster, 3),
        meta=c.meta,
    )
    atomic_write_text(out / "circuit.json", json.dumps(report.to_json_dict(), indent=2) + "\n")
    return report


def _keep_freed_memory() -> None:
    """Ask glibc malloc to keep freed blocks in the heap instead of returning each 10–40 MB
    field to the kernel, so the next map reuses the pages rather than faulting them in
    again (the build's system time drops about threefold). A no-op without glibc."""
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        mallopt = libc.mallopt
    except (OSError, AttributeError):
        return
    m_trim_threshold, m_top_pad, m_mmap_threshold = -1, -2, -3
    mallopt(m_mmap_threshold, 1 << 30)
    mallopt(m_trim_threshold, 1 << 30)
    mallopt(m_top_pad, 1 << 27)


def _work(args: tuple[CircuitInput, str, CircuitConfig]) -> CircuitReport | CircuitFailure:
    c, outdir, cfg = args
    try:
        return build_circuit(c, outdir, cfg)
    except Exception as e:  # reported per circuit, never kills the batch
        return CircuitFailure(id=c.id, name=c.name, source=c.source, error=f"{type(e).__name__}: {e}")


def build_all(
    sources: str | Path | None,
    outdir: str | Path,
    cfg: CircuitConfig = CircuitConfig(),
    jobs: int | None = None,
    only: list[str] | None = None,
    progress: Progress | None = None,
) -> CircuitBuildSummary:
    """Build every circuit (optionally ``only`` some ids) in ``jobs`` threads; write
    ``outdir/index.json`` and return the summary with per-circuit reports. ``outdir`` is
    staged and swapped in whole, keeping the folders of circuits not built."""
    t0 = time.perf_counter()
    check_output(outdir, directory=True)  # a file there is refused, never swapped away
    inputs, skipped = circuit_inputs(sources)
    if only:
        inputs = [c for c in inputs if c.id in set(only)]
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(inputs) or 1))
    # Biggest first keeps the pool busy to the end.
    inputs.sort(key=lambda c: -c.length_m)
    if jobs > 1:
        _keep_freed_memory()
    # The library is staged and swapped in whole (other circuits' folders kept): an
    # interrupt or an error at any moment leaves the previous one as it was.
    with atomic_update_dir(outdir, {c.id for c in inputs} | {"index.json"}) as stage:
        summary = _build_into(stage, inputs, skipped, cfg, jobs, progress, t0)
    return summary


def _build_into(
    stage: Path,
    inputs: list[CircuitInput],
    skipped: list[dict],
    cfg: CircuitConfig,
    jobs: int,
    progress: Progress | None,
    t0: float,
) -> CircuitBuildSummary:
    tasks = [(c, str(stage), cfg) for c in inputs]
    # Threads, not processes: the heavy steps (rasterise, measure, PNG) release the
    # GIL, and threads skip each worker's interpreter start-up and imports.
    results = pool_map(_work, tasks, jobs, progress, threads=True)
    results.sort(key=lambda r: r.id)
    built = [r for r in results if isinstance(r, CircuitReport)]
    errs = [r.length_error for r in built if r.length_error is not None]
    summary = CircuitBuildSummary(
        circuits=len(results),
        built=len(built),
        one_corridor=sum(r.one_corridor for r in built),
        grade_separated=[r.id for r in built if r.grade_separated],
        mean_length_error=float(np.mean(errs)) if errs else None,
        max_length_error=float(np.max(errs)) if errs else None,
        seconds=round(time.perf_counter() - t0, 3),
        jobs=jobs,
        config=asdict(cfg),
        skipped_as_covered=skipped,
        results=results,
    )
    index = summary.to_json_dict()
    for k in ("results", "seconds", "jobs"):
        del index[k]
    index["ids"] = [r.id for r in results]
    atomic_write_text(stage / "index.json", json.dumps(index, indent=2) + "\n")
    return summary
