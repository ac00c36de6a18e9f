"""``roboracer-arena tracks``: the track library catalog (tracks/catalog.json).

  list                      every track (filter with --kind)
  show ID                   one catalog entry in full
  build ID -o OUT.usdc      build a track's USD environment with the builder
  verify                    load, corridor ring, USD build and pure-pursuit lap per track
  sheet -o sheet.png        contact sheet: every track with name, lap length, extent and scale bar
  catalog                   rebuild tracks/catalog.json (--generate reruns the generated sweep)
  generate --sweep S -o DIR generate a library of N tracks from a sweep file (--ray: as Ray tasks)

A track id or a selection (circuits, recorded, generated, all) is what the gymnasium env
accepts as ``track=``. Recorded maps are read from --sources (default
$ROBORACER_ARENA_SOURCES or ../shared/track-sources)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ..builder import build_environment
from ..catalog import Catalog, default_tracks_dir, load_catalog
from ..catalog.catalog_file import update_catalog, writable_catalog
from ..catalog.entry import TrackEntry
from ..catalog.entry_text import entry_lines
from ..distributed.executor import make_executor
from ..errors import InvalidArgumentError
from ..foundation.paths import sources_dir, writable_tracks_dir
from ..foundation.worker_pool import Progress, tqdm_progress
from ..library.raceline_index import load_index, record_lines
from ..library.spec_sweep import load_sweep
from ..library.verify_report import CHECKS
from . import EXIT_BAD_INPUT, EXIT_GENERATION_FAILURE, EXIT_OK
from ._common import add_json_flag, print_json


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--catalog",
        type=Path,
        default=None,
        metavar="FILE",
        help="catalog JSON (default: the one shipped in the package)",
    )
    p.add_argument(
        "--sources", type=Path, default=None, metavar="DIR", help="track-sources directory for recorded maps"
    )
    add_json_flag(p)


def _subset(p: argparse.ArgumentParser, kinds: tuple[str, ...] = ("circuit", "recorded", "generated")) -> None:
    p.add_argument("--kind", choices=list(kinds), help="only tracks of this kind")
    p.add_argument("--limit", type=int, default=None, metavar="N", help="at most N tracks of each kind")
    p.add_argument("--ids", nargs="+", metavar="ID", help="only these ids")


def register(sub) -> None:
    p = sub.add_parser(
        "tracks",
        help="the track library: list, show, build, verify, sheet",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    t = p.add_subparsers(dest="tracks_cmd", metavar="ACTION", required=True)
    a = t.add_parser("list", help="list catalog tracks (--kind open: the recorded maps offered as open maps)")
    _common(a)
    _subset(a, ("circuit", "recorded", "generated", "open"))
    a.set_defaults(func=run_list)
    a = t.add_parser("show", help="show one catalog entry")
    a.add_argument("id", help="track id")
    _common(a)
    a.set_defaults(func=run_show)
    a = t.add_parser("build", help="build a track's USD environment")
    a.add_argument("id", help="track id")
    a.add_argument("-o", "--out", type=Path, required=True, metavar="OUT.usdc", help="output USD file")
    _common(a)
    a.set_defaults(func=run_build)
    _add_verify(t)
    _add_generate(t)
    a = t.add_parser("sheet", help="contact sheet of every track")
    a.add_argument(
        "-o", "--out", type=Path, required=True, metavar="sheet.png", help="picture to write (.png, .jpg or .jpeg)"
    )
    a.add_argument("--columns", type=int, default=12, help="thumbnails per row (default 12)")
    _common(a)
    _subset(a)
    a.set_defaults(func=run_sheet)
    _add_catalog(t)


def _add_verify(t: Any) -> None:
    """``tracks verify``: laps, USD, PhysX and raceline checks of catalog tracks."""
    a = t.add_parser("verify", help="verify tracks end to end; prints a table and a summary")
    _common(a)
    _subset(a)
    a.add_argument("--jobs", type=int, default=None, metavar="N", help="worker processes (default: all cores)")
    a.add_argument("--no-usd", action="store_true", help="skip the USD build check")
    a.add_argument(
        "--no-physx", action="store_true", help="skip the PhysX check (run when the 'physx' extra is installed)"
    )
    a.add_argument("--no-drive", action="store_true", help="skip the pure-pursuit lap")
    a.add_argument(
        "--raceline",
        action="store_true",
        help="also check each track's recorded raceline (tracks/racelines.json): planned again, same lap and CSV",
    )
    a.add_argument("--reverse", action="store_true", help="drive each lap against the track's racing direction")
    a.add_argument(
        "--update-catalog",
        action="store_true",
        help="record the results in the catalog (checks not run keep their recorded verdict); "
        "recorded maps that fail move to left_out",
    )
    _ray_flag(a)
    a.set_defaults(func=run_verify)


def _add_generate(t: Any) -> None:
    """``tracks generate``: a library of tracks from a spec sweep file."""
    a = t.add_parser(
        "generate",
        help="generate a library of tracks from a sweep file (locally or on Ray)",
        description=GENERATE_DOC,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    a.add_argument(
        "--sweep", type=Path, required=True, metavar="SWEEP.json", help="sweep file: spec ranges and base seed"
    )
    a.add_argument("--count", type=int, required=True, metavar="N", help="accepted tracks to keep")
    a.add_argument("-o", "--out", type=Path, required=True, metavar="DIR", help="output directory")
    a.add_argument(
        "--max-requests", type=int, default=None, metavar="M", help="give up after M requests (default 10 x N)"
    )
    a.add_argument("--jobs", type=int, default=None, metavar="N", help="local worker processes (default: all cores)")
    _ray_flag(a)
    add_json_flag(a)
    a.set_defaults(func=run_generate, output_dirs=("out",))


def _add_catalog(t: Any) -> None:
    """``tracks catalog``: rebuild (or rejudge) ``tracks/catalog.json``."""
    a = t.add_parser("catalog", help="rebuild tracks/catalog.json from tracks/ and the sources")
    _common(a)
    a.add_argument(
        "--tracks",
        type=Path,
        default=None,
        metavar="DIR",
        help="tracks directory read (circuits/, generated/) and written (catalog.json); "
        "default: the package's tracks/ in a source checkout, required for an installed package",
    )
    a.add_argument(
        "--generate",
        action="store_true",
        help="rerun the generated-track sweep first (staged: generated/ and catalog.json are swapped in together)",
    )
    a.add_argument("--count", type=int, default=60, help="generated tracks to keep (default 60)")
    a.add_argument(
        "--max-requests",
        type=int,
        default=None,
        metavar="M",
        help="with --generate: try only the sweep's first M requests (default all 96)",
    )
    a.add_argument("--jobs", type=int, default=None, metavar="N", help="worker processes (default: all cores)")
    a.add_argument(
        "--rejudge",
        action="store_true",
        help="instead of a rebuild: verify again the recorded maps 'verify' moved to left_out (current drivers: "
        "reference, cautious, clearance path), put back the ones that lap, measure the others' narrowest gap, and "
        "recompute the open maps; every other entry is kept as it is",
    )
    a.set_defaults(func=run_catalog)


GENERATE_DOC = """Generate --count accepted tracks from a sweep file into DIR/generated/<id>/, then write
DIR/sweep.json (every request up to the last kept one) and DIR/catalog.json (readable by
'tracks verify --catalog'; each map.yaml is a track= for the env). The result depends only on the sweep file
and --count, never on the number of workers.

