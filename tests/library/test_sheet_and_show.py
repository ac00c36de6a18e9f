"""``tracks sheet`` has a legend and draws open floor plans readably; ``tracks show``
prints units and leaves out missing fields."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image, ImageDraw

from roboracer_arena import _core
from roboracer_arena.catalog.entry_text import entry_lines, format_value
from roboracer_arena.cli import main
from roboracer_arena.library.sheet import CORRIDOR, FLOOR, SHADE, WALLS, sheet_legend, thumbnail
from roboracer_arena.maps.occupancy import OccupancyMap
from roboracer_arena.render.frame import draw_legend


def colour_share(img: Image.Image, colour) -> float:
    a = np.asarray(img.convert("RGB")).astype(int)
    return float(np.all(np.abs(a - np.array(colour)) <= 12, axis=-1).mean())


@pytest.fixture(scope="module")
def open_floor(tmp_path_factory):
    """A 60 x 60 m map, free everywhere, with a few thin walls in the middle (an office
    floor plan like f1tenth-gym-ros's levine): no closed corridor."""
    data = np.full((1200, 1200), 254, np.uint8)
    data[500, 400:800] = 0  # a long wall
    data[700, 400:800] = 0
    data[500:701, 400] = 0
    data[560:640, 600] = 0
    return OccupancyMap(data, 0.05, (0.0, 0.0, 0.0)).save(tmp_path_factory.mktemp("open") / "floor.yaml")


@pytest.fixture(scope="module")
def ring_map(tmp_path_factory):
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    xy = np.column_stack([5.0 * np.cos(t), 3.0 * np.sin(t)])
    data, origin = _core.rasterise_centreline(xy, np.full(len(xy), 1.5), resolution=0.05)
    return OccupancyMap(data, 0.05, origin).save(tmp_path_factory.mktemp("ring") / "ring.yaml")


def test_an_open_floor_plan_is_light_floor_with_dark_walls_cropped_to_the_walls(open_floor):
    img, extent = thumbnail(open_floor, (200, 160))
    assert colour_share(img, SHADE[FLOOR]) > 0.5  # mostly floor, not a dark blob
    assert 0.01 < colour_share(img, SHADE[WALLS]) < 0.3  # the thin walls survive the shrinking
    assert extent[0] == pytest.approx(20.0 + 2.0, abs=0.2) and extent[1] == pytest.approx(10.0 + 2.0, abs=0.2)


def test_a_closed_corridor_is_green_and_cropped_to_it(ring_map):
    img, extent = thumbnail(ring_map, (200, 160))
    assert colour_share(img, SHADE[CORRIDOR]) > 0.15 and colour_share(img, SHADE[FLOOR]) == 0
    assert 11 < extent[0] < 14 and 7 < extent[1] < 10


def test_the_sheet_has_a_legend_of_its_frame_and_map_colours(tmp_path):
    names = [e.name for e in sheet_legend()]
    assert names[:3] == ["frame: circuit track", "frame: recorded track", "frame: generated track"]
    assert {"drivable corridor", "walls"} <= set(names)
    out = tmp_path / "sheet.png"
    assert main(["tracks", "sheet", "-o", str(out), "--limit", "2", "--columns", "2", "--kind", "generated"]) == 0
    bottom = draw_legend(ImageDraw.Draw(Image.new("RGB", (1, 1))), sheet_legend(), 8, 66, 360 - 16)[3]
    with Image.open(out) as im:
        assert im.width == 360  # two cells; the legend wraps to fit
        header = np.asarray(im.convert("RGB"))[:bottom]
    for e in sheet_legend():  # every swatch is drawn in the header
        assert np.all(np.abs(header.astype(int) - np.array(e.colour)) <= 12, axis=-1).sum() > 20, e.name


def test_show_prints_units_and_leaves_out_missing_fields(capsys):
    assert main(["tracks", "show", "gen-l040-w12-h1c1s0-ccw-s0"]) == 0
    out = capsys.readouterr().out
    assert "None" not in out and "width_px=" not in out and "repository=" not in out
    lines = {ln[:19].strip(): ln[19:] for ln in out.splitlines()}
    assert lines["lap length"].endswith(" m") and lines["min radius"].endswith(" m")
    assert lines["width min"].endswith(" m") and lines["resolution"] == "0.05 m/cell"
    assert lines["raster"].endswith(" px") and lines["scale"] == "1:1"
    assert main(["tracks", "show", "monaco"]) == 0
    out = capsys.readouterr().out
    assert "None" not in out and "scale              1:10" in out


def test_entry_lines_skip_none_and_format_each_unit():
    lines = entry_lines({"id": "x", "scale": None, "start": None, "lap_length_m": 12.5, "narrowed_fraction": 0.25})
    assert lines == ["id                 x", "lap length         12.5 m", "narrowed           25.0% of the centreline"]
    assert format_value("raster", {"width_px": 3, "height_px": 4}) == "3 x 4 px"
    assert format_value("start", [1.5, -2.0]) == "x 1.5 m, y -2 m"
    assert format_value("verified", {"load": "pass", "drive": None}) == "load pass"
