"""Writing an accepted track: ROS map (PNG + YAML), centreline CSV (x, y, w_right,
w_left), the spec JSON and the validation report JSON, each written atomically.

:func:`output_folder` makes a whole folder of outputs appear at once: everything is
written into a fresh hidden sibling directory, which then replaces the target by rename.
A folder left by an earlier ``generate`` (it holds ``report.json``) is replaced whole,
so no stale file (e.g. an old stage when ``--build`` is not given) survives; a folder
holding anything else is refused, never overwritten."""

from __future__ import annotations

import contextlib
import io
import json
import os
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from ..errors import ArenaError, InvalidArgumentError
from ..foundation.fileio import atomic_dir, atomic_write_text, read_json
from .outcomes import Acceptance

REPORT_NAME = "report.json"


def centreline_csv(line: np.ndarray, width_m: float) -> str:
    """CSV text in the driving direction; the corridor is symmetric about the centreline."""
    buf = io.StringIO()
    buf.write("# x_m, y_m, w_tr_right_m, w_tr_left_m\n")
    half = width_m / 2
    for x, y in np.asarray(line, float):
        buf.write(f"{x:.4f},{y:.4f},{half:.4f},{half:.4f}\n")
    return buf.getvalue()


def write_outputs(acc: Acceptance, outdir: str | Path, stem: str = "map") -> dict[str, Path]:
    """Write every artefact of an acceptance into ``outdir``; returns their paths."""
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    paths = {
        "map_yaml": out / f"{stem}.yaml",
        "map_png": out / f"{stem}.png",
        "centreline_csv": out / "centreline.csv",
        "spec_json": out / "spec.json",
        "report_json": out / "report.json",
    }
    acc.map.save(paths["map_yaml"])
    atomic_write_text(paths["centreline_csv"], centreline_csv(acc.centreline, acc.spec.corridor_width_m))
    atomic_write_text(paths["spec_json"], acc.spec.model_dump_json(indent=2) + "\n")
    report = {
        "valid": acc.report.valid,
        "constructor": acc.constructor,
        "seed": acc.seed,
        "candidates_tried": acc.candidates_tried,
        "seconds": round(acc.seconds, 4),
        **acc.report.model_dump(mode="json", include={"checks", "measurements", "features"}),
    }
    atomic_write_text(paths["report_json"], json.dumps(report, indent=2) + "\n")
    return paths


def _is_generate_folder(d: Path) -> bool:
    """Empty, or holds the report an earlier ``generate`` wrote."""
    names = os.listdir(d)
    if not names:
        return True
    try:  # the one JSON reader: a report nested 10 000 deep or of 5000-digit numbers is simply not ours
        report = read_json(d / REPORT_NAME, "generate report")
    except (ArenaError, OSError):
        return False
    return isinstance(report, dict) and "constructor" in report and "checks" in report


@contextlib.contextmanager
def output_folder(outdir: str | Path) -> Iterator[Path]:
    """Yield a temporary folder beside ``outdir``; on success it replaces ``outdir``.

    Raises :class:`~roboracer_arena.errors.InvalidArgumentError` (before any work) when
    ``outdir`` is an existing file, or a folder that an earlier ``generate`` did not
    write. On any error the temporary folder is removed and ``outdir`` is untouched.
    """
    out = Path(outdir)
    if out.exists() or out.is_symlink():
        if not out.is_dir() or out.is_symlink():
            raise InvalidArgumentError(
                f"-o {out}: exists and is not a directory; give a new or an earlier generate output directory"
            )
        if not _is_generate_folder(out):
            raise InvalidArgumentError(
                f"-o {out}: directory holds files generate did not write; give a new, empty or earlier generate output directory"
            )
    with atomic_dir(out) as tmp:
        yield tmp
