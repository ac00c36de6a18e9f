"""The stages ``build`` writes, loaded in PhysX (ovphysx, CPU): single-sided PhysX lidar
parity with our scan and car-sized bodies that stay in the corridor, on a recorded map,
a circuit and a generated track (issue #23), and an open map (levine's floor plan). The control: the same stage with its wall
winding reversed (main's winding before the fix) must fail the check.

Needs the ``physx`` extra; CI installs it (WHEEL_EXTRAS), locally the tests skip without it.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from roboracer_arena.physx import available

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(
        not available(), reason="the 'physx' extra (ovphysx, physx-usd-schemas) is not installed; CI installs it"
    ),
]


def _build(map_yaml, out):
    from roboracer_arena import build_environment

    build_environment(map_yaml, out)
    return out


@pytest.fixture(scope="module")
def berlin_stage(sources, tmp_path_factory):
    return _build(sources / "f1tenth-gym" / "maps" / "berlin.yaml", tmp_path_factory.mktemp("berlin") / "berlin.usdc")


@pytest.fixture(scope="module")
def circuit_stage(sources, tmp_path_factory):
    from roboracer_arena.cli import main

    d = tmp_path_factory.mktemp("circuit")
    assert main(["circuits", "--sources", str(sources), "-o", str(d), "--only", "monaco", "--jobs", "1"]) == 0
    return _build(d / "monaco" / "map.yaml", d / "monaco.usdc")


@pytest.fixture(scope="module")
def generated_stage(tmp_path_factory):
    from roboracer_arena import TrackSpec, generate_track
    from roboracer_arena.generate import write_outputs

    d = tmp_path_factory.mktemp("generated")
    out = generate_track(TrackSpec(lap_length_m=40.0), seed=3)
    paths = write_outputs(out, d)
    return _build(paths["map_yaml"], d / "generated.usdc")


@pytest.mark.parametrize("which", ["berlin_stage", "circuit_stage", "generated_stage"])
def test_fresh_stage_holds_in_physx(which, request):
    from roboracer_arena.physx.check import check_stage

    report = check_stage(request.getfixturevalue(which), points=6, seconds=1.2)
    assert report.lidar.beams == 1081
    assert report.lidar.fraction >= 0.99, report.summary()
    assert report.containment.contained == report.containment.bodies == 6 * 8 * 3, report.summary()
    assert max(report.containment.speeds_m_s) == pytest.approx(7.0)  # the car's top speed
    assert report.ok and report.load_seconds > 0


def _reverse_wall_winding(src, dst):
    """Copy a stage with its collision-wall triangles wound the other way (main's mesh)."""
    from pxr import Usd, UsdGeom

    stage = Usd.Stage.Open(str(src))
    mesh = UsdGeom.Mesh(stage.GetPrimAtPath("/World/Track/Walls"))
    idx = np.asarray(mesh.GetFaceVertexIndicesAttr().Get()).reshape(-1, 3)
    mesh.GetFaceVertexIndicesAttr().Set(idx[:, ::-1].ravel().tolist())
    stage.GetRootLayer().Export(str(dst))
    return dst


def test_the_check_fails_on_walls_facing_away(berlin_stage, tmp_path):
    from roboracer_arena.physx.check import check_stage

    bad = _reverse_wall_winding(berlin_stage, tmp_path / "reversed.usdc")
    report = check_stage(bad, points=3, seconds=1.2)
    assert not report.ok
    assert report.lidar.fraction < 0.5, report.summary()  # single-sided rays see the back faces not at all
    assert report.containment.contained < report.containment.bodies, report.summary()


def test_cli_json_and_exit_codes(berlin_stage, tmp_path, capsys):
    from roboracer_arena.cli import main

    assert main(["physx-check", str(berlin_stage), "--points", "2", "--seconds", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["ok"] and out["lidar"]["beams"] == 1081 and out["containment"]["bodies"] == 48
    bad = _reverse_wall_winding(berlin_stage, tmp_path / "reversed.usdc")
    assert main(["physx-check", str(bad), "--points", "2", "--seconds", "1"]) == 6
    assert "FAILED" in capsys.readouterr().out
    assert main(["physx-check", str(tmp_path / "missing.usdc")]) == 2
    assert "missing.usdc" in capsys.readouterr().err
    (tmp_path / "plain.usda").write_text('#usda 1.0\ndef Xform "World" {}\n')
    assert main(["physx-check", str(tmp_path / "plain.usda")]) == 2
    assert "not a roboracer-arena stage" in capsys.readouterr().err


def test_json_stdout_is_only_json_in_a_fresh_process(berlin_stage):
    """Warp, under ovphysx, greets on stdout when it starts; a fresh process shows whether
    that greeting reaches ``--json`` (in-process tests start Warp once, earlier)."""
    import subprocess
    import sys

    main = "import sys; from roboracer_arena.cli import main; sys.exit(main())"
    cmd = [sys.executable, "-c", main, "physx-check", str(berlin_stage), "--points", "1", "--seconds", "0.5", "--json"]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    assert json.loads(r.stdout)["ok"]


@pytest.fixture(scope="module")
def levine_stage(sources, tmp_path_factory):
    """An open map: levine's hallways leak to the map border, so ``build`` makes it a floor plan."""
    return _build(
        sources / "f1tenth-gym-ros" / "maps" / "levine.yaml", tmp_path_factory.mktemp("levine") / "levine.usdc"
    )


def test_open_map_holds_in_physx(levine_stage, tmp_path):
    from roboracer_arena.physx.check import check_stage, track_of_stage

    track = track_of_stage(levine_stage)
    assert track.is_open and track.source.start_pose == (0.0, 0.0, 0.0)  # the build's start, not a re-guess
    report = check_stage(levine_stage, points=4, seconds=1.2)
    assert report.map_kind == "open"
    assert report.lidar.fraction >= 0.99 and report.lidar.pose == (0.0, 0.0, 0.0), report.summary()
    assert report.containment.points == 4
    assert report.containment.contained == report.containment.bodies == 4 * 8 * 3, report.summary()
    assert report.ok and "free region" in report.summary()
    # every station lies in the building, beside its walls, not on the empty margin by the map edge
    from roboracer_arena.config.sim import SimConfig
    from roboracer_arena.physx.check import probe_plan
    from roboracer_arena.physx.open_probes import FreeRegion

    free = FreeRegion.of_geometry(track.source, (0.0, 0.0))
    xy = np.array(sorted({(x, y) for _, x, y, *_ in probe_plan(track, SimConfig(), 4, free)}))
    assert len(xy) == 4 and np.abs(xy).max() < 30.0
    assert (track.clearance(xy) > 0.5 * np.hypot(0.55, 0.29)).all()
    # the controls: walls facing away fail the lidar (levine's walls are thin, so the far
    # face of each still stops the bodies); with no collision walls at all the bodies escape
    bad = check_stage(_reverse_wall_winding(levine_stage, tmp_path / "reversed.usdc"), points=1, seconds=0.5)
    assert not bad.ok and bad.lidar.fraction < 0.5, bad.summary()
    bad = check_stage(_without_walls(levine_stage, tmp_path / "no-walls.usdc"), points=2, seconds=1.2)
    assert not bad.ok and bad.containment.contained < bad.containment.bodies, bad.summary()
    assert all(e.start_xy is not None for e in bad.containment.escapes)
    assert {e.reason for e in bad.containment.escapes} <= {"left the free region", "passed through a wall"}


def _without_walls(src, dst):
    """Copy a stage without its collision walls."""
    from pxr import Usd

    stage = Usd.Stage.Open(str(src))
    stage.RemovePrim("/World/Track/Walls")
    stage.GetRootLayer().Export(str(dst))
    return dst
