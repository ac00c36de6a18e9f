"""Direction of travel: which way round a closed track is driven, and where a lap starts.

Every track carries its racing direction from the source to the simulator. The simulator
drives a centreline in its vertex order and starts the grid at its first vertex, so the
one thing to get right is the order of that centreline: :func:`orient` turns any closed
centreline (for example the corridor centreline the builder extracts, which is always
counter-clockwise) into the racing direction and starts it at the start line.

Where the direction comes from (:func:`direction_for_map`):

* **circuits** (``tracks/circuits/<id>/``) and **generated tracks** (``generate`` output,
  ``tracks/generated/<id>/``): the ``centreline.csv`` beside ``map.yaml``. The circuit
  builder keeps the point order of the source centreline (TUM CSV / bacinger GeoJSON:
  both list their points in the racing direction); the generator writes the requested
  direction.
* **recorded maps**: a centreline or raceline file of the same source beside the map
  (f1tenth-racetracks ``<T>_centerline.csv`` / ``<T>_raceline.csv``, BDEvan5
  ``<name>_centerline.csv``), in its point order.
* otherwise :data:`DEFAULT_DIRECTION` (counter-clockwise, the mathematical positive sense
  and the convention of F1TENTH maps), starting where the corridor extraction starts.

Directions are the strings ``"clockwise"`` and ``"counterclockwise"`` (as in
:class:`~roboracer_arena.spec.TrackSpec`). The map frame is the ROS map frame (x right,
y up), so a positive signed area is counter-clockwise seen from above.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .. import _core
from ..errors import InvalidArgumentError, MapFormatError
from ..foundation.fileio import read_text

CLOCKWISE = "clockwise"
COUNTERCLOCKWISE = "counterclockwise"
DIRECTIONS = (CLOCKWISE, COUNTERCLOCKWISE)
#: Direction of a map whose source has no centreline or raceline.
DEFAULT_DIRECTION = COUNTERCLOCKWISE
#: The source's first point is taken as the start line only if it lies this close (m)
#: to the track's centreline (else the file is in another frame and only its order counts).
START_TOLERANCE_M = 1.5


@dataclass(frozen=True)
class TrackDirection:
    """The racing direction of a track and, when known, its start point (map frame, m).

    ``source`` says what decided it (a file path relative to its folder, or ``"default"``).
    """

    direction: str
    start: tuple[float, float] | None = None
    source: str = "default"


def check_direction(value: Any, what: str = "direction") -> str:
    """``value`` as one of :data:`DIRECTIONS` (``"ccw"``/``"cw"`` and dashes accepted);
    raises :class:`InvalidArgumentError` naming ``what`` otherwise."""
    v = str(value).strip().lower().replace("-", "").replace("_", "").replace(" ", "")
    v = {"cw": CLOCKWISE, "ccw": COUNTERCLOCKWISE, "anticlockwise": COUNTERCLOCKWISE}.get(v, v)
    if v not in DIRECTIONS:
        raise InvalidArgumentError(f"{what}: expected 'clockwise' or 'counterclockwise', got {value!r}")
    return v


def opposite(direction: str) -> str:
    """The other direction."""
    return COUNTERCLOCKWISE if check_direction(direction) == CLOCKWISE else CLOCKWISE


def _ring(line: Any) -> tuple[np.ndarray, bool]:
    """(points without a repeated closing vertex, whether one was there)."""
    c = np.asarray(line, dtype=np.float64)[:, :2]
    closed = len(c) > 3 and bool(np.allclose(c[0], c[-1]))
    return (c[:-1] if closed else c), closed


def signed_area(line: Any) -> float:
    """Shoelace area of a closed polyline ((N, 2); positive = counter-clockwise)."""
    return _core.signed_area(_ring(line)[0])


def direction_of(line: Any) -> str:
    """``"counterclockwise"`` if the polyline's signed area is positive, else ``"clockwise"``."""
    return COUNTERCLOCKWISE if signed_area(line) > 0 else CLOCKWISE


