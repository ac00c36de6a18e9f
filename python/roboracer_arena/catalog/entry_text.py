"""``tracks show`` as text: one catalog entry, a field a line, each number with its unit,
and no line for a field the entry does not have (no ``None``)."""

from __future__ import annotations

from typing import Any

#: Fields whose unit is not in their name: (label, format of the value).
SPECIAL = {
    "resolution_m": ("resolution", "{:g} m/cell"),
    "narrowed_fraction": ("narrowed", "{:.1%} of the centreline"),
    "length_error": ("length error", "{:.2%} (raster vs smoothed centreline)"),
}
#: Unit suffixes of field names.
UNITS = {"_m": "m", "_px": "px", "_s": "s"}
WIDTH = 19


def _unit(key: str) -> tuple[str, str]:
    """The field's label without its unit suffix, and the unit ("" if none)."""
    for suffix, unit in UNITS.items():
        if key.endswith(suffix):
            return key[: -len(suffix)], unit
    return key, ""


def format_value(key: str, value: Any) -> str | None:
    """``value`` of field ``key`` for people, with its unit; None for a missing value."""
    if value is None or value == [] or value == {}:
        return None
    if key in SPECIAL:
        return SPECIAL[key][1].format(value)
    if key == "scale":
        return "1:1" if value == 1 else f"1:{1 / value:g}" if 0 < value < 1 else f"{value:g}:1"
    if key == "raster":
        return f"{value['width_px']} x {value['height_px']} px"
    if key == "start" and len(value) == 2:
        return f"x {value[0]:g} m, y {value[1]:g} m"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, dict):
        parts = [(k, format_value(k, v)) for k, v in value.items()]
        return ", ".join(f"{_unit(k)[0]} {v}" for k, v in parts if v is not None)
    unit = _unit(key)[1]
    if isinstance(value, float):
        return f"{value:g} {unit}".rstrip()
    return f"{value} {unit}".rstrip()


def entry_lines(entry: dict[str, Any]) -> list[str]:
    """The lines of ``tracks show`` for an entry's JSON dict (plus e.g. ``map_path``)."""
    lines = []
    for key, value in entry.items():
        if key == "notes":
            lines += [f"{'note':<{WIDTH}}{n}" for n in value]
            continue
        text = format_value(key, value)
        if text is None:
            continue
        label = SPECIAL[key][0] if key in SPECIAL else _unit(key)[0].replace("_", " ")
        lines.append(f"{label:<{WIDTH}}{text}")
    return lines
