"""``roboracer-arena generate`` / ``validate`` end to end: exit codes 0/2/3 with --json,
one-line errors for bad spec files."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from roboracer_arena import TrackSpec
from roboracer_arena.cli import main

SMALL = TrackSpec(name="cli-small", lap_length_m=40, hall_x_m=15, hall_y_m=12, hairpins=1)


def _write(tmp_path, spec: TrackSpec, name="spec.json"):
    p = tmp_path / name
    p.write_text(spec.model_dump_json())
    return p


def test_generate_accepts_with_exit_0_and_validate_agrees(tmp_path, capsys):
    spec = _write(tmp_path, SMALL)
    out = tmp_path / "out"
    assert main(["generate", "--spec", str(spec), "--seed", "1", "-o", str(out), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["outcome"] == "accepted" and all(c["passed"] for c in summary["checks"])
    for key in ("map_yaml", "map_png", "centreline_csv", "spec_json", "report_json"):
        assert (out / summary["files"][key].split("/")[-1]).is_file(), key
    assert main(["validate", str(out / "map.yaml"), "--spec", str(spec), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["valid"] is True
    # The same map against another spec: some check fails, exit 4.
    other = _write(tmp_path, SMALL.model_copy(update={"lap_length_m": 55.0}), "other.json")
    assert main(["validate", str(out / "map.yaml"), "--spec", str(other)]) == 4
    assert "BAD lap_length" in capsys.readouterr().out


def test_generate_rejects_with_exit_3(tmp_path, capsys):
    spec = _write(tmp_path, TrackSpec(lap_length_m=200))
    assert main(["generate", "--spec", str(spec), "-o", str(tmp_path / "o"), "--json"]) == 3
    summary = json.loads(capsys.readouterr().out)
    assert summary["outcome"] == "rejected"
    assert "L_max = 123.7 m" in summary["violations"][0]
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(
    "content, needles",
    [
        (None, ["missing.json", "cannot read"]),
        ('{"lap_length_m": 40,', ["bad.json", "not valid JSON"]),
        ('{"lap_length_m": -3}', ["bad.json", "lap_length_m"]),
        ('{"hairpins": -1}', ["bad.json", "hairpins"]),
        ('{"lap_length_m": 40, "colour": "red"}', ["bad.json", "colour", "Extra inputs"]),
        ("[1, 2]", ["bad.json", "JSON object"]),
    ],
)
def test_bad_spec_file_exits_2_with_one_line(tmp_path, capsys, content, needles):
    path = tmp_path / ("missing.json" if content is None else "bad.json")
    if content is not None:
        path.write_text(content)
    assert main(["generate", "--spec", str(path), "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert err.startswith("roboracer-arena generate: error:")
    for n in needles:
        assert n in err
    assert main(["validate", str(tmp_path / "nomap.yaml"), "--spec", str(path)]) == 2


def test_console_script_runs(tmp_path):
    spec = _write(tmp_path, TrackSpec(lap_length_m=200))
    exe = [str(Path(sys.executable).parent / "roboracer-arena")]
    r = subprocess.run([*exe, "generate", "--spec", str(spec), "--json"], capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 3, r.stderr
    assert json.loads(r.stdout)["outcome"] == "rejected"
