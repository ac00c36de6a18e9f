"""TUM CSV and ForzaETH JSON: written atomically, read back equal, malformed refused."""

from __future__ import annotations

import json

import numpy as np
import pytest

from roboracer_arena.raceline import RacelineFormatError, read_forza_json, read_tum_csv
from roboracer_arena.raceline.export import raceline_csv_text, raceline_forza_text, write_outputs
from roboracer_arena.raceline.forza_json import REQUIRED_KEYS, WPNT_FIELDS


def test_tum_csv_round_trip(stadium_line, tmp_path):
    (p,) = write_outputs([(tmp_path / "raceline.csv", raceline_csv_text(stadium_line))])
    lines = p.read_text().splitlines()
    assert lines[0].startswith("# ") and len(lines[0]) == 2 + 36  # uuid
    assert lines[1] == "# " + stadium_line.limits.sha1()
    assert lines[2] == "# s_m; x_m; y_m; psi_rad; kappa_radpm; vx_mps; ax_mps2"
    t = read_tum_csv(p)
    n = len(stadium_line.s)
    assert len(t.s) == n + 1 and np.isclose(t.s[-1], stadium_line.length, atol=1e-6)
    assert np.allclose(t.x[:n], stadium_line.xy[:, 0], atol=1e-6) and np.allclose(t.vx[:n], stadium_line.vx, atol=1e-6)
    assert ((t.psi >= 0) & (t.psi < 2 * np.pi + 1e-6)).all()
    assert np.isclose(t.lap_time, stadium_line.lap_time, rtol=1e-5)
    assert raceline_csv_text(stadium_line) == p.read_text()  # deterministic, uuid included


def test_forza_json_round_trip(stadium_line, oval, tmp_path):
    (p,) = write_outputs([(tmp_path / "global_waypoints.json", raceline_forza_text(stadium_line, oval))])
    doc = json.loads(p.read_text())
    assert set(REQUIRED_KEYS) <= set(doc)
    assert set(doc["global_traj_wpnts_iqp"]["wpnts"][0]) == set(WPNT_FIELDS)
    w = read_forza_json(p)
    assert np.isclose(w.est_lap_time, stadium_line.lap_time, atol=1e-3)
    assert np.allclose(w.raceline["vx_mps"], stadium_line.vx, atol=1e-6)
    across = w.raceline["d_left"] + w.raceline["d_right"]  # the stadium is 1.6 m wide: more where the line is oblique
    assert across.min() > 1.55 and abs(np.median(across) - 1.6) < 0.05
    assert "estimated lap time" in w.map_info_str


@pytest.mark.parametrize(
    "text, why",
    [
        ("", "no column header"),
        ("# a\n# b\n# s_m; x_m; y_m\n1;2;3\n", "columns are"),
        ("# s_m; x_m; y_m; psi_rad; kappa_radpm; vx_mps; ax_mps2\n" + "0;0;0;0;0;1\n" * 5, "6 values"),
        ("# s_m; x_m; y_m; psi_rad; kappa_radpm; vx_mps; ax_mps2\n" + "0;0;0;0;0;x;0\n" * 5, "not a number"),
        ("# s_m; x_m; y_m; psi_rad; kappa_radpm; vx_mps; ax_mps2\n" + "0;0;0;0;0;1;0\n" * 5, "increase strictly"),
        ("1;2;3;4;5;6;7\n", "before the column header"),
        ("# s_m; x_m; y_m; psi_rad; kappa_radpm; vx_mps; ax_mps2\n0;0;0;0;0;nan;0\n", "not finite"),
    ],
)
def test_tum_reader_refuses_malformed_files(tmp_path, text, why):
    p = tmp_path / "bad.csv"
    p.write_text(text)
    with pytest.raises(RacelineFormatError, match=why) as e:
        read_tum_csv(p)
    assert str(p) in str(e.value)


@pytest.mark.parametrize(
    "mutate, why",
    [
        (lambda d: d.pop("est_lap_time"), "missing est_lap_time"),
        (lambda d: d.__setitem__("est_lap_time", {"data": "fast"}), "est_lap_time.data"),
        (lambda d: d["global_traj_wpnts_iqp"]["wpnts"][3].__setitem__("vx_mps", None), r"wpnts\[3\].vx_mps"),
        (lambda d: d.__setitem__("trackbounds_markers", []), "trackbounds_markers"),
        (lambda d: d["global_traj_wpnts_iqp"].__setitem__("wpnts", []), "a line needs at least 4"),
    ],
)
def test_forza_reader_refuses_malformed_files(stadium_line, oval, tmp_path, mutate, why):
    doc = json.loads(raceline_forza_text(stadium_line, oval))
    mutate(doc)
    p = tmp_path / "global_waypoints.json"
    p.write_text(json.dumps(doc))
    with pytest.raises(RacelineFormatError, match=why):
        read_forza_json(p)
    p.write_text("{not json")
    with pytest.raises(RacelineFormatError, match="not valid JSON"):
        read_forza_json(p)


def test_outputs_appear_together_or_not_at_all(tmp_path):
    (tmp_path / "blocker").write_text("a file where a folder should be")
    from roboracer_arena.errors import ArenaError

    with pytest.raises(ArenaError):
        write_outputs([(tmp_path / "a.csv", "x"), (tmp_path / "blocker" / "b.json", "y")])
    assert not (tmp_path / "a.csv").exists()
