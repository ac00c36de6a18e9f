"""Classes 10 and 13: catalog entries are range-checked on load (empty sha256, lap length
0 or NaN, raster size, resolution and widths), ids use a safe character set, map paths
stay inside the library; and ``tracks verify`` compares the raster size and resolution,
so a tampered catalog fails instead of passing with exit 0."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from roboracer_arena.catalog.catalog_file import default_tracks_dir, load_catalog
from roboracer_arena.cli import main


@pytest.fixture
def small_catalog(tmp_path) -> Path:
    """The shipped catalog cut to one generated track, copied with its files."""
    doc = json.loads((default_tracks_dir() / "catalog.json").read_text())
    e = next(t for t in doc["tracks"] if t["kind"] == "generated")
    src = default_tracks_dir() / Path(e["map"]).parent
    shutil.copytree(src, tmp_path / Path(e["map"]).parent)
    doc.update(tracks=[e], left_out=[], count=1)
    (tmp_path / "catalog.json").write_text(json.dumps(doc))
    return tmp_path / "catalog.json"


def _tamper(path: Path, **fields) -> None:
    doc = json.loads(path.read_text())
    e = doc["tracks"][0]
    for k, v in fields.items():
        if k == "raster":
            e["raster"] = {**e["raster"], **v}
        else:
            e[k] = v
    path.write_text(json.dumps(doc, allow_nan=True))


def test_the_shipped_catalog_loads():
    assert len(load_catalog().entries) > 0


@pytest.mark.parametrize(
    "fields,says",
    [
        ({"sha256": ""}, "sha256"),
        ({"lap_length_m": 0}, "lap_length_m"),
        ({"lap_length_m": float("nan")}, "lap_length_m"),
        ({"resolution_m": -0.05}, "resolution_m"),
        ({"width_min_m": 0}, "width_min_m"),
        ({"width_mean_m": 1e9}, "width_mean_m"),
        ({"raster": {"width_px": 0}}, "width_px"),
        ({"raster": {"height_px": 10**9}}, "height_px"),
        ({"id": "evil\nid\x1b[31m"}, "id"),
        ({"id": "../up"}, "id"),
        ({"map": "/etc/passwd"}, "map"),
        ({"map": "../../outside/map.yaml"}, "map"),
        ({"centreline": "generated/../../x.csv"}, "centreline"),
    ],
)
def test_a_tampered_entry_is_refused_on_load_with_exit_2(small_catalog, capsys, fields, says):
    _tamper(small_catalog, **fields)
    assert main(["tracks", "list", "--catalog", str(small_catalog)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and says in err and "\x1b" not in err, err


@pytest.mark.parametrize(
    "fields", [{"raster": {"width_px": 7}}, {"resolution_m": 0.07}, {"sha256": "0" * 64}, {"lap_length_m": 500.0}]
)
def test_verify_fails_a_plausible_but_false_entry(small_catalog, capsys, fields):
    _tamper(small_catalog, **fields)
    code = main(["tracks", "verify", "--catalog", str(small_catalog), "--no-usd", "--no-drive", "--jobs", "1"])
    assert code != 0, capsys.readouterr()
