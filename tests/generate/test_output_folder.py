"""``generate -o DIR`` output folder (issue 10): it appears whole or not at all, replaces
an earlier generate output (no stale stage left for ``preview``), and a file or a foreign
folder at DIR is refused with exit 2 and one line."""

import json

import pytest

from roboracer_arena import TrackSpec
from roboracer_arena.cli import main
from roboracer_arena.errors import InvalidArgumentError
from roboracer_arena.generate import generate_track
from roboracer_arena.generate.outputs import output_folder, write_outputs

SPEC = TrackSpec(name="out-small", lap_length_m=40, hall_x_m=15, hall_y_m=12, hairpins=1)


def _spec_file(tmp_path):
    p = tmp_path / "spec.json"
    p.write_text(SPEC.model_dump_json())
    return p


@pytest.mark.slow
def test_rerun_without_build_removes_the_stale_stage(tmp_path, capsys):
    spec, out = _spec_file(tmp_path), tmp_path / "out"
    assert main(["generate", "--spec", str(spec), "-o", str(out), "--build", "--json"]) == 0
    assert (out / "track.usda").is_file()
    assert main(["generate", "--spec", str(spec), "-o", str(out), "--seed", "1", "--json"]) == 0
    capsys.readouterr()
    assert not (out / "track.usda").exists() and not (out / "textures").exists()
    assert sorted(p.name for p in out.iterdir()) == [
        "centreline.csv",
        "map.png",
        "map.yaml",
        "report.json",
        "spec.json",
    ]
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []  # no temp folders left


def test_out_naming_a_file_exits_2_with_one_line(tmp_path, capsys):
    target = tmp_path / "taken.txt"
    target.write_text("keep me")
    assert main(["generate", "--spec", str(_spec_file(tmp_path)), "-o", str(target)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "is not a directory" in err
    assert target.read_text() == "keep me"


def test_foreign_folder_is_refused_and_untouched(tmp_path, capsys):
    d = tmp_path / "mine"
    d.mkdir()
    (d / "notes.txt").write_text("x")
    assert main(["generate", "--spec", str(_spec_file(tmp_path)), "-o", str(d)]) == 2
    assert "did not write" in capsys.readouterr().err
    assert [p.name for p in d.iterdir()] == ["notes.txt"]


def test_a_failure_inside_the_folder_leaves_nothing(tmp_path):
    acc = generate_track(SPEC)
    out = tmp_path / "out"
    with pytest.raises(RuntimeError):
        with output_folder(out) as tmp:
            write_outputs(acc, tmp)
            raise RuntimeError("a later write fails")
    assert not out.exists() and list(tmp_path.iterdir()) == []
    # An earlier output survives a failed rewrite whole.
    with output_folder(out) as tmp:
        write_outputs(acc, tmp)
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    with pytest.raises(RuntimeError), output_folder(out) as tmp:
        (tmp / "map.yaml").write_text("half")
        raise RuntimeError("boom")
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_output_folder_refuses_a_file_before_any_work(tmp_path):
    f = tmp_path / "f"
    f.write_text("")
    with pytest.raises(InvalidArgumentError, match="not a directory"):
        with output_folder(f):
            pass
    assert json.dumps(sorted(p.name for p in tmp_path.iterdir())) == '["f"]'
