"""Sweep files (``tracks generate --sweep``): format checks with one-line errors, the seed
scheme (request k is the same whatever the range asked), and a local library build that
is identical on 1 and 2 processes, with atomic outputs and a catalog verify reads."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from roboracer_arena.catalog import load_catalog
from roboracer_arena.cli import main
from roboracer_arena.distributed import LocalExecutor
from roboracer_arena.errors import SpecError
from roboracer_arena.library.spec_sweep import GridSweep, SweepFile, SweepRequest, load_sweep
from roboracer_arena.library.spec_sweep_run import generate_library

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "sweep.json"
SMALL = {
    "name": "t",
    "base_seed": 7,
    "ranges": {
        "lap_length_m": [30, 45],
        "hairpins": [0, 1],
        "direction": {"choice": ["clockwise", "counterclockwise"]},
    },
    "fixed": {"corridor_width_m": 1.5, "hall_x_m": 15, "hall_y_m": 12},
}


def write(tmp_path: Path, doc) -> Path:
    p = tmp_path / "sweep.json"
    p.write_text(json.dumps(doc) if not isinstance(doc, str) else doc)
    return p


def test_example_sweep_loads_and_draws_within_ranges():
    sw = load_sweep(EXAMPLE)
    for k in range(40):
        s = sw.spec(k)
        lo, hi = sw.ranges["lap_length_m"]
        assert lo <= s.lap_length_m <= hi and 0 <= s.hairpins <= 2 and isinstance(s.hairpins, int)
        assert s.name == f"hall-sweep-{k:05d}"
    assert len({sw.spec(k).direction for k in range(40)}) == 2


def test_request_k_does_not_depend_on_the_window():
    sw = SweepFile.model_validate(SMALL)
    assert sw.requests(3, 5) == sw.requests(0, 5)[3:]
    assert sw.seed(3) != sw.seed(4) and sw.spec(3) != sw.spec(4)
    other = SweepFile.model_validate({**SMALL, "base_seed": 8})
    assert [other.spec(k) for k in range(5)] != [sw.spec(k) for k in range(5)]


@pytest.mark.parametrize(
    "doc, msg",
    [
        ("{not json", "not valid JSON"),
        ({**SMALL, "ranges": {"lap_lenght_m": [1, 2]}}, "unknown TrackSpec field"),
        ({**SMALL, "ranges": {"lap_length_m": [50, 40]}}, "lower bound 50 is above"),
        ({**SMALL, "ranges": {"hairpins": [0, 1.5]}}, "integer bounds"),
        ({**SMALL, "fixed": {"hairpins": "two"}}, "hairpins"),
        ({**SMALL, "name": "a b/c"}, "name"),
        ({**SMALL, "seeds": 3}, "seeds"),
    ],
)
def test_bad_sweep_files_name_file_and_field(tmp_path, doc, msg):
    p = write(tmp_path, doc)
    with pytest.raises(SpecError, match=msg) as e:
        load_sweep(p)
    assert str(p) in str(e.value) and "\n" not in str(e.value)


def test_cli_bad_sweep_and_count_exit_2(tmp_path, capsys):
    p = write(tmp_path, {**SMALL, "ranges": {"nope": [1, 2]}})
    assert main(["tracks", "generate", "--sweep", str(p), "--count", "2", "-o", str(tmp_path / "o")]) == 2
    assert "unknown TrackSpec field" in capsys.readouterr().err
    p = write(tmp_path, SMALL)
    assert (
        main(["tracks", "generate", "--sweep", str(p), "--count", "0", "-o", str(tmp_path / "o"), "--jobs", "1"]) == 2
    )
    assert (
        main(["tracks", "generate", "--sweep", str(tmp_path / "missing.json"), "--count", "1", "-o", str(tmp_path)])
        == 2
    )


def tree(d: Path) -> dict[str, bytes]:
    """Every file under ``d`` except the generator's wall-clock timings."""
    out = {}
    for f in sorted(d.rglob("*")):
        if f.is_file() and f.name not in ("report.json", "sweep.json", "catalog.json"):
            out[str(f.relative_to(d))] = f.read_bytes()
    return out


