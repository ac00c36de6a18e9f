"""Top-down previews a person can read: title, legend, scale bar and axes outside the map,
labels inside the picture and never on top of each other, the racing direction and the
grid start exactly where the env puts the car."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from PIL import Image

from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.foundation.paths import tracks_dir
from roboracer_arena.maps.direction import direction_of, read_centreline_file
from roboracer_arena.render.frame import scale_length
from roboracer_arena.render.preview import preview_map
from roboracer_arena.render.topdown import TopDown, boxes_overlap

GEN_CW = "gen-l040-w12-h2c1s1-clo-s0"  # clockwise, 2 hairpins, a chicane and a sweeper


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    yaml = tracks_dir() / "generated" / GEN_CW / "map.yaml"
    out = tmp_path_factory.mktemp("preview") / "gen.png"
    return yaml, out, preview_map(yaml, out, vehicles=2)


def _inside(box, size) -> bool:
    return 0 <= box[0] < box[2] <= size[0] and 0 <= box[1] < box[3] <= size[1]


def test_labels_stay_inside_and_apart_and_the_frame_is_off_the_map(generated):
    _, out, s = generated
    lay = s.layout
    size = Image.open(out).size
    assert tuple(lay["size"]) == size == tuple(s.size_px)
    labels = [b for _, b in lay["label_boxes"]]
    assert {t for t, _ in lay["label_boxes"]} >= {"start", "hairpin 1", "hairpin 2", "chicane 1"}
    assert not lay["dropped_labels"]
    for b in labels:
        mx0, my0, mx1, my1 = lay["map_box"]
        assert _inside(b, size) and mx0 <= b[0] < b[2] <= mx1 and my0 <= b[1] < b[3] <= my1, b
    for a, b in itertools.combinations(labels, 2):
        assert not boxes_overlap(a, b), (a, b)
    frame = [lay[k] for k in ("title_box", "legend_box", "scale_box", "axes_box")]
    for a, b in itertools.combinations([lay["map_box"], *frame], 2):
        assert not boxes_overlap(a, b), (a, b)


def test_the_legend_never_covers_the_track(generated):
    """Every wall vertex of the track, mapped into the picture the way the preview maps it,
    lies on the map and none under the legend (or title, scale bar, axes)."""
    from roboracer_arena.maps.corridor import extract_corridor
    from roboracer_arena.maps.occupancy import load_map

    yaml, _, s = generated
    occ = load_map(yaml)
    canvas = TopDown.for_raster(occ.data, occ.resolution, occ.origin)
    mx, my = s.layout["map_box"][:2]
    walls = np.vstack(extract_corridor(occ).walls)
    px = canvas.to_px(walls) + [mx, my]
    x0, y0, x1, y1 = s.layout["map_box"]
    assert ((px[:, 0] >= x0) & (px[:, 0] <= x1) & (px[:, 1] >= y0) & (px[:, 1] <= y1)).all()
    for key in ("legend_box", "title_box", "scale_box", "axes_box"):
        bx0, by0, bx1, by1 = s.layout[key]
        under = (px[:, 0] >= bx0) & (px[:, 0] < bx1) & (px[:, 1] >= by0) & (px[:, 1] < by1)
        assert not under.any(), key


def test_direction_and_grid_are_the_envs(generated):
    yaml, _, s = generated
    source = read_centreline_file(yaml.parent / "centreline.csv")
    assert s.race["direction"] == direction_of(source) == "clockwise"
    env = RoboRacerEnv(track=str(yaml), reset_poses="grid", vehicles_per_env=2)
    obs, _ = env.reset(seed=0)
    poses = env.odometry_raw(obs)[:, :3]
    drawn = np.asarray(s.race["grid"])
    np.testing.assert_allclose(drawn[:, :2], poses[:, :2], atol=2e-3)
    turn = (drawn[:, 2] - poses[:, 2] + np.pi) % (2 * np.pi) - np.pi
    assert np.abs(turn).max() < 2e-3
    env.close()


def test_the_picture_shows_arrows_start_car_and_a_title(generated):
    from roboracer_arena.render.race_marks import ARROW, CAR

    _, out, s = generated
    img = np.asarray(Image.open(out).convert("RGB")).astype(int)
    x0, y0, x1, y1 = s.layout["map_box"]
    on_map = img[y0:y1, x0:x1]
    assert (np.abs(on_map - ARROW).sum(axis=2) < 10).sum() > 200  # direction arrows
    assert (np.abs(on_map - CAR).sum(axis=2) < 10).sum() > 50  # the cars on the grid
    tx0, ty0, tx1, ty1 = s.layout["title_box"]
    title = img[ty0:ty1, tx0:tx1]
    assert (title.sum(axis=2) < 150).sum() > 200  # dark title text on white


def test_many_labels_at_one_point_never_overlap_or_leave_the_canvas():
    canvas = TopDown(100, 60, 0.05, (0.0, 0.0, 0.0), scale=4.0)  # 400 x 240 px, 5 x 3 m
    for k in range(40):
        canvas.label((0.2, 0.2), f"label number {k}")  # the lower-left corner
    boxes = [b for _, b in canvas.label_boxes]
    assert len(boxes) >= 5 and len(boxes) + len(canvas.dropped_labels) == 40
    for b in boxes:
        assert _inside(b, canvas.image.size)
    for a, b in itertools.combinations(boxes, 2):
        assert not boxes_overlap(a, b)


def test_scale_bar_is_a_round_length_that_fits():
    assert scale_length(20.0, 170) == (5.0, 100.0)
    assert scale_length(0.9, 170) == (100.0, pytest.approx(90.0))
    m, px = scale_length(1234.0, 170)
    assert m == 0.1 and px <= 170
