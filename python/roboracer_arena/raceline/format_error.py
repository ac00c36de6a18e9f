"""The one error of the raceline readers."""

from __future__ import annotations

from ..errors import MapFormatError


class RacelineFormatError(MapFormatError):
    """A raceline file (TUM CSV or ForzaETH JSON) that cannot be read: the message names the
    file and what is wrong (line, column or field). The CLI exits 2 on it."""