def test_library_is_identical_on_one_and_two_processes_and_verifies(tmp_path):
    sw = SweepFile.model_validate(SMALL)
    runs = {}
    for jobs in (1, 2):
        with LocalExecutor(jobs) as ex:
            s = generate_library(sw, 4, tmp_path / f"j{jobs}", ex)
        assert s.kept == 4 and s.workers == jobs
        runs[jobs] = (s, tree(tmp_path / f"j{jobs}"))
    (s1, t1), (s2, t2) = runs[1], runs[2]
    assert t1 == t2 and len(t1) == 4 * 4  # map.yaml, map.png, centreline.csv, spec.json per track
    strip = [r.model_copy(update={"seconds": 0.0}) for r in s1.records]
    assert strip == [r.model_copy(update={"seconds": 0.0}) for r in s2.records]
    assert [r.k for r in s1.records] == list(range(len(s1.records)))
    kept = [r.id for r in s1.records if r.kept]
    assert kept == sorted(kept) and len(kept) == 4
    assert not list((tmp_path / "j2" / "generated").glob(".*"))  # no temporaries left
    cat = load_catalog(tmp_path / "j2" / "catalog.json")
    assert [e.id for e in cat.entries] == kept and all(e.direction for e in cat.entries)
    assert (
        main(
            [
                "tracks",
                "verify",
                "--catalog",
                str(tmp_path / "j2" / "catalog.json"),
                "--no-usd",
                "--no-drive",
                "--jobs",
                "1",
            ]
        )
        == 0
    )
    # A smaller rerun into the same directory leaves exactly its tracks behind.
    with LocalExecutor(1) as ex:
        generate_library(sw, 2, tmp_path / "j2", ex)
    assert sorted(p.name for p in (tmp_path / "j2" / "generated").iterdir()) == kept[:2]


def test_budget_exhausted_exits_4(tmp_path, capsys):
    doc = {**SMALL, "fixed": {**SMALL["fixed"], "hall_x_m": 4, "hall_y_m": 4}}  # nothing fits: all rejected
    p = write(tmp_path, doc)
    assert (
        main(
            [
                "tracks",
                "generate",
                "--sweep",
                str(p),
                "--count",
                "2",
                "-o",
                str(tmp_path / "o"),
                "--jobs",
                "1",
                "--max-requests",
                "3",
            ]
        )
        == 4
    )
    assert "only 0 of 2 tracks" in capsys.readouterr().err
    s = json.loads((tmp_path / "o" / "sweep.json").read_text())
    assert s["requests"] == 3 and s["rejected"] == 3 and load_catalog(tmp_path / "o" / "catalog.json").entries == []


def test_packaged_example_sweep_is_the_examples_file():
    from roboracer_arena.library.spec_sweep import EXAMPLE_SWEEP

    assert json.loads(EXAMPLE.read_text()) == EXAMPLE_SWEEP


def test_packaged_sweep_summary_loads_typed_and_round_trips():
    from roboracer_arena.foundation.paths import tracks_dir
    from roboracer_arena.library.spec_sweep_report import GeneratedSweepSummary

    text = (tracks_dir() / "generated" / "sweep.json").read_text(encoding="utf-8")
    s = GeneratedSweepSummary.model_validate_json(text)
    assert s.kept == sum(bool(r.kept) for r in s.records) and s.specs_tried == len(s.records)
    assert json.dumps(s.to_json_dict(), indent=2) + "\n" == text


def test_packaged_generated_library_is_what_the_sweep_builds(tmp_path):
    """``build_generated`` (``tracks catalog --generate``) on two processes rebuilds the
    packaged ``tracks/generated``: the same 60 tracks, byte for byte (bar the generator's
    wall-clock timings), and the same records."""
    from roboracer_arena.foundation.paths import tracks_dir
    from roboracer_arena.library.generated import build_generated

    shipped = tracks_dir() / "generated"
    s = build_generated(tmp_path, count=60, jobs=2)
    assert tree(tmp_path) == tree(shipped) and s.kept == 60
    old = json.loads((shipped / "sweep.json").read_text())["records"]
    assert [r.model_copy(update={"seconds": 0.0}).to_json_dict() for r in s.records] == [
        {**r, "seconds": 0.0} for r in old
    ]


def test_grid_sweep_crosses_its_axes_then_admits_thins_and_seeds():
    """GridSweep, the one grid builder (the generated library's and the benchmarks' sweeps):
    the last axis varies fastest, directions alternate by grid index before ``admit``,
    the admitted requests are thinned evenly, and a request without a seed gets k % cycle."""
    grid = GridSweep(
        axes=([{"lap_length_m": 40.0}, {"lap_length_m": 50.0}], [{"hairpins": h} for h in range(3)]),
        name=lambda f: f"g-{f['lap_length_m']:g}-{f['hairpins']}-{f['direction'][:3]}",
        directions=("clockwise", "counterclockwise"),
        admit=lambda spec: spec.hairpins != 1,
        count=3,
        seed_cycle=2,
    )
    reqs = grid.requests()
    assert all(isinstance(r, SweepRequest) and r.spec.name == r.id for r in reqs)
    # grid: (40,0,cw) (40,1,ccw) (40,2,cw) (50,0,ccw) (50,1,cw) (50,2,ccw); admitted 4, thinned to 3
    assert [r.id for r in reqs] == ["g-40-0-clo", "g-40-2-clo", "g-50-0-cou"]
    assert [r.seed for r in reqs] == [0, 1, 0]
    seeded = GridSweep(axes=([{"lap_length_m": 40.0}], [{"seed": 7}, {"seed": 9}]), name=lambda f: f"s{f['seed']}")
    assert [(r.id, r.seed) for r in seeded.requests()] == [("s7", 7), ("s9", 9)]
    assert grid.requests() == reqs  # a pure function of the sweep
