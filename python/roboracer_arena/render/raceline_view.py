"""A raceline picture: the track preview (map, corridor, ducts, collision walls, racing
direction and start) with a raceline drawn on it, coloured by its planned speed from
dark violet (slowest) through magenta to orange (fastest), and the speed scale in the legend."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

import numpy as np

from .formats import image_format
from .frame import LegendEntry, framed
from .preview import map_canvas, track_name
from .race_marks import draw_race_marks

#: Speed scale, slow to fast: dark violet, magenta, orange (apart from the red walls,
#: the blue direction arrows and the green corridor).
SPEED_STOPS = ((40, 10, 140), (200, 40, 150), (245, 150, 20))


def speed_colour(frac: float) -> tuple[int, int, int]:
    """The colour of a speed ``frac`` of the way from the slowest (0) to the fastest (1)."""
    f = float(np.clip(frac, 0.0, 1.0)) * (len(SPEED_STOPS) - 1)
    i = min(int(f), len(SPEED_STOPS) - 2)
    a, b = np.array(SPEED_STOPS[i]), np.array(SPEED_STOPS[i + 1])
    c = a + (f - i) * (b - a)
    return (int(c[0]), int(c[1]), int(c[2]))


def raceline_picture(
    map_path: str | Path,
    track: Any,
    xy: np.ndarray,
    speed: np.ndarray,
    title: str,
    out: str | Path,
    max_px: int = 2048,
) -> bytes:
    """The picture's bytes (PNG or JPEG by the extension of ``out``; the caller writes them)."""
    fmt = image_format(out)
    canvas, _, _, _, legend = map_canvas(Path(map_path), max_px=max_px)
    marks, _ = draw_race_marks(canvas, track, 1, cars=False)
    lo, hi = float(np.min(speed)), float(np.max(speed))
    span = max(hi - lo, 1e-6)
    width = max(0.06, 2.0 / canvas.px_per_m())
    pts = np.vstack([xy, xy[:1]])
    v = np.append(speed, speed[0])
    for i in range(len(xy)):
        canvas.polyline(pts[i : i + 2], speed_colour((0.5 * (v[i] + v[i + 1]) - lo) / span), width_m=width, min_px=4)
    scale = [
        LegendEntry(f"raceline {lo + f * span:.1f} m/s", speed_colour(f), "line") for f in (0.0, 0.25, 0.5, 0.75, 1.0)
    ]
    img, _ = framed(
        canvas, title or track_name(Path(map_path)), "Raceline coloured by planned speed.", [*legend, *marks, *scale]
    )
    buf = io.BytesIO()
    if fmt == "JPEG":
        img.convert("RGB").save(buf, format="JPEG", quality=92)
    else:
        img.save(buf, format=fmt, optimize=True)
    return buf.getvalue()
