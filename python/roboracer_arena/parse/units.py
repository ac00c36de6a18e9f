"""Length units: every spelling a request may use, its canonical symbol, and its size in
metres. A number without a unit is read as metres (the spec's unit)."""

from __future__ import annotations

#: canonical symbol -> metres per unit
METRES_PER: dict[str, float] = {
    "m": 1.0,
    "cm": 0.01,
    "mm": 0.001,
    "km": 1000.0,
    "ft": 0.3048,
    "yd": 0.9144,
    "inch": 0.0254,
}

#: spelling (lower case) -> canonical symbol
SPELLINGS: dict[str, str] = {
    "m": "m", "meter": "m", "meters": "m", "metre": "m", "metres": "m", "mtr": "m", "mtrs": "m",
    "cm": "cm", "centimeter": "cm", "centimeters": "cm", "centimetre": "cm", "centimetres": "cm",
    "mm": "mm", "millimeter": "mm", "millimeters": "mm", "millimetre": "mm", "millimetres": "mm",
    "km": "km", "kilometer": "km", "kilometers": "km", "kilometre": "km", "kilometres": "km",
    "ft": "ft", "foot": "ft", "feet": "ft",
    "yd": "yd", "yds": "yd", "yard": "yd", "yards": "yd",
    "inch": "inch", "inches": "inch",
}  # fmt: skip


def canonical_unit(word: str) -> str | None:
    """The canonical symbol of a unit spelling, or ``None`` if ``word`` is not a unit."""
    return SPELLINGS.get(word.lower())


def to_metres(value: float, unit: str | None) -> float:
    """Convert ``value`` in canonical ``unit`` (``None`` = metres) to metres, rounded to
    the micrometre so that 150 cm is exactly 1.5 m."""
    return round(value * METRES_PER[unit or "m"], 6)
