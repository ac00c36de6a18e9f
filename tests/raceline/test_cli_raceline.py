"""``roboracer-arena raceline``: outputs, the JSON summary and exit 2 on bad input."""

from __future__ import annotations

import json

from roboracer_arena.cli import EXIT_BAD_INPUT, EXIT_OK, main
from roboracer_arena.raceline import read_forza_json, read_tum_csv

SMALL = "gen-l040-w12-h2c1s1-clo-s0"  # a 40 m generated track from the catalog


def test_raceline_writes_every_output(tmp_path, capsys):
    assert main(["raceline", SMALL, "--out", str(tmp_path / "out"), "--json"]) == EXIT_OK
    summary = json.loads(capsys.readouterr().out)
    assert summary["track"] == SMALL and summary["lap_time_s"] > 0 and len(summary["outputs"]) == 3
    t = read_tum_csv(tmp_path / "out" / "raceline.csv")
    w = read_forza_json(tmp_path / "out" / "global_waypoints.json")
    assert abs(t.lap_time - summary["lap_time_s"]) < 1e-3 and abs(w.est_lap_time - summary["lap_time_s"]) < 1e-3
    assert (tmp_path / "out" / "raceline.png").read_bytes()[:4] == b"\x89PNG"


def test_raceline_limits_presets_and_flags(tmp_path, capsys):
    assert main(["raceline", SMALL, "--limits", "forzaeth", "--v-max", "3", "--json"]) == EXIT_OK
    out = json.loads(capsys.readouterr().out)
    assert out["v_max_mps"] <= 3.0 and "forzaeth" in out["limits"]


def test_raceline_bad_input_exits_2(tmp_path, capsys):
    bad = tmp_path / "bad.json"
    bad.write_text('{"v_max": 8, "ggv": [[0, 5]], "ax_max_machines": [[0, 3]]}')
    cases = [
        ["raceline", SMALL, "--limits", str(bad)],
        ["raceline", SMALL, "--limits", str(tmp_path / "missing.json")],
        ["raceline", "no-such-track"],
        ["raceline", SMALL, "--margin", "-1"],
        ["raceline", SMALL, "--png", str(tmp_path / "x.bmp")],
        ["raceline"],
    ]
    for argv in cases:
        assert main(argv) == EXIT_BAD_INPUT, argv
        err = capsys.readouterr().err.strip()
        assert err.startswith("roboracer-arena raceline: error:") and "\n" not in err, err
    assert not list(tmp_path.glob("*.png"))


def test_catalog_job_never_writes_into_an_installed_package(monkeypatch, capsys, tmp_path):
    from roboracer_arena.foundation import paths

    monkeypatch.delenv(paths.TRACKS_ENV, raising=False)
    monkeypatch.setattr(paths, "checkout_dir", lambda: None)  # as an installed wheel
    assert main(["raceline", "--catalog", SMALL]) == EXIT_BAD_INPUT
    assert "--tracks DIR is required" in capsys.readouterr().err
    assert main(["raceline", "--catalog", SMALL, "--tracks", str(tmp_path), "--json"]) == EXIT_OK
    assert json.loads(capsys.readouterr().out)["driver_clean"] == 1
    assert (tmp_path / "racelines.json").is_file()
