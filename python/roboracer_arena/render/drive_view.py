"""Frames of a ``drive`` video at the preview's standard.

The still part is drawn once with the preview's own code: the map with its drivable
corridor, ducts and collision walls (:func:`.preview.map_canvas`; a track without a map
gets its collision walls), the racing direction and start line of the track as driven
(:func:`.race_marks.draw_race_marks`), and the frame (:func:`.frame.framed`: title,
legend, scale bar, map axes). Each frame adds the car (enlarged like the preview's grid
car when it would be too small to see), its lidar rays, and a HUD band under the title
with the simulated time, the car's speed and the lap, so nothing covers the track.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image, ImageDraw

from ..config.sim import SimConfig
from .frame import PAD, LegendEntry, framed
from .preview import WALL, map_canvas, map_title
from .race_marks import CAR, car_size, draw_car, draw_race_marks
from .sim_view import RAY, VEHICLE_COLOURS, lidar_rays
from .topdown import TopDown, font

#: Text size of the HUD band (px).
HUD_PX = 22
#: Longer side of the map part of a frame (px) unless the caller says otherwise.
DEFAULT_MAP_PX = 720


@dataclass(frozen=True)
class HudState:
    """What the HUD shows: simulated time (s), the car's speed (m/s), the laps completed
    and requested, and the last completed lap's time (s) if any."""

    time_s: float
    speed_mps: float
    laps_done: int
    laps: int
    last_lap_s: float | None = None


def hud_text(h: HudState) -> str:
    """One HUD line. The lap is the one being driven ("lap 1 of 2"), and once every lap
    is done, "finished 2 of 2 laps": never a lap beyond the last."""
    if h.laps_done >= h.laps:
        lap = f"finished {h.laps} of {h.laps} lap{'s' if h.laps > 1 else ''}"
    else:
        lap = f"lap {h.laps_done + 1} of {h.laps}"
    last = f"   last lap {h.last_lap_s:.2f} s" if h.last_lap_s is not None else ""
    # The lap first: it changes least often, so the read-out does not jump about.
    return f"{lap}   time {h.time_s:6.2f} s   speed {h.speed_mps:5.2f} m/s{last}"


def drive_subtitle(laps: int) -> str:
    """The subtitle of a ``drive`` video: who drives, how many laps, from where."""
    return f"The reference pure-pursuit driver, {laps} lap{'s' if laps > 1 else ''} from the grid start."


class DriveView:
    """Draws the frames of a drive of ``track`` (the :class:`~roboracer_arena.track.drivable.Track`
    as driven, so the arrows show the driven direction)."""

    def __init__(self, track: Any, sim: Any = None, subtitle: str = "", map_px: int = DEFAULT_MAP_PX) -> None:
        self.sim = sim or SimConfig()

        canvas, occ, legend = _still(track, int(map_px))
        marks, race = draw_race_marks(canvas, track, vehicles=1, cars=False)
        self.car_length, self.car_width = car_size(canvas, self.sim.vehicle)
        enlarged = " (enlarged)" if self.car_length > self.sim.vehicle.chassis_length + 1e-9 else ""
        legend += [*marks, LegendEntry(f"car{enlarged}", CAR, "car"), LegendEntry("lidar rays", RAY, "line")]
        if occ is not None:
            self.title = map_title(track.name, race, occ)
        else:
            self.title = f"{track.name}: {race['direction']}, lap {race['lap_length_m']:.1f} m"
        framed_img, layout = framed(canvas, self.title, subtitle, legend)
        # The HUD band goes under the title, so the frame grows by its height there.
        self.hud_h = HUD_PX + 2 * PAD
        tb = layout.title_box[3]
        w, h = framed_img.size
        bg = Image.new("RGB", (w, h + self.hud_h), (255, 255, 255))
        bg.paste(framed_img.crop((0, 0, w, tb)), (0, 0))
        bg.paste(framed_img.crop((0, tb, w, h)), (0, tb + self.hud_h))
        self.background = bg
        self.hud_box = (0, tb, w, tb + self.hud_h)
        mx, my, mx2, my2 = layout.map_box
        self.map_box = (mx, my + self.hud_h, mx2, my2 + self.hud_h)
        self.layout = layout
        self.canvas = canvas
        self._map = canvas.image.copy()

    @property
    def size(self) -> tuple[int, int]:
        """(width, height) of every frame in pixels."""
        return self.background.size

    def frame(self, state: np.ndarray, field_index: dict[str, int], scans: Any, hud: HudState) -> np.ndarray:
        """One frame, (H, W, 3) uint8: the cars of ``state`` ((V, S) rows), the rays of
        ``scans`` ((V, B) ranges, or None) and the HUD."""
        c = copy.copy(self.canvas)  # the same map frame, drawn into a fresh copy of the still map
        c.image = self._map.copy()
        c.draw = ImageDraw.Draw(c.image, "RGBA")
        fx, fy, fyaw = field_index["x"], field_index["y"], field_index["yaw"]
        poses = [(float(r[fx]), float(r[fy]), float(r[fyaw])) for r in np.asarray(state)]
        poses = [p for p in poses if np.isfinite(p).all()]
        if scans is not None:
            for k, pose in enumerate(poses):
                origin, ends = lidar_rays(pose, scans[k], self.sim.lidar)
                c.segments(np.repeat([origin], len(ends), axis=0), ends, (*RAY, 110))
        for k, pose in enumerate(poses):
            colour = CAR if k == 0 else VEHICLE_COLOURS[k % len(VEHICLE_COLOURS)]
            draw_car(c, pose, self.car_length, self.car_width, colour)
        img = self.background.copy()
        img.paste(c.image, self.map_box[:2])
        d = ImageDraw.Draw(img)
        x0, y0, x1, y1 = self.hud_box
        d.rectangle([x0, y0, x1 - 1, y1 - 1], fill=(32, 32, 36))
        d.text((PAD, y0 + PAD - 2), hud_text(hud), fill=(255, 255, 255), font=font(HUD_PX))
        return np.asarray(img, dtype=np.uint8)


def _still(track: Any, map_px: int) -> tuple[TopDown, Any, list[LegendEntry]]:
    """The canvas with the map layers (the map itself when the track came from one, else
    its collision walls), the map (or None) and the legend so far."""
    src = track.source
    if isinstance(src, (str, Path)) and Path(src).is_file():
        canvas, _, occ, _, legend = map_canvas(Path(src), max_px=map_px, min_px=map_px)
        return canvas, occ, legend
    x0, y0, x1, y1 = (float(v) for v in track.bounds)
    canvas = TopDown.for_bounds((x0, y0), (x1, y1), resolution=0.02, margin=0.5, max_px=map_px)
    for wall in track.walls:
        canvas.polyline(wall, WALL, min_px=2)
    return canvas, None, [LegendEntry("collision walls", WALL, "line")]
