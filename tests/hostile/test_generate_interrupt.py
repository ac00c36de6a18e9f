"""Class 7: an interrupted ``tracks generate`` used to corrupt an existing library (the
catalog described the old tracks while some folders were already new, so ``tracks
verify`` failed their checksums) and, on a fresh folder, to leave track folders and no
catalog. The library is now staged and swapped in whole: a signal at any moment leaves
the previous library byte for byte (or no library) and no staging folder."""

from __future__ import annotations

import hashlib
import json
import signal
import time
from pathlib import Path

import pytest

from .conftest import cli, strays

pytestmark = [pytest.mark.slow, pytest.mark.timeout(300)]

SWEEP = {
    "name": "t",
    "base_seed": 7,
    "ranges": {"lap_length_m": [30, 45], "hairpins": [0, 1]},
    "fixed": {"corridor_width_m": 1.5, "hall_x_m": 15, "hall_y_m": 12},
}


def tree(root: Path) -> dict[str, str]:
    return {
        str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest() for p in root.rglob("*") if p.is_file()
    }


def _wait_for_a_new_track(tmp_path: Path, proc, timeout: float = 120.0) -> None:
    """Until the run has written a track of its own, wherever it writes (mid-run)."""
    t0 = time.time()
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and proc.poll() is None:
        specs = [*tmp_path.glob("*/generated/t-*/spec.json"), *tmp_path.glob(".*/generated/t-*/spec.json")]
        if any(s.stat().st_mtime >= t0 for s in specs if s.exists()):
            return
        time.sleep(0.05)
    pytest.fail("the run never wrote a track")


def _generate(tmp_path: Path, out: Path, count: int, base_seed: int) -> object:
    sweep = tmp_path / f"sweep{base_seed}.json"
    sweep.write_text(json.dumps({**SWEEP, "base_seed": base_seed}))
    return cli("tracks", "generate", "--sweep", str(sweep), "--count", str(count), "-o", str(out), "--jobs", "1")


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_an_interrupted_rerun_leaves_the_old_library_whole(tmp_path, sig):
    out = tmp_path / "lib"
    p = _generate(tmp_path, out, 2, 7)
    _, err = p.communicate(timeout=240)
    assert p.returncode == 0, err
    (out / "generated" / "mine.txt").write_text("a file of the user's")
    before = tree(out)
    p = _generate(tmp_path, out, 30, 8)  # another library into the same folder
    _wait_for_a_new_track(tmp_path, p)
    p.send_signal(sig)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130 and "Traceback" not in err, err
    assert tree(out) == before and strays(tmp_path) == []
    from roboracer_arena.catalog.catalog_file import load_catalog, sha256_file

    cat = load_catalog(out / "catalog.json")  # and it still verifies: catalog == folders
    assert all(sha256_file(out / Path(e.map).parent / "map.png") == e.sha256 for e in cat.entries)


def test_an_interrupted_first_run_leaves_nothing(tmp_path):
    out = tmp_path / "fresh"
    p = _generate(tmp_path, out, 30, 7)
    _wait_for_a_new_track(tmp_path, p)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    assert not out.exists() and strays(tmp_path) == []
