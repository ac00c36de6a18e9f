"""THE ALL-MAPS TEST: every ROS map in the shared track sources (``map-inventory.csv``)
either builds into a valid stage whose collision walls reproduce the corridor (IoU ≥ 0.97),
or is refused with the reason that is right for that map. A map refused as a track for
having no closed corridor builds as an open map (walls only) by default, its report
naming that reason, and is refused only with ``open=False``."""

from __future__ import annotations

import csv
import re

import pytest

from roboracer_arena import build_environment
from roboracer_arena.errors import ArenaError, CorridorError, MapFormatError
from roboracer_arena.usd import validation_errors
from shared_data import sources_dir  # tests/ is on sys.path (rootdir conftest)

NO_LOOP = r"no closed corridor: no free region encloses an infield"
LEAK = r"no closed corridor: the walls leak .* reaches the map border \(\d+ border cells, e\.g\. at \(-?\d+\.\d+, -?\d+\.\d+\) m\)"

# Race loops the raster crops: the corridor grazes the map edge, which closes it (acts as a
# wall). Their wall-deviation figure is measured against the occupied cells only, so it is
# large along the edge; the IoU still holds.
EDGE_CLOSED = {
    "cps-tuwien-f1tenth-maps/maps/vegas.yaml",  # 39 free cells on the top row
    "f1tenth-gym/maps/vegas.yaml",
    "cps-tuwien-f1tenth-maps/maps/stata_basement.yaml",  # the basement loop; a side corridor runs off the map
    "f1tenth-gym/maps/stata_basement.yaml",
    "f1tenth-simulator/maps/stata_basement.yaml",
}

# Maps that must be refused, with why that is right for the map.
REFUSED: dict[str, tuple[type[ArenaError], str, str]] = {
    "bdevan5-f1tenth-benchmarks/maps/CornerHall.yaml": (CorridorError, NO_LOOP, "an L-shaped hallway: no loop"),
    "cps-tuwien-f1tenth-maps/maps/levinelobby.yaml": (CorridorError, NO_LOOP, "a building lobby: no loop"),
    "f1tenth-simulator/maps/levinelobby.yaml": (CorridorError, NO_LOOP, "a building lobby: no loop"),
    "f1tenth-gym-ros/maps/levine.yaml": (CorridorError, LEAK, "a building floor (thin-line) wide open to the map edge"),
    "f1tenth-gym-ros/maps/Spielberg_blank_map.yaml": (
        CorridorError,
        r"no closed corridor: .*the map is blank \(no walls\)",
        "every pixel is free",
    ),
    "f1tenth-simulator/maps/porto.yaml": (
        MapFormatError,
        r"porto\.yaml: map image .*map\.pgm.* does not exist; .*porto\.pgm' exists beside the YAML",
        "its YAML names map.pgm; the raster is porto.pgm",
    ),
}


def inventory() -> list[dict[str, str]]:
    path = sources_dir() / "map-inventory.csv"
    if not path.is_file():
        return []
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


ROWS = inventory()


def test_inventory_is_there_and_expectations_name_real_maps():
    assert len(ROWS) >= 90, f"map inventory not found under {sources_dir()}"
    names = {r["yaml"] for r in ROWS}
    assert set(REFUSED) <= names and EDGE_CLOSED <= names and not (EDGE_CLOSED & set(REFUSED))


@pytest.mark.slow
@pytest.mark.parametrize("row", ROWS, ids=[r["yaml"] for r in ROWS])
def test_every_shared_map_builds_or_is_refused_for_its_reason(row, tmp_path):
    yaml = sources_dir() / row["yaml"]
    out = tmp_path / "track.usdc"
    cfg = {"materials": {"textures": False}}  # the USD is built in full; PNG textures are tested elsewhere
    expected = REFUSED.get(row["yaml"])
    if expected is not None:
        cls, pattern, why = expected
        if cls is CorridorError:  # no closed corridor: an open map unless a track is required
            report = build_environment(yaml, out, cfg)
            assert report.map_kind == "open" and re.search(pattern, report.open_reason or ""), report.open_reason
            assert report.iou >= 0.97 and report.walls >= 1 and validation_errors(out) == []
            out.unlink()
        with pytest.raises(cls) as e:
            build_environment(yaml, out, cfg, open=False)
        msg = str(e.value)
        assert re.search(pattern, msg), f"{row['yaml']} ({why}): unexpected message {msg!r}"
        assert str(yaml) in msg or cls is CorridorError
        assert "\n" not in msg
        assert not out.exists()
        return
    report = build_environment(yaml, out, cfg)
    assert report.iou >= 0.97, f"{row['yaml']}: round-trip IoU {report.iou:.4f}"
    assert (report.border_contact_cells > 0) == (row["yaml"] in EDGE_CLOSED), report.border_contact_cells
    if row["yaml"] not in EDGE_CLOSED:
        assert report.max_wall_deviation_cells <= 1.0
    assert report.walls >= 2 and report.meshes["walls"].triangles > 0
    assert report.raster_px == (int(row["width_px"]), int(row["height_px"]))
    assert validation_errors(out) == []
