"""A learning-curve PNG (Pillow only): mean and best population return per generation."""

from __future__ import annotations

import io
from collections.abc import Sequence
from pathlib import Path

from PIL import Image, ImageDraw, ImageFont

from ..foundation.fileio import atomic_write_bytes


def plot_curve(
    curve: Sequence[dict[str, float]], path: str | Path, title: str, size: tuple[int, int] = (720, 400)
) -> None:
    """Write ``path`` (PNG): return against env-steps, mean (blue) and best (grey) of each generation."""
    w, h = size
    left, right, top, bottom = 70, 20, 40, 50
    img = Image.new("RGB", size, "white")
    d = ImageDraw.Draw(img)
    font = ImageFont.load_default(size=14)
    xs = [r["env_steps"] for r in curve]
    series = {"best": [r["max_return"] for r in curve], "mean": [r["mean_return"] for r in curve]}
    lo = min(min(v) for v in series.values())
    hi = max(max(v) for v in series.values())
    lo, hi = min(lo, 0.0), hi if hi > lo else lo + 1.0
    x0, x1 = 0.0, max(xs) or 1.0

    def px(x: float, y: float) -> tuple[float, float]:
        return left + (x - x0) / (x1 - x0) * (w - left - right), h - bottom - (y - lo) / (hi - lo) * (h - top - bottom)

    d.rectangle([left, top, w - right, h - bottom], outline="black")
    for k in range(5):
        y = lo + (hi - lo) * k / 4
        _, py = px(x0, y)
        d.line([left - 4, py, left, py], fill="black")
        d.text((5, py - 7), f"{y:7.1f}", fill="black", font=font)
        x = x0 + (x1 - x0) * k / 4
        qx, _ = px(x, lo)
        d.line([qx, h - bottom, qx, h - bottom + 4], fill="black")
        d.text((qx - 20, h - bottom + 6), f"{x / 1e3:.0f}k", fill="black", font=font)
    if lo < 0 < hi:
        d.line([px(x0, 0), px(x1, 0)], fill=(200, 200, 200))
    for name, colour in (("best", (150, 150, 150)), ("mean", (31, 94, 200))):
        d.line([px(x, y) for x, y in zip(xs, series[name])], fill=colour, width=2)
    d.text((left, 10), title, fill="black", font=font)
    d.text((5, 10), "return", fill="black", font=font)
    d.text((w - right - 250, 10), "mean (blue) / best (grey) return", fill="black", font=font)
    d.text((w // 2 - 40, h - 22), "env-steps", fill="black", font=font)
    buf = io.BytesIO()
    img.save(buf, format="PNG")
    atomic_write_bytes(path, buf.getvalue())
