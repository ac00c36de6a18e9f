"""The package carries what the catalog needs; recorded maps come from the sources folder,
which one function resolves; licences and notices name what ships."""

from __future__ import annotations

import json
import os
import re
import sys
from pathlib import Path

import pytest

import roboracer_arena
from roboracer_arena.catalog import load_catalog
from roboracer_arena.cli import EXIT_BAD_INPUT, main
from roboracer_arena.errors import MapIOError
from roboracer_arena.foundation import paths

REPO = Path(__file__).resolve().parents[2]


def test_catalog_maps_of_circuits_and_generated_tracks_ship_in_the_package():
    cat = load_catalog()
    assert cat.path == paths.tracks_dir() / "catalog.json"
    assert paths.tracks_dir().is_relative_to(paths.PACKAGE_DIR)
    shipped = [e for e in cat.entries if e.kind in ("circuit", "generated")]
    assert len(shipped) >= 100
    for e in shipped:
        for rel in (e.map, e.centreline):
            assert rel is not None, e.id
            f = cat.file_path(e, rel)
            assert f.is_file() and f.is_relative_to(paths.PACKAGE_DIR), f


def test_the_package_carries_no_paper_benchmark_or_baseline(capsys):
    """Only the machine benchmarks (``bench physics``, ``bench env``) ship; the paper's
    harnesses, peer comparisons, their data and the baselines are the checkout's benchmarks/."""
    bench = paths.PACKAGE_DIR / "bench"
    assert sorted(p.name for p in bench.iterdir() if p.name != "__pycache__") == [
        "__init__.py",
        "env.py",
        "output.py",
        "physics.py",
    ]
    assert not (paths.PACKAGE_DIR / "generate" / "baselines.py").exists()
    assert main(["bench", "build", "--repeat", "1"]) == EXIT_BAD_INPUT
    assert "python -m benchmarks build" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["bench", "--help"])
    listed = capsys.readouterr().out
    assert "physics" in listed and "env" in listed and "constructors" not in listed


def test_recorded_maps_need_the_sources_setting(monkeypatch):
    rec = next(e for e in load_catalog().entries if e.kind == "recorded")
    monkeypatch.delenv(paths.SOURCES_ENV, raising=False)
    monkeypatch.setattr(paths, "checkout_dir", lambda: None)  # as an installed wheel
    assert paths.default_sources_dir() is None
    with pytest.raises(MapIOError, match=f"recorded map '{rec.id}'.*set ROBORACER_ARENA_SOURCES"):
        load_catalog().map_path(rec)
    monkeypatch.setenv(paths.SOURCES_ENV, "/nonexistent/track-sources")
    with pytest.raises(
        MapIOError, match="/nonexistent/track-sources: track-sources folder not found.*ROBORACER_ARENA_SOURCES"
    ):
        load_catalog().map_path(rec)


def test_sources_flag_beats_the_setting(tmp_path, monkeypatch, sources):
    monkeypatch.setenv(paths.SOURCES_ENV, str(tmp_path / "nope"))
    assert paths.sources_dir(sources) == sources


def test_installed_package_is_never_written_into(monkeypatch, capsys, tmp_path):
    monkeypatch.delenv(paths.TRACKS_ENV, raising=False)
    monkeypatch.setattr(paths, "checkout_dir", lambda: None)
    assert main(["tracks", "catalog"]) == EXIT_BAD_INPUT
    assert "--tracks DIR is required" in capsys.readouterr().err
    assert main(["circuits", "--only", "monaco"]) == EXIT_BAD_INPUT
    assert "-o/--out DIR is required" in capsys.readouterr().err
    assert paths.writable_tracks_dir(tmp_path, "--tracks") == tmp_path


def test_tracks_catalog_writes_where_the_user_says(tmp_path, sources, capsys):
    """An empty tracks folder and a sources folder with two recorded maps (one with a
    source centreline beside it) give a catalog of those two, written there."""
    src = tmp_path / "sources"
    for rel in (
        "f1tenth-gym/maps/berlin.yaml",
        "f1tenth-gym/maps/berlin.png",
        "bdevan5-f1tenth-benchmarks/maps/aut.yaml",
        "bdevan5-f1tenth-benchmarks/maps/aut.png",
        "bdevan5-f1tenth-benchmarks/maps/aut_centerline.csv",
    ):
        (src / rel).parent.mkdir(parents=True, exist_ok=True)
        (src / rel).symlink_to(sources / rel)
    out = tmp_path / "mytracks"
    out.mkdir()
    assert main(["tracks", "catalog", "--tracks", str(out), "--sources", str(src), "--jobs", "1", "--json"]) == 0
    doc = json.loads((out / "catalog.json").read_text())
    assert doc["counts"] == {"circuit": 0, "recorded": 2, "generated": 0}
    by_id = {e["id"]: e for e in doc["tracks"]}
    assert by_id["gym-berlin"]["direction"] == "counterclockwise" and by_id["gym-berlin"][
        "direction_source"
    ].startswith("default")
    assert by_id["bdevan5-aut"]["direction"] == "clockwise"
    assert (
        by_id["bdevan5-aut"]["direction_source"]
        == "point order of the source file bdevan5-f1tenth-benchmarks/maps/aut_centerline.csv"
    )


def test_third_party_notice_names_every_packaged_circuit_and_its_source():
    notice = (REPO / "THIRD_PARTY_NOTICES.md").read_text(encoding="utf-8")
    assert "LGPL-3.0" in notice and "MIT" in notice
    for f in sorted((paths.tracks_dir() / "circuits").glob("*/circuit.json")):
        r = json.loads(f.read_text())
        assert re.search(rf"^\| `{re.escape(r['id'])}` \| `{re.escape(r['source_file'])}` \|$", notice, re.M), r["id"]
    for lic in ("LGPL-3.0.txt", "GPL-3.0.txt", "MIT-bacinger-f1-circuits.txt"):
        assert (REPO / "LICENSES" / lic).is_file()
    assert "MIT License" in (REPO / "LICENSE").read_text()


@pytest.mark.skipif(
    not os.environ.get("ROBORACER_ARENA_EXPECT_INSTALLED"), reason="runs against the installed wheel only"
)
def test_running_against_the_installed_wheel():
    """`make test` runs this suite against the wheel installed outside the checkout."""
    assert "site-packages" in roboracer_arena.__file__ and paths.checkout_dir() is None
    dist = next(Path(sys.prefix).glob("lib/python*/site-packages/roboracer_arena-*.dist-info"))
    licences = {p.name for p in (dist / "licenses").rglob("*") if p.is_file()}
    assert {"LICENSE", "THIRD_PARTY_NOTICES.md", "LGPL-3.0.txt", "MIT-bacinger-f1-circuits.txt"} <= licences, licences
