"""The racing direction as the *source data* gives it, read here with plain numpy/json
(independent of the package): the sign of the shoelace area of the source centreline in
its own point order. TUM CSVs are local metres (x east, y north); bacinger GeoJSON is
[lon, lat], whose orientation an equirectangular scaling keeps."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np


def shoelace(xy: np.ndarray) -> float:
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def source_points(path: Path) -> np.ndarray:
    """The source centreline's points in file order."""
    if path.suffix == ".geojson":
        doc = json.loads(path.read_text(encoding="utf-8"))
        ll = np.asarray(doc["features"][0]["geometry"]["coordinates"], float)[:, :2]
        return np.column_stack([ll[:, 0] * np.cos(np.radians(ll[:, 1].mean())), ll[:, 1]])
    text = path.read_text(encoding="utf-8")
    if ";" in text:  # f1tenth raceline: s; x; y; ...
        return np.loadtxt(path, delimiter=";", comments="#")[:, 1:3]
    return np.loadtxt(path, delimiter=",", comments="#")[:, :2]


def source_sign(path: Path) -> int:
    """+1 counter-clockwise, -1 clockwise, as the source file lists its points."""
    return 1 if shoelace(source_points(path)) > 0 else -1