def orient(line: Any, direction: str, start: Any = None) -> np.ndarray:
    """The closed centreline ``line`` ((N, 2)) in ``direction``, beginning at the vertex
    nearest ``start`` (x, y) when given, else at its own first vertex. The shape is kept (a repeated closing vertex
    stays repeated); only the vertex order changes."""
    direction = check_direction(direction)
    c, closed = _ring(line)
    if direction_of(c) != direction:
        c = np.vstack([c[:1], c[:0:-1]])  # reversed, same first vertex
    if start is not None:
        sx, sy = float(start[0]), float(start[1])
        c = np.roll(c, -int(np.argmin(np.hypot(c[:, 0] - sx, c[:, 1] - sy))), axis=0)
    c = np.ascontiguousarray(c)
    return np.vstack([c, c[:1]]) if closed else c


def reverse(line: Any) -> np.ndarray:
    """The same closed centreline driven the other way, from the same first vertex."""
    c, closed = _ring(line)
    r = np.vstack([c[:1], c[:0:-1]])
    return np.vstack([r, r[:1]]) if closed else r


def read_centreline_file(path: str | Path) -> np.ndarray:
    """The (N, 2) points of a centreline or raceline file, in file order. Reads our
    ``centreline.csv`` and the TUM/f1tenth ``x_m, y_m, w_right, w_left`` CSVs (comma,
    ``#`` comments) and the f1tenth ``s_m; x_m; y_m; ...`` racelines (semicolons)."""
    p = Path(path)
    text = read_text(p, "centreline")
    rows = []
    raceline = False
    for lineno, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        raceline = ";" in s
        try:
            rows.append([float(v) for v in re.split(r"[;,\s]+", s) if v])
        except ValueError:
            raise MapFormatError(f"{p}:{lineno}: expected numbers, got {line!r}") from None
    try:
        a = np.asarray(rows, dtype=np.float64)
        xy = a[:, 1:3] if raceline else a[:, 0:2]
    except (ValueError, IndexError):
        raise MapFormatError(f"{p}: expected rows of at least 2 (3 for a raceline) numbers") from None
    if len(xy) < 3 or not np.isfinite(xy).all():
        raise MapFormatError(f"{p}: a closed centreline needs >= 3 finite points, got {len(xy)}")
    return xy


def centreline_file_for_map(yaml_path: str | Path) -> Path | None:
    """The centreline/raceline file that comes with a map, if any (see the module docs)."""
    y = Path(yaml_path)
    stem = y.stem[:-4] if y.stem.endswith("_map") else y.stem
    for name in ("centreline.csv", f"{stem}_centerline.csv", f"{stem}_raceline.csv"):
        f = y.parent / name
        if f.is_file():
            return f
    return None


def direction_for_map(yaml_path: str | Path) -> TrackDirection:
    """The racing direction of the map ``yaml_path`` and its start point (the first point
    of its centreline file), or the documented default."""
    f = centreline_file_for_map(yaml_path)
    if f is None:
        return TrackDirection(DEFAULT_DIRECTION, None, "default")
    xy = read_centreline_file(f)
    return TrackDirection(direction_of(xy), (float(xy[0, 0]), float(xy[0, 1])), f.name)


def orient_to(line: Any, how: TrackDirection, reverse_it: bool = False) -> np.ndarray:
    """``line`` oriented as ``how`` says (starting at ``how.start`` when it lies within
    :data:`START_TOLERANCE_M` of the line), then reversed if ``reverse_it``."""
    start = how.start
    if start is not None:
        c, _ = _ring(line)
        if float(np.min(np.hypot(c[:, 0] - start[0], c[:, 1] - start[1]))) > START_TOLERANCE_M:
            start = None
    out = orient(line, how.direction, start)
    return reverse(out) if reverse_it else out


__all__ = [
    "CLOCKWISE",
    "COUNTERCLOCKWISE",
    "DEFAULT_DIRECTION",
    "DIRECTIONS",
    "TrackDirection",
    "centreline_file_for_map",
    "check_direction",
    "direction_for_map",
    "direction_of",
    "opposite",
    "orient",
    "orient_to",
    "read_centreline_file",
    "reverse",
    "signed_area",
]
