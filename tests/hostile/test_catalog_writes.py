"""Issue 38, class A: ``tracks verify --update-catalog`` never loses or overwrites data.

* it refuses (exit 2, before any work) to write the installed package's catalog: no
  ``--catalog``, or one inside the package;
* a ``--sources`` folder that does not exist is an error (exit 2), never a verdict that
  moves the checked maps to ``left_out``;
* only the entries it checked change: other tracks, left-out maps and open maps stay
  byte for byte;
* two runs on different ids of one library, started at random moments, both keep their
  verdicts (the write re-reads the catalog under a lock and replaces it atomically).

The library here is tiny: two generated tracks copied from the shipped catalog (their
load and ring checks take a fraction of a second), one recorded map (read from the shared
sources), the shipped left-out and open-map entries.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from roboracer_arena.catalog import load_catalog
from roboracer_arena.cli import main
from roboracer_arena.foundation.paths import PACKAGE_DIR

PACKAGE_CATALOG = PACKAGE_DIR / "tracks" / "catalog.json"
CHECKS = ["--no-usd", "--no-drive", "--no-physx", "--jobs", "1"]


@pytest.fixture
def library(tmp_path: Path) -> Path:
    """A copy of a sliver of the shipped catalog: 2 generated tracks without verdicts,
    1 recorded map, every left-out and open-map entry."""
    doc = json.loads(PACKAGE_CATALOG.read_text(encoding="utf-8"))
    gens = [t for t in doc["tracks"] if t["kind"] == "generated"][:2]
    rec = [t for t in doc["tracks"] if t["kind"] == "recorded"][:1]
    for t in gens:
        t.pop("verified", None)
        t.pop("drive", None)
        src = PACKAGE_CATALOG.parent / Path(t["map"]).parent
        shutil.copytree(src, tmp_path / Path(t["map"]).parent)
    doc["tracks"] = gens + rec
    doc["count"] = len(doc["tracks"])
    doc["counts"] = {"circuit": 0, "recorded": 1, "generated": 2}
    path = tmp_path / "catalog.json"
    path.write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    return path


def _ids(path: Path) -> list[str]:
    return [t["id"] for t in json.loads(path.read_text())["tracks"] if t["kind"] == "generated"]


def test_update_catalog_refuses_the_installed_package_catalog(capsys):
    before = PACKAGE_CATALOG.read_bytes(), PACKAGE_CATALOG.stat().st_mtime_ns
    gen = load_catalog().select("generated")[0].id
    t0 = time.perf_counter()
    assert main(["tracks", "verify", "--update-catalog", "--ids", gen, *CHECKS]) == 2
    err = capsys.readouterr().err
    assert "--catalog FILE is required" in err and err.count("\n") == 1, err
    assert main(["tracks", "verify", "--update-catalog", "--catalog", str(PACKAGE_CATALOG), "--ids", gen, *CHECKS]) == 2
    err = capsys.readouterr().err
    assert "inside the installed package" in err and err.count("\n") == 1, err
    assert time.perf_counter() - t0 < 5  # refused before any work
    assert (PACKAGE_CATALOG.read_bytes(), PACKAGE_CATALOG.stat().st_mtime_ns) == before


def test_a_missing_sources_folder_is_an_error_not_a_verdict(library, tmp_path, capsys):
    before = library.read_bytes()
    rec = next(t["id"] for t in json.loads(before)["tracks"] if t["kind"] == "recorded")
    missing = tmp_path / "track-sourcez"  # a typo
    for ids in ([rec], [rec, *_ids(library)], _ids(library)[:1]):
        argv = ["tracks", "verify", "--catalog", str(library), "--sources", str(missing), "--update-catalog"]
        assert main([*argv, "--ids", *ids, *CHECKS]) == 2
        err = capsys.readouterr().err
        assert "track-sourcez" in err and "not found" in err and err.count("\n") == 1, err
        assert library.read_bytes() == before  # nothing moved to left_out, no open map dropped


def test_only_the_checked_entries_change(library, capsys):
    before = json.loads(library.read_text())
    gen = _ids(library)[0]
    assert main(["tracks", "verify", "--catalog", str(library), "--update-catalog", "--ids", gen, *CHECKS]) == 0
    after = json.loads(library.read_text())
    assert after["open_maps"] == before["open_maps"] and after["open_maps"]
    assert after["left_out"] == before["left_out"]
    changed = [t["id"] for t, u in zip(before["tracks"], after["tracks"]) if t != u]
    assert changed == [gen]
    assert after["tracks"][0]["verified"] == {
        "load": "pass",
        "ring": "pass",
        "usd": "not run",
        "physx": "not run",
        "drive": "not run",
    }


def test_two_concurrent_verify_runs_never_lose_a_verdict(library):
    """50 rounds: two ``tracks verify --update-catalog`` processes on different ids of one
    library, started 0-60 ms apart in random order (each run's read-check-write takes
    about as long, so they overlap between read and write in most rounds). Every round
    both exit 0 and both verdicts land (before the lock, about half the rounds lost one)."""
    a, b = _ids(library)
    driver = Path(__file__).with_name("catalog_race.py")
    r = subprocess.run(
        [sys.executable, str(driver), str(library), a, b, "50", "38", "0.06"],
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "RAYON_NUM_THREADS": "1"},
    )
    assert r.returncode == 0, r.stderr[-2000:]
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out["rounds"] == 50 and out["exit_codes"] == [0] * 100
    assert out["lost"] == [], out["lost"]
    cat = load_catalog(library)
    assert [o.id for o in cat.open_maps] and len(cat.left_out) == len(
        json.loads(PACKAGE_CATALOG.read_text())["left_out"]
    )
    assert not [p.name for p in library.parent.iterdir() if p.name.startswith(".arena-")]  # no temporary left


LOCK_RACE = r"""
import os, sys
from pathlib import Path
from roboracer_arena.foundation.fileio import file_lock
target = Path(sys.argv[1])
target.write_text("0")
kids = []
for k in range(8):
    pid = os.fork()
    if pid == 0:
        for _ in range(25):
            with file_lock(target):
                n = int(target.read_text())
                target.write_text(str(n + 1))
        os._exit(0)
    kids.append(pid)
codes = [os.waitstatus_to_exitcode(os.waitpid(p, 0)[1]) for p in kids]
print(target.read_text(), codes, sorted(p.name for p in target.parent.iterdir()))
"""


def test_file_lock_serialises_writers_and_leaves_no_lock_file(tmp_path):
    """8 processes x 25 read-increment-write steps under ``fileio.file_lock``: every
    increment lands (200), and the lock file is gone afterwards (its holder removes it;
    a waiter that wakes on a removed one locks the fresh one)."""
    r = subprocess.run(
        [sys.executable, "-c", LOCK_RACE, str(tmp_path / "counter")], capture_output=True, text=True, timeout=300
    )
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.split("[")[0].strip() == "200", r.stdout
    assert "[0, 0, 0, 0, 0, 0, 0, 0]" in r.stdout and "['counter']" in r.stdout, r.stdout
