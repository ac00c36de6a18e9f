"""Issue 38, classes C and F for outputs.

* The demo's ``--out`` naming an existing file, a folder under a file, or a read-only
  folder is refused (exit 2, one line) before any work.
* A full disk during ``build`` is one line and exit 2 naming the file being written
  (usd-core's ``Tf.ErrorException`` and an ``OSError`` ENOSPC alike), and no partial stage
  or temporary file is left.

A read-only folder and a full disk are real here when the test may mount a small tmpfs
(root in a container); else those cases are skipped (root ignores file permissions) and
the write path is driven by a file-size limit instead (``RLIMIT_FSIZE``: a real failed
write, EFBIG).
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from roboracer_arena import demo
from roboracer_arena.errors import MapIOError
from roboracer_arena.foundation.fileio import write_failure


def _mount_tmpfs(where: Path, options: str) -> bool:
    where.mkdir(parents=True, exist_ok=True)
    if os.geteuid() != 0:
        return False
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(where)], capture_output=True)
    return r.returncode == 0


@pytest.fixture
def tmpfs(tmp_path):
    mounted: list[Path] = []

    def make(name: str, options: str) -> Path:
        d = tmp_path / name
        if not _mount_tmpfs(d, options):
            pytest.skip("cannot mount a tmpfs here (needs root in a container that allows it)")
        mounted.append(d)
        return d

    yield make
    for d in mounted:
        subprocess.run(["umount", "-l", str(d)], capture_output=True)


def test_demo_out_an_existing_file_is_refused_before_any_work(tmp_path, capsys):
    f = tmp_path / "taken"
    f.write_text("mine")
    for out in (f, f / "sub"):
        t0 = time.perf_counter()
        assert demo.main(["--out", str(out)]) == 2
        assert time.perf_counter() - t0 < 5  # no parse, no generation
        captured = capsys.readouterr()
        assert captured.err.count("\n") == 1 and "taken" in captured.err and "directory" in captured.err
        assert "== parse" not in captured.out
    assert f.read_text() == "mine"


def test_demo_out_a_read_only_folder_is_refused_before_any_work(tmpfs, capsys):
    ro = tmpfs("ro", "ro,size=64k")
    t0 = time.perf_counter()
    assert demo.main(["--out", str(ro / "demo")]) == 2
    assert time.perf_counter() - t0 < 5
    captured = capsys.readouterr()
    assert captured.err.count("\n") == 1 and "not writable" in captured.err, captured.err
    assert "== parse" not in captured.out


def test_a_full_disk_during_build_names_the_file(tmpfs, ellipse_map, capsys):
    from roboracer_arena.cli import main

    full = tmpfs("full", "size=48k")
    out = full / "stage.usda"
    assert main(["build", str(ellipse_map), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "stage.usda" in err and ("no space left" in err or "cannot write" in err), err
    assert not list(full.iterdir()), list(full.iterdir())  # no partial stage, no temporary


def test_a_failed_stage_write_names_the_file_under_a_size_limit(ellipse_map, tmp_path):
    """A real write failure through usd-core in a child process: ``RLIMIT_FSIZE`` makes
    the stage's write fail half-way (EFBIG); the command says which file, exits 2, and
    leaves nothing."""
    out = tmp_path / "o" / "stage.usda"
    code = (
        "import resource, signal, sys\n"
        "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
        "from roboracer_arena.cli import main\n"
        "resource.setrlimit(resource.RLIMIT_FSIZE, (20000, 20000))\n"
        f"sys.exit(main(['build', {str(ellipse_map)!r}, '-o', {str(out)!r}]))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 2, r.stderr[-2000:]
    assert r.stderr.count("\n") == 1 and "stage.usda" in r.stderr and "Traceback" not in r.stderr, r.stderr
    assert not (out.parent.exists() and list(out.parent.iterdir()))


def test_write_failure_names_the_target_and_the_reason():
    import errno

    e = write_failure("/x/stage.usdc", OSError(errno.ENOSPC, "No space left on device", "/x/.arena-1.usdc"))
    assert (
        isinstance(e, MapIOError)
        and str(e) == "/x/stage.usdc: cannot write: no space left on the device (the disk is full)"
    )
    tf = RuntimeError("\tError in 'SdfLayer::Export': Failed to write: No space left on device\n")
    assert "no space left" in str(write_failure("/x/s.usda", tf))


def test_generate_out_holding_a_hostile_report_is_refused_not_a_traceback(tmp_path, capsys):
    """``generate -o DIR`` reads DIR's report.json to tell an earlier output from someone
    else's folder: nested 100 000 deep it was a RecursionError traceback."""
    from roboracer_arena.cli import main

    d = tmp_path / "out"
    d.mkdir()
    (d / "report.json").write_text("[" * 100_000 + "]" * 100_000)
    assert main(["generate", "a 40 m lap", "-o", str(d)]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and "did not write" in err.strip().splitlines()[-1], err


def test_a_catalog_rebuild_names_a_hostile_generated_spec(tmp_path):
    """``tracks catalog`` reads each generated track's spec.json and report.json with the
    one JSON reader: another shape is one line naming the folder."""
    import shutil

    from roboracer_arena.errors import MapFormatError
    from roboracer_arena.foundation.paths import PACKAGE_DIR
    from roboracer_arena.library.index import _generated_entries

    src = next((PACKAGE_DIR / "tracks" / "generated").iterdir())
    dst = tmp_path / "generated" / src.name
    shutil.copytree(src, dst)
    assert len(_generated_entries(tmp_path)) == 1
    for text in ("[1, 2]", '{"name": "x"}', "[" * 5000 + "]" * 5000):
        (dst / "spec.json").write_text(text)
        with pytest.raises(MapFormatError, match=src.name):
            _generated_entries(tmp_path)
