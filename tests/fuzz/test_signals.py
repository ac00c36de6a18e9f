"""Round 2 (issue 25): SIGINT or SIGTERM at random moments (seeded, so the same moments
on every run) during ``drive --mcap``, ``ros2 --record``, ``tracks generate`` and
``tracks catalog --generate``. After
every signal: the inputs are byte for byte what they were, the output is either whole
and readable or absent, and no temporary or staging file is left. A signal can land
anywhere, including during the interpreter's imports (then the process dies of it
before any file exists)."""

from __future__ import annotations

import hashlib
import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = [pytest.mark.slow, pytest.mark.timeout(300)]
RNG = random.Random(25)
#: Exit codes after a signal: 130 the CLI's own (SIGINT and SIGTERM alike), -2/-15 dead
#: of the signal before the CLI installed its handlers, 0 finished before the signal.
AFTER_SIGNAL = {0, 130, -2, -15}


def _cli(args: list[str], cwd: Path) -> subprocess.Popen:
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    env["RAYON_NUM_THREADS"] = "2"
    return subprocess.Popen(
        [sys.executable, "-c", "import sys; from roboracer_arena.cli import main; sys.exit(main())", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        cwd=cwd,
    )


def _tree(root: Path) -> dict[str, str]:
    return {
        str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(root.rglob("*"))
        if p.is_file()
    }


def _strays(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


def _mcap_whole(path: Path) -> bool:
    from mcap.reader import make_reader

    with open(path, "rb") as f:
        reader = make_reader(f)
        reader.get_summary()
        sum(1 for _ in reader.iter_messages())
    return True


def _interrupt(p: subprocess.Popen, started, run: int, within: float) -> tuple[int, str]:
    """Signal ``p`` at a random moment: for run 0 counted from the process start (often
    during imports), else counted from when ``started()`` first holds (the job is writing)."""
    if run:
        deadline = time.monotonic() + 120
        while not started() and p.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)
    time.sleep(RNG.uniform(0.0, within))
    p.send_signal(RNG.choice([signal.SIGINT, signal.SIGTERM]))
    _, err = p.communicate(timeout=120)
    return p.returncode, err


@pytest.mark.parametrize("run", range(4))
@pytest.mark.parametrize("command", ["drive", "ros2"])
def test_a_signal_during_a_recording_leaves_it_whole_or_absent(ellipse_map, tmp_path, command, run):
    pytest.importorskip("mcap")
    inputs = tmp_path / "in"
    inputs.mkdir()
    for p in ellipse_map.parent.iterdir():
        (inputs / p.name).write_bytes(p.read_bytes())
    before = _tree(inputs)
    out = tmp_path / "out"
    out.mkdir()
    target = out / "run.mcap"
    if command == "drive":
        args = ["drive", str(inputs / ellipse_map.name), "--laps", "100", "--mcap", str(target), "--json"]
    else:
        args = ["ros2", str(inputs / ellipse_map.name), "--record", str(target), "--loopback", "--json"]
        args += ["--domain-id", str(RNG.randint(1, 200))]
    code, err = _interrupt(_cli(args, out), lambda: bool(_strays(out)), run, 3.0)  # the temporary exists
    assert code in AFTER_SIGNAL, err[-800:]
    if code in (0, 130):
        assert "Traceback" not in err, err[-800:]
    assert _tree(inputs) == before
    assert _strays(out) == []
    assert not target.exists() or _mcap_whole(target)


SWEEP = {
    "name": "fz",
    "base_seed": 3,
    "ranges": {"lap_length_m": [30, 45], "hairpins": [0, 1]},
    "fixed": {"corridor_width_m": 1.5, "hall_x_m": 15, "hall_y_m": 12},
}


@pytest.fixture(scope="module")
def library(tmp_path_factory) -> Path:
    """A one-track library made once; each test interrupts a rerun over a copy of it."""
    root = tmp_path_factory.mktemp("lib")
    (root / "s.json").write_text(json.dumps(SWEEP))
    p = _cli(["tracks", "generate", "--sweep", "s.json", "--count", "1", "-o", "lib", "--jobs", "1"], root)
    _, err = p.communicate(timeout=240)
    assert p.returncode == 0, err
    return root / "lib"


@pytest.mark.parametrize("run", range(3))
def test_a_signal_during_tracks_generate_leaves_the_library_whole(library, tmp_path, run):
    import shutil

    from roboracer_arena.catalog.catalog_file import load_catalog, sha256_file

    lib = tmp_path / "lib"
    shutil.copytree(library, lib)
    sweep = tmp_path / "s.json"
    sweep.write_text(json.dumps({**SWEEP, "base_seed": 4 + run}))
    before, sweep_before = _tree(lib), sweep.read_bytes()
    args = ["tracks", "generate", "--sweep", "s.json", "--count", "5000", "-o", "lib", "--jobs", "1"]
    t0 = time.time()

    def started() -> bool:  # a track of this run is written, wherever this code writes it
        specs = [*tmp_path.glob("*/generated/*/spec.json"), *tmp_path.glob(".*/generated/*/spec.json")]
        return any(p.stat().st_mtime >= t0 for p in specs if p.exists())

    code, err = _interrupt(_cli(args, tmp_path), started, run, 4.0)
    assert code in AFTER_SIGNAL - {0}, err[-800:]
    assert _tree(lib) == before and sweep.read_bytes() == sweep_before
    assert _strays(tmp_path) == [] and _strays(lib / "generated") == []
    cat = load_catalog(lib / "catalog.json")
    assert all(sha256_file(lib / Path(e.map).parent / "map.png") == e.sha256 for e in cat.entries)


@pytest.fixture(scope="module")
def catalog_library(tmp_path_factory) -> Path:
    """A tracks folder with 60 generated tracks (the shipped ones), a file of the user's and
    its catalog; an empty sources folder (no recorded maps), made once."""
    import shutil

    from roboracer_arena.foundation.paths import tracks_dir

    root = tmp_path_factory.mktemp("catalog")
    shutil.copytree(tracks_dir() / "generated", root / "tracks" / "generated")
    (root / "tracks" / "generated" / "mine.txt").write_text("a file of the user's\n")
    (root / "src").mkdir()
    p = _cli(["tracks", "catalog", "--tracks", "tracks", "--sources", "src", "--jobs", "1"], root)
    _, err = p.communicate(timeout=240)
    assert p.returncode == 0, err
    return root


def _catalog_whole(tracks: Path, kept: int) -> bool:
    """``catalog.json`` and ``generated/`` describe each other, with ``kept`` generated tracks."""
    from roboracer_arena.catalog.catalog_file import load_catalog, sha256_file

    cat = load_catalog(tracks / "catalog.json")
    ids = {e.id for e in cat.entries if e.kind == "generated"}
    folders = {d.name for d in (tracks / "generated").iterdir() if d.is_dir()}
    sums = all(sha256_file(tracks / Path(e.map).parent / "map.png") == e.sha256 for e in cat.entries)
    return ids == folders and len(ids) == kept and sums and (tracks / "generated" / "mine.txt").exists()


@pytest.mark.parametrize("run", range(3))
def test_a_signal_during_tracks_catalog_generate_leaves_old_or_new_whole(catalog_library, tmp_path, run):
    """The rerun (the sweep's first 12 requests, to stay quick) keeps 6 of the 60 tracks: a
    signal leaves the old library byte for byte, or (landing after the swap) the new one
    whole; the sources are never touched."""
    import shutil

    shutil.copytree(catalog_library, tmp_path, dirs_exist_ok=True)
    tracks = tmp_path / "tracks"
    before = _tree(tmp_path)
    t0 = time.time()

    def started() -> bool:  # a track of this run is written, wherever this code writes it
        specs = [*tracks.glob("generated/*/spec.json"), *tracks.glob(".generated.*/*/spec.json")]
        return any(p.stat().st_mtime >= t0 for p in specs if p.exists())

    args = ["tracks", "catalog", "--tracks", "tracks", "--sources", "src", "--generate", "--count", "6"]
    code, err = _interrupt(_cli([*args, "--max-requests", "12", "--jobs", "1"], tmp_path), started, run, 1.0)
    assert code in AFTER_SIGNAL, err[-800:]
    if code in (0, 130):
        assert "Traceback" not in err, err[-800:]
    assert not any((tmp_path / "src").iterdir())  # the input folder
    assert _strays(tracks) == [] and _strays(tracks / "generated") == []
    assert _tree(tmp_path) == before or _catalog_whole(tracks, 6)
