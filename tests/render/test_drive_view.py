"""``drive --gif`` frames carry what a preview shows (title, direction arrows, start line,
scale bar, legend) plus a HUD, and the lap counter is right on the last frame."""

from __future__ import annotations

import re

import numpy as np
import pytest
from PIL import Image, ImageDraw

from roboracer_arena.drivers import drive_laps
from roboracer_arena.render.drive_view import HUD_PX, DriveView, HudState, drive_subtitle, hud_text
from roboracer_arena.render.frame import PAD
from roboracer_arena.render.race_marks import ARROW, CAR
from roboracer_arena.render.topdown import font
from roboracer_arena.track.drivable import track_from_map_path


def near(img: np.ndarray, colour, tol: int = 40) -> np.ndarray:
    return np.all(np.abs(img.astype(int) - np.array(colour)) <= tol, axis=-1)


def test_hud_text_names_the_lap_being_driven_and_never_one_past_the_last():
    assert hud_text(HudState(3.0, 4.256, 0, 1)).startswith("lap 1 of 1   time   3.00 s   speed  4.26 m/s")
    assert hud_text(HudState(9.0, 1.0, 1, 2, 8.5)).startswith("lap 2 of 2")
    done = hud_text(HudState(17.0, 2.0, 1, 1, 16.9))
    assert done.startswith("finished 1 of 1 lap ") and "last lap 16.90 s" in done and "lap 2" not in done
    assert hud_text(HudState(30.0, 2.0, 2, 2, 15.0)).startswith("finished 2 of 2 laps")


def test_a_frame_shows_the_previews_marks_the_car_and_the_hud(ellipse_map):
    track = track_from_map_path(ellipse_map)
    view = DriveView(track, map_px=400)
    bg = np.asarray(view.background)
    x0, y0, x1, y1 = view.map_box
    m = bg[y0:y1, x0:x1]
    assert near(m, ARROW, 30).sum() > 100  # racing-direction arrows on the map
    assert track.name in view.title and "lap" in view.title and "counterclockwise" in view.title
    assert ": clockwise" in DriveView(track.reversed(), map_px=200).title  # the arrows show the way it is driven
    title = bg[: view.hud_box[1]]
    assert (title.min(axis=-1) < 80).sum() > 300  # the title's ink
    sx0, sy0, sx1, sy1 = view.layout.scale_box
    scale = bg[sy0 + view.hud_h : sy1 + view.hud_h, sx0:sx1]
    assert (scale.max(axis=-1) < 40).sum() > 100  # the scale bar's black half
    # a frame: the car drawn where the state says, the HUD band filled, the rest unchanged
    state = np.zeros((1, 3))
    pose = track.centreline[len(track.centreline) // 4]
    state[0, :2] = pose
    f = view.frame(state, {"x": 0, "y": 1, "yaw": 2}, None, HudState(1.5, 3.2, 0, 1))
    assert f.shape == (*view.size[::-1], 3)
    cx, cy = view.canvas.to_px(pose[None])[0]
    car = f[y0 + int(cy) - 4 : y0 + int(cy) + 5, x0 + int(cx) - 4 : x0 + int(cx) + 5]
    assert near(car, CAR, 10).any()
    hx0, hy0, hx1, hy1 = view.hud_box
    hud = f[hy0:hy1, hx0:hx1]
    assert (hud.min(axis=-1) > 200).sum() > 200 and (hud.max(axis=-1) < 60).sum() > 0.5 * hud[..., 0].size
    changed = np.any(f != bg, axis=-1)
    changed[hy0:hy1] = False
    assert 20 < changed.sum() < 0.02 * changed.size  # only the car (no scan given) differs elsewhere


def _lap_text_mask(img: np.ndarray, view: DriveView, text: str) -> np.ndarray:
    """Where the HUD's first item ``text`` sits: light pixels of ``img`` in that box."""
    face = font(HUD_PX)
    d = ImageDraw.Draw(Image.new("RGB", (1, 1)))
    w = int(d.textlength(text, font=face))
    y0 = view.hud_box[1]
    return img[y0 : y0 + view.hud_h, PAD : PAD + w].min(axis=-1) > 128


def test_the_last_gif_frame_says_the_lap_is_finished(ellipse_map, tmp_path):
    gif = tmp_path / "drive.gif"
    res = drive_laps(ellipse_map, 1, video=gif, video_fps=4, render_size=300, sim={"lidar": {"num_beams": 55}})
    assert res.completed and res.laps_completed == 1
    with Image.open(gif) as im:
        im.seek(im.n_frames - 1)
        last = np.asarray(im.convert("RGB"))
        im.seek(1)
        early = np.asarray(im.convert("RGB"))
    view = DriveView(track_from_map_path(ellipse_map), subtitle=drive_subtitle(1), map_px=300)
    assert last.shape[:2] == view.size[::-1]
    state = np.zeros((1, 3))
    want = {}
    for k, done in (("finished", 1), ("lap 1", 0)):
        ref = view.frame(state, {"x": 0, "y": 1, "yaw": 2}, None, HudState(0.0, 0.0, done, 1))
        want[k] = _lap_text_mask(ref, view, "finished 1 of 1 lap" if done else "lap 1 of 1")
    got = _lap_text_mask(last, view, "finished 1 of 1 lap")
    assert (got == want["finished"]).mean() > 0.98
    assert (_lap_text_mask(early, view, "lap 1 of 1") == want["lap 1"]).mean() > 0.98


def test_the_progress_bar_shows_simulated_time_and_the_cars_speed(ellipse_map, capsys):
    res = drive_laps(ellipse_map, 1, progress=True, sim={"lidar": {"num_beams": 55}})
    err = capsys.readouterr().err
    updates = [u for u in err.replace("\r", "\n").splitlines() if "sim " in u]
    assert updates, err[-500:]
    last = re.search(r"/(\d+\.\d) m, sim (\d+\.\d) s, (\d+\.\d\d) m/s", updates[-1])
    assert last is not None, updates[-1]
    assert float(last.group(1)) == pytest.approx(res.track_length, abs=0.1)
    assert 0 < float(last.group(2)) <= res.sim_time + 1e-9  # simulated seconds, not wall
    speeds = [float(m.group(1)) for u in updates for m in [re.search(r"(\d+\.\d\d) m/s", u)] if m]
    assert 0 < max(speeds) <= res.max_speed + 0.01  # the car's own speed, not metres per wall second
    assert "it/s" not in err and "m/s]" not in err  # no tqdm rate
