"""``roboracer-arena build`` and ``preview`` end to end."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
from PIL import Image

from roboracer_arena.cli import main

from .ringmap import ring_raster, write_map


def test_build_and_preview(tmp_path, capsys):
    yaml = write_map(tmp_path / "maps", ring_raster(200, style="filled"))
    out = tmp_path / "out" / "ring.usdc"
    assert main(["build", str(yaml), "-o", str(out), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["output"] == str(out) and out.is_file() and report["iou"] >= 0.97
    assert (tmp_path / "out" / "textures").is_dir()

    png = tmp_path / "map.png"
    assert main(["preview", str(yaml), "-o", str(png), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert {"map", "corridor", "walls", "ducts"} <= set(summary["drawn"])
    x0, y0, x1, y1 = summary["layout"]["map_box"]
    assert x1 - x0 == y1 - y0 and 800 <= x1 - x0 <= 1024  # a small map is enlarged (at most 4x) for legible labels
    assert Image.open(png).size == tuple(summary["size_px"])

    png2 = tmp_path / "usd.png"
    assert main(["preview", str(out), "-o", str(png2)]) == 0
    assert "walls" in capsys.readouterr().out
    img = np.asarray(Image.open(png2).convert("RGB"))
    red = (img[..., 0] > 180) & (img[..., 1] < 80) & (img[..., 2] < 80)
    assert red.sum() > 100  # the collision walls were drawn


def test_usda_flag_and_config(tmp_path, capsys):
    yaml = write_map(tmp_path, ring_raster(160, style="thin"))
    cfg = tmp_path / "build.toml"
    cfg.write_text("[geometry]\ntube_diameter_m = 0.2\n[materials]\ntextures = false\n")
    out = tmp_path / "ring.usda"
    assert main(["build", str(yaml), "-o", str(out), "--usda", "--config", str(cfg)]) == 0
    assert out.read_text().startswith("#usda") and "built" in capsys.readouterr().out
    assert main(["build", str(yaml), "-o", str(tmp_path / "x.usdc"), "--usda"]) == 2
    assert "--usda" in capsys.readouterr().err


def test_bad_map_exits_2_with_one_line(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("image: nothing.png\nresolution: 0.05\norigin: [0, 0, 0]\n")
    proc = subprocess.run(
        [
            sys.executable,
            "-c",
            "import sys; from roboracer_arena.cli import main; sys.exit(main())",
            "build",
            str(bad),
            "-o",
            str(tmp_path / "bad.usdc"),
        ],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "nothing.png" in lines[0] and lines[0].startswith("roboracer-arena build: error:")
    assert not (tmp_path / "bad.usdc").exists()


def test_preview_of_a_generated_track_labels_features(tmp_path, capsys):
    from roboracer_arena import TrackSpec, generate_track
    from roboracer_arena.generate import Acceptance, write_outputs

    outcome = generate_track(TrackSpec(hairpins=2, chicanes=1), seed=0)
    assert isinstance(outcome, Acceptance)
    paths = write_outputs(outcome, tmp_path / "gen")
    png = tmp_path / "gen.png"
    assert main(["preview", str(paths["map_yaml"]), "-o", str(png), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert "generated centreline" in summary["drawn"] and "features" in summary["drawn"]
    kinds = sorted(f["kind"] for f in summary["features"])
    assert kinds.count("hairpin") == 2 and kinds.count("chicane") == 1


def test_preview_of_a_stage_whose_map_is_gone(tmp_path, capsys):
    import shutil

    yaml = write_map(tmp_path / "maps", ring_raster(160, style="filled"))
    out = tmp_path / "ring.usdc"
    assert main(["build", str(yaml), "-o", str(out), "--no-textures"]) == 0
    shutil.rmtree(tmp_path / "maps")
    capsys.readouterr()
    assert main(["preview", str(out), "-o", str(tmp_path / "p.png"), "--json"]) == 0
    drawn = json.loads(capsys.readouterr().out)["drawn"]
    assert "map" not in drawn and {"walls", "ducts", "floor outline"} <= set(drawn)


def test_preview_of_a_non_stage_is_bad_input(tmp_path, capsys):
    bad = tmp_path / "x.usda"
    bad.write_text("not usd at all")
    assert main(["preview", str(bad), "-o", str(tmp_path / "x.png")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "x.usda" in err


def test_start_pose_off_the_corridor_is_bad_input(tmp_path, capsys):
    yaml = write_map(tmp_path, ring_raster(160, style="filled"))  # 8 m map, centre (-1, -1) + 4 m is the infield
    assert main(["build", str(yaml), "-o", str(tmp_path / "a.usdc"), "--start=-1.0,-1.0"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("roboracer-arena build: error:") and "\n" not in err
    assert main(["build", str(yaml), "-o", str(tmp_path / "a.usdc"), "--start", "x,y"]) == 2
    assert "start pose" in capsys.readouterr().err
    assert not (tmp_path / "a.usdc").exists()
