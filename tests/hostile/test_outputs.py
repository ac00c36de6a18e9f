"""Classes 2, 3 and 12: one output guard for every command that writes, checked before
any work (inputs and the files they name are refused as targets; a directory, a file
used as a parent or an unwritable place fails at once with exit 2 and no temporary),
and recordings created with the umask's permissions like every other output."""

from __future__ import annotations

import hashlib
import os
import time
from pathlib import Path

import pytest

from benchmarks.__main__ import main as benchmarks_main
from roboracer_arena.cli import main

from .conftest import strays


def _digest(p: Path) -> str:
    return hashlib.sha256(p.read_bytes()).hexdigest()


def _image(map_yaml: Path) -> Path:
    from roboracer_arena.foundation.fileio import image_named_by

    return map_yaml.parent / image_named_by(map_yaml.read_text())


@pytest.fixture
def map_copy(ellipse_map, tmp_path) -> Path:
    for p in (ellipse_map, _image(ellipse_map)):
        (tmp_path / p.name).write_bytes(p.read_bytes())
    return tmp_path / ellipse_map.name


# -- class 2: outputs never overwrite inputs, including the files inputs name ----------


@pytest.mark.parametrize(
    "argv",
    [
        lambda m, img: ["drive", str(m), "--mcap", str(img)],  # the image the YAML names
        lambda m, img: ["drive", str(m), "--gif", str(img)],
        lambda m, img: ["ros2", str(m), "--record", str(m)],  # no check at all before
        lambda m, img: ["ros2", str(m), "--record", str(img)],
        lambda m, img: ["preview", str(m), "-o", str(img)],
    ],
    ids=["drive-mcap-image", "drive-gif-image", "ros2-record-yaml", "ros2-record-image", "preview-image"],
)
def test_an_output_onto_an_input_or_its_image_exits_2_and_leaves_it(map_copy, capsys, argv):
    img = _image(map_copy)
    before = (_digest(map_copy), _digest(img))
    t0 = time.perf_counter()
    assert main(argv(map_copy, img)) == 2
    assert time.perf_counter() - t0 < 5.0  # refused before any work
    assert "would overwrite the input" in capsys.readouterr().err
    assert (_digest(map_copy), _digest(img)) == before and strays(map_copy.parent) == []


def test_bench_json_onto_its_requests_file_exits_2(tmp_path, capsys):
    req = tmp_path / "requests.jsonl"
    req.write_text('{"text": "a 40 m lap"}\n')
    before = req.read_bytes()
    assert benchmarks_main(["parser", "--requests", str(req), "--json", str(req)]) == 2
    assert "would overwrite the input" in capsys.readouterr().err and req.read_bytes() == before


# -- class 3: bad targets fail fast, exit 2, nothing left behind ----------------------


@pytest.mark.parametrize("kind", ["directory", "file-as-parent", "unwritable"])
@pytest.mark.parametrize("cmd", ["drive", "ros2"])
def test_a_bad_recording_target_fails_before_the_run(map_copy, tmp_path, capsys, kind, cmd):
    if kind == "directory":
        target = tmp_path / "adir"
        target.mkdir()
    elif kind == "file-as-parent":
        (tmp_path / "afile").write_text("x")
        target = tmp_path / "afile" / "run.mcap"
    else:  # root writes anywhere a mode bit says no; a read-only file system refuses even root
        target = Path("/proc/run.mcap")
    flag = "--mcap" if cmd == "drive" else "--record"
    extra = ["--laps", "1"] if cmd == "drive" else ["--sim-time", "0.5", "--loopback"]
    t0 = time.perf_counter()
    assert main([cmd, str(map_copy), flag, str(target), *extra]) == 2
    assert time.perf_counter() - t0 < 5.0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and str(target) in err
    assert [p for p in strays(tmp_path) if p != ".pytest"] == []


def test_the_bridge_api_checks_its_recording_before_building_anything(map_copy, tmp_path):
    from roboracer_arena.errors import MapIOError
    from roboracer_arena.ros2.bridge import Bridge

    (tmp_path / "afile").write_text("x")
    with pytest.raises(MapIOError, match="not a directory"):
        Bridge(str(map_copy), record=tmp_path / "afile" / "x.mcap", dds=False)


# -- class 12: recordings follow the umask ---------------------------------------------


def test_recordings_follow_the_umask(map_copy, tmp_path):
    pytest.importorskip("mcap")
    from roboracer_arena.ros2.recorder import McapRecorder

    old = os.umask(0o022)
    try:
        rec = McapRecorder(tmp_path / "r.mcap")
        rec.close()
    finally:
        os.umask(old)
    assert (tmp_path / "r.mcap").stat().st_mode & 0o777 == 0o644
