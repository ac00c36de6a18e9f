"""An interrupted ``tracks catalog --generate`` used to leave the generated folder and
the catalog out of step: the sweep's tracks were written into ``tracks/generated`` one by
one and the ones not kept removed, and only then was ``tracks/catalog.json`` rebuilt, so
a signal in between left a catalog naming tracks that no longer existed. The folder and
the catalog are now staged and swapped in together: a signal at any moment leaves both
as they were (or both new), and no staging folder. ``circuits`` wrote each circuit's
files into the library in place the same way; its folder is staged too."""

from __future__ import annotations

import hashlib
import shutil
import signal
import time
from pathlib import Path

import pytest

from .conftest import cli, strays

pytestmark = [pytest.mark.slow, pytest.mark.timeout(300)]


def tree(root: Path) -> dict[str, str]:
    return {
        str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest() for p in root.rglob("*") if p.is_file()
    }


def catalog_run(root: Path, *extra: str):
    return cli("tracks", "catalog", "--tracks", str(root / "tracks"), "--sources", str(root / "src"), *extra)


@pytest.fixture(scope="module")
def library(tmp_path_factory) -> Path:
    """A tracks folder holding the 60 shipped generated tracks, a file of the user's beside
    them, and the catalog ``tracks catalog`` builds from them (no recorded maps: an empty
    sources folder)."""
    from roboracer_arena.foundation.paths import tracks_dir

    root = tmp_path_factory.mktemp("catalog")
    shutil.copytree(tracks_dir() / "generated", root / "tracks" / "generated")
    (root / "tracks" / "generated" / "mine.txt").write_text("a file of the user's\n")
    (root / "src").mkdir()
    p = catalog_run(root, "--jobs", "1")
    _, err = p.communicate(timeout=240)
    assert p.returncode == 0, err
    return root


def writing(root: Path, t0: float) -> bool:
    """True once the run has written a generated track, wherever it writes it."""
    tracks = root / "tracks"
    specs = [*tracks.glob("generated/*/spec.json"), *tracks.glob(".generated.*/*/spec.json")]
    return any(p.stat().st_mtime >= t0 for p in specs if p.exists())


def whole(root: Path) -> bool:
    """The catalog and the generated folder describe each other: every entry's map is
    there with its checksum, and every track folder is an entry."""
    from roboracer_arena.catalog.catalog_file import load_catalog, sha256_file

    tracks = root / "tracks"
    cat = load_catalog(tracks / "catalog.json")
    ids = {e.id for e in cat.entries if e.kind == "generated"}
    folders = {d.name for d in (tracks / "generated").iterdir() if d.is_dir()}
    return ids == folders and all(sha256_file(tracks / Path(e.map).parent / "map.png") == e.sha256 for e in cat.entries)


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_an_interrupted_catalog_generate_leaves_the_library_as_it_was(library, tmp_path, sig):
    shutil.copytree(library, tmp_path, dirs_exist_ok=True)
    before = tree(tmp_path)
    t0 = time.time()
    p = catalog_run(tmp_path, "--generate", "--count", "30", "--jobs", "1")  # 30 of the 60 kept
    deadline = time.monotonic() + 120
    while not writing(tmp_path, t0) and p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.02)
    p.send_signal(sig)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130 and "Traceback" not in err, err[-800:]
    assert tree(tmp_path) == before and whole(tmp_path)
    assert strays(tmp_path / "tracks") == [] and strays(tmp_path / "tracks" / "generated") == []


def test_a_finished_catalog_generate_swaps_both_in(library, tmp_path):
    shutil.copytree(library, tmp_path, dirs_exist_ok=True)
    p = catalog_run(tmp_path, "--generate", "--count", "6", "--max-requests", "12", "--jobs", "1")
    _, err = p.communicate(timeout=240)
    assert p.returncode == 0, err
    assert whole(tmp_path) and (tmp_path / "tracks" / "generated" / "mine.txt").exists()
    assert len([d for d in (tmp_path / "tracks" / "generated").iterdir() if d.is_dir()]) == 6
    assert strays(tmp_path / "tracks") == [] and strays(tmp_path / "tracks" / "generated") == []


def test_an_interrupted_circuits_rebuild_leaves_the_library_as_it_was(sources, tmp_path):
    out = tmp_path / "circuits"
    base = ["circuits", "--sources", str(sources), "-o", str(out), "--only", "monaco", "--jobs", "1"]
    p = cli(*base)
    _, err = p.communicate(timeout=240)
    assert p.returncode == 0, err
    (out / "mine.txt").write_text("a file of the user's\n")
    before = tree(tmp_path)
    t0 = time.time()
    p = cli(*base, "--resolution", "0.1")  # a different map: the old code overwrote it in place
    deadline = time.monotonic() + 120
    while p.poll() is None and time.monotonic() < deadline:  # the build has begun, wherever it writes
        maps = [m for m in tmp_path.glob("circuits/monaco/map.yaml") if m.stat().st_mtime >= t0]
        if maps or any(tmp_path.glob(".circuits.*.tmp")):
            break
        time.sleep(0.01)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130 and "Traceback" not in err, err[-800:]
    assert tree(tmp_path) == before and strays(tmp_path) == [] and strays(out) == []
