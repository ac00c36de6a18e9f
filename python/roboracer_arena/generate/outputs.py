"""Writing an accepted track: ROS map (PNG + YAML), centreline CSV (x, y, w_right,
w_left), the spec JSON and the validation report JSON, each written atomically."""

from __future__ import annotations

import io
import json
from pathlib import Path

import numpy as np

from ..fileio import atomic_write_text
from .outcomes import Acceptance


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
        "valid": acc.report["valid"],
        "constructor": acc.constructor,
        "seed": acc.seed,
        "candidates_tried": acc.candidates_tried,
        "seconds": round(acc.seconds, 4),
        "checks": acc.report["checks"],
        "measurements": acc.report["measurements"],
        "features": acc.report["features"],
    }
    atomic_write_text(paths["report_json"], json.dumps(report, indent=2) + "\n")
    return paths
