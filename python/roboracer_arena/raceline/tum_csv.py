"""TUM's raceline export, as f1tenth_racetracks ships it (``*_raceline.csv``)::

    # <uuid>
    # <sha1 of the ggv / limits>
    # s_m; x_m; y_m; psi_rad; kappa_radpm; vx_mps; ax_mps2
    0.0000000;-0.0440806;-0.8491629;3.4034118;0.0000525;8.0000000;0.0000000
    ...

Seven columns separated by ``;`` with seven decimals; the last row repeats the first at
``s = lap length`` (the loop closed). ``psi_rad`` is the heading from +x, wrapped to
[0, 2 pi) as f1tenth_racetracks writes it (TUM's own frame has 0 along +y; their files
were converted). The reader accepts any heading wrap.
"""

from __future__ import annotations

import hashlib
import uuid
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..foundation.fileio import atomic_write_text, read_text
from .format_error import RacelineFormatError

COLUMNS = ("s_m", "x_m", "y_m", "psi_rad", "kappa_radpm", "vx_mps", "ax_mps2")
HEADER = "# " + "; ".join(COLUMNS)


@dataclass(frozen=True)
class TumRaceline:
    """The columns of a TUM raceline CSV, each (N,), the closing row included."""

    s: np.ndarray
    x: np.ndarray
    y: np.ndarray
    psi: np.ndarray
    kappa: np.ndarray
    vx: np.ndarray
    ax: np.ndarray
    uuid: str = ""
    ggv_sha1: str = ""

    @property
    def lap_time(self) -> float:
        """Lap time (s) from ``s`` and ``vx`` (TUM's: each step at the mean of its two speeds)."""
        ds = np.diff(self.s)
        return float(np.sum(2.0 * ds / np.maximum(self.vx[:-1] + self.vx[1:], 1e-9)))

    @property
    def length(self) -> float:
        return float(self.s[-1] - self.s[0])


def tum_text(
    s: np.ndarray,
    xy: np.ndarray,
    psi: np.ndarray,
    kappa: np.ndarray,
    vx: np.ndarray,
    ax: np.ndarray,
    length: float,
    ggv_sha1: str,
    name: str,
) -> str:
    """The CSV text of a closed raceline (arrays (N,) without the closing row; it is added)."""
    rows = np.column_stack(
        [
            np.append(s, length),
            np.append(xy[:, 0], xy[0, 0]),
            np.append(xy[:, 1], xy[0, 1]),
            np.mod(np.append(psi, psi[0]), 2 * np.pi),
            np.append(kappa, kappa[0]),
            np.append(vx, vx[0]),
            np.append(ax, ax[0]),
        ]
    )
    rows[np.abs(rows) < 5e-8] = 0.0  # no "-0.0000000"
    body = "\n".join(";".join(f"{v:.7f}" for v in r) for r in rows)
    # A uuid that is a function of the content: the same line gives the same file.
    digest = hashlib.sha1(body.encode()).hexdigest()
    ident = uuid.uuid5(uuid.NAMESPACE_URL, f"roboracer-arena/raceline/{name}/{ggv_sha1}/{digest}")
    return f"# {ident}\n# {ggv_sha1}\n{HEADER}\n{body}\n"


def write_tum_csv(path: str | Path, text: str) -> Path:
    """Write a raceline CSV atomically (nothing half-written is left on failure)."""
    atomic_write_text(path, text)
    return Path(path)


def read_tum_csv(path: str | Path) -> TumRaceline:
    """A TUM raceline CSV; a :class:`RacelineFormatError` naming the file and line if malformed."""
    p = Path(path)
    text = read_text(p, "raceline CSV")
    comments: list[str] = []
    rows: list[list[float]] = []
    header_seen = False
    for lineno, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith("#"):
            if rows:
                raise RacelineFormatError(f"{p}: line {lineno}: a comment after the data rows")
            body = stripped.lstrip("#").strip()
            names = [c.strip() for c in body.split(";")]
            if len(names) > 1:
                if tuple(names) != COLUMNS:
                    raise RacelineFormatError(
                        f"{p}: line {lineno}: columns are {'; '.join(names)}, expected {'; '.join(COLUMNS)}"
                    )
                header_seen = True
            else:
                comments.append(body)
            continue
        if not header_seen:
            raise RacelineFormatError(f"{p}: line {lineno}: data before the column header '{HEADER}'")
        cells = stripped.split(";")
        if len(cells) != len(COLUMNS):
            raise RacelineFormatError(f"{p}: line {lineno}: {len(cells)} values, expected {len(COLUMNS)}")
        try:
            vals = [float(c) for c in cells]
        except ValueError:
            raise RacelineFormatError(f"{p}: line {lineno}: a value is not a number") from None
        if not np.isfinite(vals).all():
            raise RacelineFormatError(f"{p}: line {lineno}: a value is not finite")
        rows.append(vals)
    if not header_seen:
        raise RacelineFormatError(f"{p}: no column header '{HEADER}'")
    if len(rows) < 4:
        raise RacelineFormatError(f"{p}: {len(rows)} data rows, a raceline needs at least 4")
    a = np.asarray(rows)
    if (np.diff(a[:, 0]) <= 0).any():
        bad = int(np.argmax(np.diff(a[:, 0]) <= 0)) + 2
        raise RacelineFormatError(f"{p}: s_m must increase strictly (data row {bad})")
    if (a[:, 5] < 0).any():
        raise RacelineFormatError(f"{p}: vx_mps must be >= 0")
    return TumRaceline(
        s=a[:, 0],
        x=a[:, 1],
        y=a[:, 2],
        psi=a[:, 3],
        kappa=a[:, 4],
        vx=a[:, 5],
        ax=a[:, 6],
        uuid=comments[0] if comments else "",
        ggv_sha1=comments[1] if len(comments) > 1 else "",
    )
