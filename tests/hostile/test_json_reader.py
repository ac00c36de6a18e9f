"""Class 5: a 5 KB JSON file with a 5000-digit integer raised a traceback (exit 1) in
every JSON reader. One reader (``fileio.parse_json``) now turns it into a one-line typed
error (exit 2) for spec, validate, sweep, catalog, build and bridge config files."""

from __future__ import annotations

import pytest

from roboracer_arena.cli import main

BIG = "9" * 5000


@pytest.mark.parametrize(
    "make_argv",
    [
        lambda d, m: ["generate", "--spec", str(d / "f.json"), "-o", str(d / "o")],
        lambda d, m: ["validate", str(m), "--spec", str(d / "f.json")],
        lambda d, m: ["tracks", "generate", "--sweep", str(d / "f.json"), "--count", "1", "-o", str(d / "o")],
        lambda d, m: ["tracks", "list", "--catalog", str(d / "f.json")],
        lambda d, m: ["build", str(m), "-o", str(d / "o.usdc"), "--config", str(d / "f.json")],
        lambda d, m: ["ros2", str(m), "--config", str(d / "f.json"), "--sim-time", "0.1", "--loopback"],
    ],
    ids=["spec", "validate", "sweep", "catalog", "build-config", "bridge-config"],
)
def test_a_5000_digit_integer_is_a_one_line_error(tmp_path, ellipse_map, capsys, make_argv):
    (tmp_path / "f.json").write_text('{"lap_length_m": ' + BIG + ', "rates": {"scan_hz": ' + BIG + "}}")
    assert main(make_argv(tmp_path, ellipse_map)) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "f.json" in err and "Traceback" not in err, err
    assert "digit" in err or "number" in err
