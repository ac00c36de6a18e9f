"""Atomic multi-file output, output-path checks and regular-file input (fileio.py)."""

from __future__ import annotations

import os

import pytest

from roboracer_arena.errors import InvalidArgumentError, MapIOError
from roboracer_arena.foundation.fileio import atomic_path, atomic_paths, check_output, read_regular_bytes, read_text


def test_all_files_appear_or_none(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "sub" / "b.txt"
    with atomic_paths([a, b]) as (ta, tb):
        ta.write_text("A")
        tb.write_text("B")
        assert not a.exists() and not b.exists()  # nothing visible before the commit
    assert (a.read_text(), b.read_text()) == ("A", "B")

    c, d = tmp_path / "c.txt", tmp_path / "new" / "deeper" / "d.txt"
    with pytest.raises(RuntimeError):
        with atomic_paths([c, d]) as (tc, td):
            tc.write_text("C")
            raise RuntimeError("fails half way")
    assert not c.exists() and not (tmp_path / "new").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "sub"]


def test_a_failed_rename_rolls_back_the_files_it_created(tmp_path):
    (tmp_path / "second.txt").write_text("old")
    with pytest.raises(MapIOError):
        with atomic_paths([tmp_path / "first.txt", tmp_path / "second.txt"]) as (t1, t2):
            t1.write_text("1")
            t2.write_text("2")
            os.unlink(t2)
            os.mkdir(t2)  # the second rename now fails (a directory cannot replace a file)
    assert not (tmp_path / "first.txt").exists()
    assert (tmp_path / "second.txt").read_text() == "old"


def test_temporaries_are_exclusive_short_and_unpredictable(tmp_path):
    target = tmp_path / ("x" * 255)
    names = set()
    for _ in range(3):
        with atomic_path(target) as tmp:
            assert tmp.parent == tmp_path and len(tmp.name) < 40 and "x" * 20 not in tmp.name
            assert tmp.stat().st_mode & 0o777 == 0o600  # created by mkstemp (O_EXCL)
            names.add(tmp.name)
            tmp.write_text("ok")
    assert len(names) == 3 and target.read_text() == "ok"


def test_check_output_refuses_what_cannot_be_written(tmp_path):
    (tmp_path / "d").mkdir()
    with pytest.raises(MapIOError, match="is a directory"):
        check_output(tmp_path / "d")
    with pytest.raises(MapIOError, match="255 bytes"):
        check_output(tmp_path / ("x" * 256))
    (tmp_path / "f").write_text("")
    with pytest.raises(MapIOError, match="not a directory"):
        check_output(tmp_path / "f" / "out.png")
    src = tmp_path / "map.yaml"
    src.write_text("")
    with pytest.raises(InvalidArgumentError, match="overwrite the input"):
        check_output(tmp_path / "." / "map.yaml", inputs=[src])


def test_inputs_must_be_regular_files(tmp_path):
    fifo = tmp_path / "p"
    os.mkfifo(fifo)
    with pytest.raises(MapIOError, match="FIFO"):
        read_regular_bytes(fifo, "spec")
    with pytest.raises(MapIOError, match="device"):
        read_regular_bytes("/dev/zero", "spec")
    with pytest.raises(MapIOError, match="directory"):
        read_regular_bytes(tmp_path, "spec")
    (tmp_path / "loop").symlink_to(tmp_path / "loop")
    with pytest.raises(MapIOError, match="symlink loop"):
        read_regular_bytes(tmp_path / "loop", "spec")
    big = tmp_path / "big"
    big.write_bytes(b"x" * 100)
    with pytest.raises(MapIOError, match="100 bytes"):
        read_regular_bytes(big, "spec", max_bytes=10)
    u16 = tmp_path / "u16.json"
    u16.write_text("{}", encoding="utf-16")
    with pytest.raises(MapIOError, match="UTF-16"):
        read_text(u16, "spec")
