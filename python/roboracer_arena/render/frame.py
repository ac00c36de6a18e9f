"""The frame around a top-down map picture: a title band above it and, below it, the
legend, a scale bar and the map-frame axes (north arrow). Nothing of the frame is drawn
over the map, so the legend never covers the track."""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from PIL import Image, ImageDraw

from .topdown import RGB, Box, TopDown, font

#: Narrowest framed picture (px): room for the legend, scale bar and axes of a tiny map.
MIN_WIDTH = 720
PAD = 10
TITLE_PX, TEXT_PX = 22, 15
INK = (20, 20, 20)


@dataclass(frozen=True)
class LegendEntry:
    """One key of the legend: ``kind`` is how its swatch looks (``area``, ``line``,
    ``arrow`` for the racing direction, ``car``, ``startline``)."""

    name: str
    colour: RGB
    kind: str = "area"


@dataclass
class Layout:
    """Where everything went in the framed picture (pixel boxes, right/bottom exclusive)."""

    size: tuple[int, int]
    map_box: Box
    title_box: Box
    legend_box: Box
    scale_box: Box
    axes_box: Box
    scale_m: float
    label_boxes: list[tuple[str, Box]] = field(default_factory=list)
    dropped_labels: list[str] = field(default_factory=list)


def framed(canvas: TopDown, title: str, subtitle: str, legend: Sequence[LegendEntry]) -> tuple[Image.Image, Layout]:
    """The canvas with a title band above and legend, scale bar and axes below."""
    mw, mh = canvas.image.size
    width = max(mw, MIN_WIDTH)
    probe = ImageDraw.Draw(Image.new("RGB", (1, 1)))
    title_font, text_font = font(TITLE_PX), font(TEXT_PX)
    title_lines = [(title, title_font), *([(subtitle, text_font)] if subtitle else [])]
    title_lines = [(t, f) for line, f in title_lines for t in _wrap(probe, line, f, width - 2 * PAD)]
    title_h = PAD + sum(_text_h(probe, t, f) + 4 for t, f in title_lines) + PAD // 2
    tools_w = 330  # scale bar and axes, right of the legend
    rows = _legend_rows(probe, legend, text_font, width - tools_w - 3 * PAD)
    footer_h = max(len(rows) * LEGEND_ROW_PX + 2 * PAD, 112)
    img = Image.new("RGB", (width, title_h + mh + footer_h), (255, 255, 255))
    d = ImageDraw.Draw(img)
    mx, my = (width - mw) // 2, title_h
    img.paste(canvas.image, (mx, my))
    d.rectangle([mx - 1, my - 1, mx + mw, my + mh], outline=(150, 150, 150))

    y = PAD
    for text, f in title_lines:
        d.text((PAD, y), text, fill=INK, font=f)
        y += _text_h(probe, text, f) + 4
    title_box = (0, 0, width, title_h)

    fy = my + mh + 1
    legend_box = _draw_rows(d, rows, PAD, fy + PAD, text_font)

    scale_m, scale_px = scale_length(canvas.px_per_m(), 200)
    sx, sy = width - tools_w + PAD, fy + PAD + 24
    _scale_bar(d, sx, sy, scale_px, scale_m, text_font)
    scale_box = (sx, fy + PAD, sx + 205, sy + 30)
    ax, ay = width - 52, fy + 56
    _axes(d, canvas, ax, ay, text_font)
    axes_box = (ax - 50, ay - 50, ax + 50, ay + 50)

    shift = lambda b: (b[0] + mx, b[1] + my, b[2] + mx, b[3] + my)
    layout = Layout(
        img.size,
        (mx, my, mx + mw, my + mh),
        title_box,
        legend_box,
        scale_box,
        axes_box,
        scale_m,
        [(t, shift(b)) for t, b in canvas.label_boxes],
        list(canvas.dropped_labels),
    )
    return img, layout


def _text_h(d: ImageDraw.ImageDraw, text: str, f) -> int:
    _, _, _, b = d.textbbox((0, 0), text or " ", font=f)
    return int(b)  # Pillow types the box as floats; bitmap and FreeType fonts give ints


