"""``bench constructors``: trial counting (screen rejections are not trials), built/valid
from the written map, the CLI's table and JSON."""

import json

import pytest

from benchmarks import constructors as bc
from benchmarks.__main__ import main
from roboracer_arena.errors import SpecError

SPECS = [
    '{"name": "small", "lap_length_m": 40, "hall_x_m": 15, "hall_y_m": 12, "hairpins": 1}',
    '{"name": "too-long", "lap_length_m": 200}',
]


def test_rejected_specs_are_not_trials_and_lattice_builds_valid_maps(tmp_path):
    path = tmp_path / "specs.jsonl"
    path.write_text("\n".join(SPECS) + "\n\n")
    result = bc.run(bc.load_specs(path), [0, 1], ["lattice", "lattice-raw", "random"], progress=False)
    assert result.admissible_specs == 1
    assert [r.spec for r in result.screen_rejections] == ["too-long"]
    by = {s.constructor: s for s in result.summary}
    assert all(s.trials == 2 for s in by.values())
    assert by["lattice"].built == by["lattice"].valid == 2
    assert by["random"].built == 2  # random always emits a map
    for row in result.trials:
        assert row.valid <= row.built and row.seconds > 0


def test_cli_prints_the_table_and_writes_json(tmp_path, capsys):
    path = tmp_path / "specs.jsonl"
    path.write_text("\n".join(SPECS))
    out = tmp_path / "r.json"
    code = main(
        [
            "constructors",
            "--specs",
            str(path),
            "--seeds",
            "0",
            "--constructors",
            "lattice",
            "random",
            "--json",
            str(out),
        ]
    )
    assert code == 0
    text = capsys.readouterr().out
    assert "valid trials" in text and "21/30  21/21  3.7 s" in text and "rejected too-long" in text
    data = json.loads(out.read_text())
    assert [s["constructor"] for s in data["summary"]] == ["lattice", "random"]


@pytest.mark.parametrize("line, needle", [('{"lap_length_m": -1}', "lap_length_m"), ("{oops", "not valid JSON")])
def test_bad_spec_lines_name_file_and_line(tmp_path, line, needle):
    path = tmp_path / "specs.jsonl"
    path.write_text(SPECS[0] + "\n" + line + "\n")
    with pytest.raises(SpecError, match=rf"specs.jsonl:2: .*{needle}"):
        bc.load_specs(path)
