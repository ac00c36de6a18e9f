"""Top-down drawing of a simulated episode with PIL: track walls, centreline, vehicles
as oriented rectangles, lidar rays and a read-out of time, speed and lap in the corner.
Used by the envs' ``render()`` (rgb_array), so every rollout GIF/MP4 frame carries them."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from PIL import Image, ImageDraw

from ..config.sim import SimConfig
from .topdown import font

BACKGROUND = (246, 246, 242)
WALL = (40, 40, 48)
CENTRELINE = (190, 190, 200)
RAY = (255, 140, 40)
VEHICLE_COLOURS = [(214, 39, 40), (31, 119, 180), (44, 160, 44), (148, 103, 189), (140, 86, 75), (227, 119, 194)]


class SimView:
    """Draws frames of any of ``tracks`` at about ``size`` pixels along the longer side."""

    def __init__(
        self,
        tracks: Sequence[Any],
        sim: SimConfig | None = None,
        size: int = 600,
        margin: float = 0.5,
        max_rays: int = 90,
    ) -> None:
        self.tracks = list(tracks)
        self.sim = sim or SimConfig()
        self.size = int(size)
        self.margin = float(margin)
        self.max_rays = int(max_rays)
        self._backgrounds: dict[int, tuple[Image.Image, tuple[float, float, float]]] = {}

    def _background(self, track_id: int) -> tuple[Image.Image, tuple[float, float, float]]:
        cached = self._backgrounds.get(track_id)
        if cached is not None:
            return cached
        t = self.tracks[track_id]
        xmin, ymin, xmax, ymax = t.bounds
        xmin, ymin, xmax, ymax = xmin - self.margin, ymin - self.margin, xmax + self.margin, ymax + self.margin
        scale = self.size / max(xmax - xmin, ymax - ymin, 1e-6)
        w, h = max(1, math.ceil((xmax - xmin) * scale)), max(1, math.ceil((ymax - ymin) * scale))
        tf = (xmin, ymax, scale)  # pixel = ((x - xmin) * s, (ymax - y) * s)
        img = Image.new("RGB", (w, h), BACKGROUND)
        d = ImageDraw.Draw(img)
        loop = np.vstack([t.centreline, t.centreline[:1]])
        d.line(_px(loop, tf), fill=CENTRELINE, width=1)
        lw = max(1, round(scale * 0.05))
        for wall in t.walls:
            d.line(_px(wall, tf), fill=WALL, width=lw)
        self._backgrounds[track_id] = (img, tf)
        return img, tf

    def draw(
        self,
        track_id: int,
        state: np.ndarray,
        field_index: Mapping[str, int],
        scans: np.ndarray | None = None,
        hud: Sequence[str] = (),
    ) -> np.ndarray:
        """One frame, (H, W, 3) uint8: vehicles from ``state`` (V, S) rows, rays from
        ``scans`` (V, B), the text lines ``hud`` in the top-left corner."""
        bg, tf = self._background(track_id)
        veh, lid = self.sim.vehicle, self.sim.lidar
        fx, fy, fyaw = field_index["x"], field_index["y"], field_index["yaw"]
        poses = [(float(r[fx]), float(r[fy]), float(r[fyaw])) for r in np.asarray(state)]
        img = bg.copy()
        if scans is not None:
            rays = Image.new("RGBA", img.size, (0, 0, 0, 0))
            d = ImageDraw.Draw(rays)
            for k, (x, y, yaw) in enumerate(poses):
                if not math.isfinite(x + y + yaw):
                    continue
                (ox, oy), ends = lidar_rays((x, y, yaw), scans[k], lid, self.max_rays)
                o = _px(np.array([[ox, oy]]), tf)[0]
                for e in _px(ends, tf):
                    d.line([o, e], fill=(*RAY, 110), width=1)
            img = Image.alpha_composite(img.convert("RGBA"), rays).convert("RGB")
        d = ImageDraw.Draw(img)
        hl, hw = veh.chassis_length / 2, veh.chassis_width / 2
        body = np.array([[hl, hw], [hl, -hw], [-hl, -hw], [-hl, hw]])
        for k, (x, y, yaw) in enumerate(poses):
            if not math.isfinite(x + y + yaw):
                continue
            c, s = math.cos(yaw), math.sin(yaw)
            rot = np.column_stack([x + body[:, 0] * c - body[:, 1] * s, y + body[:, 0] * s + body[:, 1] * c])
            d.polygon(_px(rot, tf), fill=VEHICLE_COLOURS[k % len(VEHICLE_COLOURS)], outline=(0, 0, 0))
            nose = np.array([[x, y], [x + hl * c, y + hl * s]])
            d.line(_px(nose, tf), fill=(255, 255, 255), width=max(1, round(tf[2] * 0.04)))
        if hud:
            cars = [p for x, y, yaw in poses if math.isfinite(x + y + yaw) for p in _px(np.array([[x, y]]), tf)]
            _draw_hud(img, hud, max(12, self.size // 36), bg, cars, hl * tf[2])
        return np.asarray(img, dtype=np.uint8)


def lidar_rays(
    pose: Sequence[float], ranges: Any, lidar: Any, max_rays: int = 90
) -> tuple[tuple[float, float], np.ndarray]:
    """The lidar's origin and the end points (N, 2) of at most about ``max_rays`` of its
    rays (every k-th beam) for a car at ``pose`` (x, y, yaw) with the given ``ranges``;
    ``lidar`` is the :class:`~roboracer_arena.config.sim.LidarConfig`."""
    x, y, yaw = (float(v) for v in pose)
    r = np.asarray(ranges, dtype=np.float64)
    step = max(1, len(r) // max(1, int(max_rays)))
    ang = yaw + np.linspace(-lidar.fov / 2, lidar.fov / 2, len(r))[::step]
    ox, oy = x + lidar.mount_x * math.cos(yaw), y + lidar.mount_x * math.sin(yaw)
    rr = np.nan_to_num(r[::step], nan=0.0, posinf=lidar.range_max)
    return (ox, oy), np.column_stack([ox + rr * np.cos(ang), oy + rr * np.sin(ang)])


def hud_lines(batch: Any, env: int = 0) -> list[str]:
    """Time, speed and lap of env ``env`` of a :class:`~roboracer_arena.envs.batch.SimBatch`:
    one line for the clock and one per vehicle (at most four) with its speed and lap."""
    f = batch.field_index
    t = float(batch.elapsed[env]) * batch.config.control_dt
    lines = [f"time {t:.2f} s"]
    rows = np.asarray(batch.state[env])
    for k, row in enumerate(rows[:4]):
        speed = float(row[f["speed"]]) if "speed" in f else float(np.hypot(row[f["vx"]], row[f["vy"]]))
        if "laps" in f:
            lap = int(row[f["laps"]]) + 1
        else:
            lap = int(batch.progress[env, k] // batch.lengths[batch.track_ids[env]]) + 1
        who = f"car {k + 1}: " if len(rows) > 1 else "speed "
        lines.append(f"{who}{speed:.2f} m/s, lap {lap}")
    return lines


def _draw_hud(
    img: Image.Image,
    lines: Sequence[str],
    size_px: int,
    background: Image.Image,
    cars: Sequence[tuple[float, float]],
    car_px: float,
) -> None:
    """``lines`` on a white panel in the corner of the picture that covers no car (centres
    ``cars`` in pixels, ``car_px`` half-length) and the fewest track pixels (the drawn ``background``)."""
    face = font(size_px)
    d = ImageDraw.Draw(img, "RGBA")
    step = size_px + 4
    w, h = round(12 + max(d.textlength(line, font=face) for line in lines)), 8 + step * len(lines)
    W, H = img.size
    ink = np.any(np.asarray(background) != BACKGROUND, axis=2)
    corners = [(4, 4), (W - w - 4, 4), (4, H - h - 4), (W - w - 4, H - h - 4)]

    def cost(c: tuple[int, int]) -> int:
        hidden = sum(
            c[0] - car_px <= cx <= c[0] + w + car_px and c[1] - car_px <= cy <= c[1] + h + car_px for cx, cy in cars
        )
        return hidden * W * H + int(ink[max(c[1], 0) : c[1] + h, max(c[0], 0) : c[0] + w].sum())

    x, y = min(corners, key=cost)
    d.rectangle([x, y, x + w, y + h], fill=(255, 255, 255, 215), outline=(0, 0, 0))
    for i, line in enumerate(lines):
        d.text((x + 5, y + 3 + i * step), line, fill=(0, 0, 0), font=face)


def _px(pts: np.ndarray, tf: tuple[float, float, float]) -> list[tuple[float, float]]:
    xmin, ymax, s = tf
    p = np.asarray(pts, dtype=np.float64)
    return list(zip(((p[:, 0] - xmin) * s).tolist(), ((ymax - p[:, 1]) * s).tolist()))