def _wrap(d: ImageDraw.ImageDraw, text: str, f, width: int) -> list[str]:
    """``text`` in lines at most ``width`` px wide, broken as :func:`wrap_items` says."""
    return wrap_items(text, lambda line: d.textlength(line, font=f) <= width)


def wrap_items(text: str, fits: Callable[[str], bool]) -> list[str]:
    """``text`` broken into lines for which ``fits(line)`` holds: between items first
    (after ``, `` ``; `` ``. `` or ``: ``), and only an item too long for a line of its own
    is broken at its spaces, never inside a value ("70.9 m", "30.0 x 30.0 m", "x 7.01 m")."""
    lines: list[str] = []
    cur = ""
    for piece in _items(text):
        trial = cur + piece
        if not cur or fits(trial.rstrip()):
            cur = trial
            continue
        lines.append(cur.rstrip())
        cur = piece
    lines.append(cur.rstrip())
    out: list[str] = []
    for line in lines:  # an item longer than a line: break it between its values
        out += [line] if fits(line) else _break_item(line, fits)
    return out


def _items(text: str) -> list[str]:
    """``text`` cut after each item separator (the separator stays with its item)."""
    pieces = re.split(r"(?<=[,;.:]) (?=\S)", text)
    return [p + " " for p in pieces[:-1]] + pieces[-1:]


def _break_item(item: str, fits: Callable[[str], bool]) -> list[str]:
    """``item`` broken at the spaces that do not split a value (see :func:`_glued`)."""
    words = item.split(" ")
    chunks = [words[0]]
    for prev, word in zip(words, words[1:]):
        if _glued(prev, word):
            chunks[-1] += " " + word
        else:
            chunks.append(word)
    lines, cur = [], ""
    for c in chunks:
        trial = f"{cur} {c}" if cur else c
        if cur and not fits(trial):
            lines.append(cur)
            cur = c
        else:
            cur = trial
    return [*lines, cur]


_NUMBER = re.compile(r"^[-+−]?\(?[\d.]+[\d.,%°)]*$")


def _glued(prev: str, word: str) -> bool:
    """True when the space between ``prev`` and ``word`` sits inside a value: a number and
    its unit ("70.9 m"), a name and its number ("x 7.01", "lap 2"), "30.0 x 30.0"."""
    if prev.endswith((",", ";", ".", ":")):
        return False  # the end of an item
    num_prev, num_word = bool(_NUMBER.match(prev)), bool(_NUMBER.match(word))
    if num_prev and not num_word and len(word.rstrip(",;.:")) <= 8:
        return True  # number, unit ("m", "m/cell", "cm"; also "30.0 x")
    return num_word  # label, number ("lap 2", "x 7.01", "x 30.0")


LEGEND_ROW_PX = TEXT_PX + 10


def draw_legend(d: ImageDraw.ImageDraw, legend: Sequence[LegendEntry], x: int, y: int, width: int) -> Box:
    """The legend entries flowed into rows no wider than ``width`` px from (x, y), with the
    swatches of the framed pictures; returns the box they fill."""
    f = font(TEXT_PX)
    return _draw_rows(d, _legend_rows(d, legend, f, width), x, y, f)


def _draw_rows(d: ImageDraw.ImageDraw, rows: list[list[tuple[LegendEntry, int]]], x0: int, y0: int, f) -> Box:
    right = x0
    for r, row in enumerate(rows):
        x, yy = x0, y0 + r * LEGEND_ROW_PX
        for entry, w in row:
            _swatch(d, entry, (x, yy + 1, x + 28, yy + TEXT_PX + 1))
            d.text((x + 34, yy), entry.name, fill=INK, font=f)
            x += w
        right = max(right, x)
    return (x0, y0, right, y0 + len(rows) * LEGEND_ROW_PX)


