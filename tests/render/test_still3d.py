"""``preview --3d``: a lit 3D still of the demo's stage, rendered headless (no display,
no GPU) by VTK, is a real picture: floor, ducts and the car are in it."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

pytest.importorskip("vtkmodules", reason="the render3d extra (VTK) is not installed")


@pytest.fixture(scope="module")
def demo_stage(tmp_path_factory):
    from roboracer_arena.demo import main as demo

    out = tmp_path_factory.mktemp("demo")
    assert demo(["--out", str(out), "--no-drive"]) == 0
    return out / "track.usdc"


@pytest.mark.slow
def test_demo_stage_renders_headless(demo_stage, tmp_path):
    png = tmp_path / "still.png"
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    cli = "import sys; from roboracer_arena.cli import main; sys.exit(main())"
    run = subprocess.run(
        [sys.executable, "-c", cli, "preview", "--3d", str(demo_stage), "-o", str(png), "--json"],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )
    assert run.returncode == 0, run.stderr
    summary = json.loads(run.stdout)
    assert {"floor", "ducts", "rings", "collision walls", "car"} <= set(summary["drawn"])
    img = np.asarray(Image.open(png).convert("RGB")).astype(int)
    assert img.shape == (800, 1280, 3) and img.std() > 20  # not blank
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    grey = (np.abs(r - g) < 10) & (np.abs(g - b) < 12)
    floor = grey & (r > 40) & (r < 140)  # the lit mid-grey floor (0.32, 0.33, 0.35)
    assert floor.mean() > 0.15
    silver = grey & (r > 170) & (np.abs(img - [237, 240, 245]).sum(axis=2) > 20)  # ducts, not the background
    assert silver.sum() > 2000
    car = (r > 150) & (g < 70) & (b < 70)
    assert car.sum() > 30


def test_3d_needs_a_stage_and_a_picture_extension(tmp_path, capsys):
    from roboracer_arena.cli import EXIT_BAD_INPUT, main

    assert main(["preview", "--3d", str(tmp_path / "map.yaml"), "-o", str(tmp_path / "x.png")]) == EXIT_BAD_INPUT
    assert "--3d" in capsys.readouterr().err
    assert main(["preview", "--3d", str(tmp_path / "s.usdc"), "-o", str(tmp_path / "x.gif")]) == EXIT_BAD_INPUT
    assert "'.gif'" in capsys.readouterr().err