Sweep file (JSON; example: examples/sweep.json; full text: roboracer_arena.library.spec_sweep):
  {"name": "hall-sweep", "base_seed": 0, "decimals": 1,
   "ranges": {"lap_length_m": [40, 120], "hairpins": [0, 2],
              "direction": {"choice": ["clockwise", "counterclockwise"]}},
   "fixed": {"corridor_width_m": 1.5}}
[lo, hi] draws a uniform float (an integer, inclusive, for integer fields). Request k
draws its fields from numpy default_rng([base_seed, k]) and generates with seed
SeedSequence([base_seed, k, 1]); track k is "<name>-<k:05d>"; the library is the
first --count acceptances in k order."""


def _ray_flag(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--ray",
        default=None,
        metavar="ADDRESS",
        help="run the work as Ray tasks: auto (running cluster / $RAY_ADDRESS), local (start one) or "
        "HOST:PORT; needs the [ray] extra",
    )


def _executor(args):
    if args.jobs is not None and args.jobs < 1:
        raise InvalidArgumentError(f"--jobs must be >= 1, got {args.jobs}")
    return make_executor(args.jobs, args.ray, arg="--ray")


def _progress(desc: str) -> Progress:
    return tqdm_progress(desc, "track")


def _load(args):
    return load_catalog(args.catalog)


def _select(cat: Catalog, args: argparse.Namespace) -> list[TrackEntry]:
    entries = cat.entries
    if getattr(args, "ids", None):
        entries = [cat.get(i) for i in args.ids]
    if getattr(args, "kind", None):
        entries = [e for e in entries if e.kind == args.kind]
    if getattr(args, "limit", None) is not None:  # spread over each kind: every n-th entry, at most limit
        by_kind: dict[str, list[int]] = {}
        for i, e in enumerate(entries):
            by_kind.setdefault(e.kind, []).append(i)
        keep = {i for idx in by_kind.values() for i in idx[:: max(1, len(idx) // args.limit)][: args.limit]}
        entries = [e for i, e in enumerate(entries) if i in keep]
    return entries


def run_list(args) -> int:
    cat = _load(args)
    if args.kind == "open":
        return _list_open(cat, args)
    entries = _select(cat, args)
    if args.json:
        keys = ("id", "name", "kind", "direction", "lap_length_m", "width_mean_m", "map")
        print_json([{k: getattr(e, k) for k in keys} for e in entries])
        return EXIT_OK
    print(f"{'id':<42}{'kind':<10}{'dir':<5}{'lap m':>9}{'w mean':>8}{'w min':>7}{'r min':>7}{'raster':>11}  source")
    for e in entries:
        d = {"clockwise": "cw", "counterclockwise": "ccw"}.get(e.direction or "", "-")
        print(
            f"{e.id:<42}{e.kind:<10}{d:<5}{e.lap_length_m:9.1f}{e.width_mean_m:8.2f}{e.width_min_m:7.2f}"
            f"{e.min_radius_m:7.2f}{f'{e.raster.width_px}x{e.raster.height_px}':>11}  {e.source.licence[:24]}"
        )
    counts = {k: sum(e.kind == k for e in entries) for k in ("circuit", "recorded", "generated")}
    print(
        f"\n{len(entries)} tracks: "
        + ", ".join(f"{n} {k}" for k, n in counts.items())
        + f"; {len(cat.left_out)} recorded maps left out (see 'tracks list --json' / catalog.json 'left_out'), "
        + f"{len(cat.open_maps)} of them offered as open maps ('tracks list --kind open')"
    )
    return EXIT_OK


def _list_open(cat: Catalog, args: argparse.Namespace) -> int:
    """``tracks list --kind open``: the recorded maps offered as open maps."""
    opens = cat.open_maps[: args.limit] if args.limit is not None else cat.open_maps
    if args.json:
        print_json([o.to_json_dict() for o in opens])
        return EXIT_OK
    print(f"{'id':<42}{'start x, y, yaw':>24}{'clear m':>8}{'gap m':>7}  why not a track")
    for o in opens:
        x, y, yaw = o.start
        gap = f"{o.narrowest_gap_m:7.2f}" if o.narrowest_gap_m is not None else f"{'-':>7}"
        print(f"{o.id:<42}{f'{x:.2f}, {y:.2f}, {yaw:.2f}':>24}{o.start_clearance_m:8.2f}{gap}  {o.reason[:70]}")
    print(f"\n{len(opens)} open maps (walls only, no lap: gym.make(..., track=MAP.yaml) or open=True)")
    return EXIT_OK


def run_show(args) -> int:
    cat = _load(args)
    e = cat.get(args.id)
    path = cat.map_path(e, args.sources)
    index = load_index()
    rec = index.get(e.id) if index else None
    if args.json:
        extra = {"raceline": rec.to_json_dict()} if rec else {}
        print_json({**e.to_json_dict(), "map_path": str(path), **extra})
        return EXIT_OK

    print("\n".join(entry_lines({**e.to_json_dict(), "map_path": str(path)})))
    if rec:
        print("\n".join(record_lines(rec)))
    return EXIT_OK


def run_build(args) -> int:
    cat = _load(args)
    e = cat.get(args.id)
    report = build_environment(cat.map_path(e, args.sources), args.out)
    if args.json:
        print_json({"id": e.id, "out": str(args.out), "report": getattr(report, "__dict__", str(report))})
    else:
        print(f"built {e.id} -> {args.out}")
    return EXIT_OK


def run_verify(args) -> int:
    from ..library.verify import verify

    if args.reverse and args.update_catalog:
        raise InvalidArgumentError("--reverse and --update-catalog: the catalog records laps in the racing direction")
    if args.update_catalog:  # before any work: the installed package's catalog is never written
        writable_catalog(args.catalog, "--catalog")
    cat = _load(args)
    entries = _select(cat, args)
    with _executor(args) as ex:
        s = verify(
            cat,
            entries,
            args.sources,
            usd=not args.no_usd,
            drive=not args.no_drive,
            progress=_progress("verify"),
            reverse=args.reverse,
            executor=ex,
            physx=False if args.no_physx else None,
        )
    if args.update_catalog:
        from ..library.verify import failed_recorded, record_results

        failed = failed_recorded(cat, s)
        opens = {}
        if failed:  # a recorded map that no longer laps may still be an open map
            from ..library.open_maps import is_open_candidate, open_map_entry

            src = sources_dir(args.sources, "open maps")
            opens = {lo.id: o for lo in failed if is_open_candidate(lo) and (o := open_map_entry(src, lo))}
        assert cat.path is not None
        moved = record_results(cat.path, s, opens)
        s = s.model_copy(update={"moved_to_left_out": moved})
        if not args.json:
            print(f"updated {cat.path}: {len(moved)} recorded map(s) moved to left_out: {', '.join(moved) or '-'}")
    if args.json:
        print_json(s)
    else:
        print(f"{'id':<42}{'kind':<10}" + "".join(f"{n:<9}" for n in CHECKS) + "  detail")
        for r in s.results:
            st = [r.status(n) or "-" for n in CHECKS]
            print(f"{r.id:<42}{r.kind:<10}" + "".join(f"{x:<9}" for x in st) + "  " + "; ".join(r.failures()))
        print()
        for n, d in s.per_check.items():
            print(f"{n:<6} pass {d['pass']:>4}  FAIL {d['FAIL']:>4}  not run {d['not run']:>4}")
        reasons = {c.detail for r in s.results for c in r.checks.values() if c.status == "not run"}
        for why in sorted(reasons):
            print(f"  ({why})")
        if s.drive_cautious:
            print(f"  {len(s.drive_cautious)} lap(s) needed the cautious retry: {', '.join(s.drive_cautious)}")
        print(
            f"{s.passed}/{s.tracks} tracks without a failed check in {s.seconds:.1f} s "
            f"({s.jobs} worker(s)); by kind: " + ", ".join(f"{k} {v.passed}/{v.tracks}" for k, v in s.by_kind.items())
        )
    raceline_problems = _verify_racelines([r.id for r in s.results]) if args.raceline else []
    return EXIT_OK if not s.failed and not raceline_problems else EXIT_BAD_INPUT


def _verify_racelines(ids: list[str]) -> list[str]:
    """``tracks verify --raceline``: plan each track's raceline again against its record."""
    from ..library.racelines import verify_record

    index = load_index()
    problems = [p for i in ids for p in verify_record(i, index)]
    for p in problems:
        print(f"raceline: {p}", file=sys.stderr)
    print(f"racelines: {len(ids) - len({p.split(':')[0] for p in problems})}/{len(ids)} as recorded")
    return problems


