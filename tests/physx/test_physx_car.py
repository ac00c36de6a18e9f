"""``build --car``: the paper's car as a PhysX vehicle, driven a full lap through ovphysx
on the CPU by the reference pure pursuit (issue #23). Without the ``physx`` extra,
``build --car`` is refused with the extra named (exit 2)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from roboracer_arena.physx import available


@pytest.mark.slow
@pytest.mark.skipif(
    not available(), reason="the 'physx' extra (ovphysx, physx-usd-schemas) is not installed; CI installs it"
)
def test_the_car_laps_berlin_in_physx(sources, tmp_path):
    from pxr import Usd

    from roboracer_arena import build_environment
    from roboracer_arena.physx.check import check_stage, track_of_stage
    from roboracer_arena.physx.drive import drive_native_lap, drive_physx_lap

    stage_path = tmp_path / "berlin.usdc"
    build_environment(sources / "f1tenth-gym" / "maps" / "berlin.yaml", stage_path, car=True)
    stage = Usd.Stage.Open(str(stage_path))
    car = stage.GetPrimAtPath("/World/Car")
    assert {"PhysxVehicleAPI", "PhysxVehicleControllerAPI", "PhysxVehicleSteeringAPI"} <= set(car.GetAppliedSchemas())
    assert car.GetAttribute("physics:mass").Get() == pytest.approx(4.885)
    assert len([c for c in car.GetChildren() if "PhysxVehicleWheelAttachmentAPI" in c.GetAppliedSchemas()]) == 4

    track = track_of_stage(stage_path)
    physx = drive_physx_lap(stage_path, track, max_seconds=60.0)
    ours = drive_native_lap(track, max_seconds=60.0)
    assert physx.completed and ours.completed, (physx, ours)
    # Same car, same driver, two engines: lap times within 40 %, and the PhysX car stays on the track.
    assert abs(physx.lap_time_s - ours.lap_time_s) <= 0.4 * ours.lap_time_s, (physx, ours)
    assert physx.max_deviation_m < 1.2 and physx.steps_per_second > 0
    # The sensor's own chassis does not blind the PhysX lidar; the stage with the car still holds.
    assert check_stage(stage_path, points=2, seconds=1.0).ok


_WITHOUT_EXTRA = r"""
import sys
sys.modules["physx_usd_schemas"] = None  # as if the extra were not installed
from roboracer_arena.cli import main
sys.exit(main(["build", sys.argv[1], "-o", sys.argv[2], "--car"]))
"""


def test_build_car_without_the_extra_names_it(sources, tmp_path):
    out = tmp_path / "berlin.usdc"
    run = subprocess.run(
        [sys.executable, "-c", _WITHOUT_EXTRA, str(sources / "f1tenth-gym" / "maps" / "berlin.yaml"), str(out)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 2, run.stderr[-2000:]
    assert "physx" in run.stderr and "--car" in run.stderr
    assert not out.exists()