def _legend_rows(
    d: ImageDraw.ImageDraw, legend: Sequence[LegendEntry], f, width: int
) -> list[list[tuple[LegendEntry, int]]]:
    """Legend entries flowed into rows no wider than ``width`` px: [(entry, its width)]."""
    rows: list[list[tuple[LegendEntry, int]]] = [[]]
    used = 0
    for e in legend:
        w = 34 + math.ceil(d.textlength(e.name, font=f)) + 18
        if rows[-1] and used + w > width:
            rows.append([])
            used = 0
        rows[-1].append((e, w))
        used += w
    return rows if rows[0] else []


def _swatch(d: ImageDraw.ImageDraw, e: LegendEntry, box: tuple[int, int, int, int]) -> None:
    x0, y0, x1, y1 = box
    cy = (y0 + y1) // 2
    if e.kind == "line":
        d.line([(x0, cy), (x1, cy)], fill=e.colour, width=3)
    elif e.kind == "arrow":
        d.line([(x0, cy), (x1, cy)], fill=e.colour, width=2)
        direction_chevron(d, (x1 - 6, cy), (1.0, 0.0), e.colour)
    elif e.kind == "car":
        d.rectangle([x0 + 6, cy - 4, x1 - 6, cy + 4], fill=e.colour, outline=(0, 0, 0))
    elif e.kind == "startline":
        for k in range(0, x1 - x0, 6):
            d.rectangle(
                [x0 + k, cy - 3, min(x1, x0 + k + 5), cy + 3],
                fill=(0, 0, 0) if k % 12 else (255, 255, 255),
                outline=(0, 0, 0),
            )
    else:
        d.rectangle([x0 + 4, y0, x1 - 4, y1 - 1], fill=e.colour, outline=(0, 0, 0))


def direction_chevron(
    d: ImageDraw.ImageDraw, tip: tuple[float, float], heading: tuple[float, float], colour: RGB, size: float = 9.0
) -> None:
    """A filled arrow head at ``tip`` pointing along the image-space unit vector ``heading``."""
    hx, hy = heading
    nx, ny = -hy, hx
    x, y = tip
    pts = [
        (x, y),
        (x - size * hx + 0.6 * size * nx, y - size * hy + 0.6 * size * ny),
        (x - 0.55 * size * hx, y - 0.55 * size * hy),
        (x - size * hx - 0.6 * size * nx, y - size * hy - 0.6 * size * ny),
    ]
    d.polygon(pts, fill=colour, outline=(255, 255, 255))


def scale_length(px_per_m: float, max_px: int) -> tuple[float, float]:
    """The longest 1-2-5 length (m) whose bar fits in ``max_px`` pixels, and its pixels."""
    best = 0.01
    for exp in range(-2, 6):
        for m in (1, 2, 5):
            length = m * 10.0**exp
            if length * px_per_m <= max_px:
                best = length
    return best, best * px_per_m


def _scale_bar(d: ImageDraw.ImageDraw, x: int, y: int, px: float, metres: float, f) -> None:
    """A two-tone bar ``px`` long at (x, y) with its length written above."""
    half = px / 2
    d.rectangle([x, y, x + half, y + 7], fill=(0, 0, 0))
    d.rectangle([x + half, y, x + px, y + 7], fill=(255, 255, 255), outline=(0, 0, 0))
    text = f"{metres:g} m" if metres >= 1 else f"{metres * 100:g} cm"
    d.text((x, y - TEXT_PX - 6), f"scale  {text}", fill=INK, font=f)


def _axes(d: ImageDraw.ImageDraw, canvas: TopDown, cx: int, cy: int, f) -> None:
    """The map frame's x and y axes as arrows (y is "north" of the map frame); they turn
    with a map whose origin has a yaw."""
    o, ex, ey = canvas.to_px(np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]))
    for end, name in ((ex, "x"), (ey, "y")):
        v = (end - o) / max(float(np.linalg.norm(end - o)), 1e-12)
        tip = (cx + 30 * v[0], cy + 30 * v[1])
        d.line([(cx, cy), tip], fill=INK, width=2)
        direction_chevron(d, tip, (float(v[0]), float(v[1])), INK, size=8)
        d.text((cx + 40 * v[0] - 4, cy + 40 * v[1] - 9), name, fill=INK, font=f)