def run_sheet(args) -> int:
    from ..library.sheet import contact_sheet

    cat = _load(args)
    entries = _select(cat, args)
    out = contact_sheet(cat, entries, args.out, args.sources, columns=args.columns, progress=_progress("sheet"))
    if args.json:
        print_json({"out": str(out), "tracks": len(entries)})
    else:
        print(f"wrote {out} ({len(entries)} tracks)")
    return EXIT_OK


def run_catalog(args) -> int:
    import os

    from ..library.index import build_catalog, build_catalog_generating

    tracks = writable_tracks_dir(args.tracks or (args.catalog.parent if args.catalog else None), "--tracks")
    sources = sources_dir(args.sources, "tracks catalog (it assesses the recorded maps)")
    jobs = args.jobs or os.cpu_count() or 1
    if args.rejudge:
        return _rejudge(args, Path(sources), jobs)
    if args.max_requests is not None and not args.generate:
        raise InvalidArgumentError("--max-requests needs --generate")
    if args.generate:
        g, cat = build_catalog_generating(
            Path(sources),
            Path(tracks),
            count=args.count,
            jobs=jobs,
            progress=_progress("recorded maps"),
            generate_progress=_progress("generate"),
            max_requests=args.max_requests,
        )
        if not args.json:
            print(
                f"generated sweep: {g.specs_tried} specs, {g.accepted} accepted, {g.failed} failed, "
                f"{g.rejected} rejected; kept {g.kept} ({g.seconds:.1f} s)"
            )
    else:
        cat = build_catalog(Path(sources), Path(tracks), jobs=jobs, progress=_progress("recorded maps"))
    if args.json:
        print_json(
            {
                **cat.meta.to_json_dict(),
                "count": len(cat.entries),
                "left_out": [lo.to_json_dict() for lo in cat.left_out],
            }
        )
    else:
        print(
            f"wrote {cat.path}: {len(cat.entries)} tracks {cat.meta.counts}; {len(cat.left_out)} recorded maps left out:"
        )
        for lo in cat.left_out:
            print(f"  {lo.source_path}: {lo.reason}")
    return EXIT_OK


def _rejudge(args: argparse.Namespace, sources: Path, jobs: int) -> int:
    from ..library.open_maps import map_kinds, open_maps, rejudge

    def change(cat: Catalog) -> tuple[list[str], Catalog]:
        joined = rejudge(cat, sources, jobs)
        cat.open_maps = open_maps(sources, cat.left_out, jobs)
        return joined, cat

    # under the catalog's lock throughout: a verify --update-catalog meanwhile waits, then merges
    joined, cat = update_catalog(args.catalog or default_tracks_dir() / "catalog.json", change)
    kinds = map_kinds(cat)
    counts = {k: sum(v == k for v in kinds.values()) for k in ("track", "open", "duplicate", "broken", "left out")}
    if args.json:
        print_json({"joined": joined, "recorded_maps": len(kinds), "by_kind": counts})
    else:
        print(f"updated {cat.path}: {len(joined)} map(s) joined the tracks: {', '.join(joined) or '-'}")
        print(f"{len(kinds)} recorded source maps: " + ", ".join(f"{n} {k}" for k, n in counts.items()))
        for lo in cat.left_out:
            if lo.reason.startswith("verify failed"):
                print(f"  {lo.id}: {lo.reason}")
    return EXIT_OK


def run_generate(args) -> int:
    from ..library.spec_sweep_run import generate_library

    sweep = load_sweep(args.sweep)
    with _executor(args) as ex:
        s = generate_library(
            sweep, args.count, args.out, ex, max_requests=args.max_requests, progress=_progress("generate")
        )
    if args.json:
        print_json(s.model_dump(mode="json", exclude={"records"}))
    else:
        print(
            f"{s.kept}/{s.count} tracks in {args.out / 'generated'} from {s.requests} requests "
            f"({s.accepted} accepted, {s.rejected} rejected, {s.failed} failed) in {s.seconds:.1f} s "
            f"on {s.workers} worker(s) ({s.executor}); catalog {args.out / 'catalog.json'}"
        )
    if s.kept < s.count:
        print(
            f"roboracer-arena tracks: error: only {s.kept} of {s.count} tracks within --max-requests "
            f"{s.requests}; widen the sweep ranges or raise --max-requests",
            file=sys.stderr,
        )
        return EXIT_GENERATION_FAILURE
    return EXIT_OK
