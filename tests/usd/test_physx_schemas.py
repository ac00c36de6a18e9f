"""PhysX settings on the stage (issue #23): authored through physx-usd-schemas when the
``physx`` extra is installed; without it the stage still loads, validates and parses in
plain usd-core (checked in a subprocess where the schema package cannot be imported)."""

from __future__ import annotations

import subprocess
import sys

import pytest
from pxr import Usd, UsdPhysics

from builder.synthetic import load_physics, ring_meshes
from roboracer_arena.config.build import BuildConfig
from roboracer_arena.config.sim import SimConfig
from roboracer_arena.errors import ConfigError
from roboracer_arena.usd import physx_schemas, validate_stage, write_stage

META = {"source_map": "/maps/ring.yaml", "resolution": 0.05, "origin": [-5.0, -5.0, 0.0], "build_config": "{}"}


def test_default_steps_per_second_is_the_simulators_dt():
    assert BuildConfig().physics.time_steps_per_second == round(1.0 / SimConfig().physics.dt)


def test_rest_offset_must_stay_below_the_contact_offset():
    with pytest.raises(ConfigError, match="rest_offset_m"):
        BuildConfig.from_dict({"physics": {"contact_offset_m": 0.01, "rest_offset_m": 0.02}})


@pytest.mark.skipif(not physx_schemas.available(), reason="the 'physx' extra (physx-usd-schemas) is not installed")
def test_physx_scene_and_collider_settings(tmp_path):
    out = write_stage(tmp_path / "ring.usdc", ring_meshes(), BuildConfig(), META).path
    stage = Usd.Stage.Open(str(out))
    scene = stage.GetPrimAtPath("/World/PhysicsScene")
    assert "PhysxSceneAPI" in scene.GetAppliedSchemas()
    assert scene.GetAttribute("physxScene:solverType").Get() == "TGS"
    assert scene.GetAttribute("physxScene:timeStepsPerSecond").Get() == 200
    assert scene.GetAttribute("physxScene:enableCCD").Get() is True
    for path in ("/World/Track/Walls", "/World/Track/Floor"):
        prim = stage.GetPrimAtPath(path)
        assert "PhysxCollisionAPI" in prim.GetAppliedSchemas()
        assert prim.GetAttribute("physxCollision:contactOffset").Get() == pytest.approx(0.02)
        assert prim.GetAttribute("physxCollision:restOffset").Get() == pytest.approx(0.0)
    assert validate_stage(stage) == []
    parsed = load_physics(stage)
    assert len(parsed[UsdPhysics.ObjectType.Scene][0]) == 1
    assert len(parsed[UsdPhysics.ObjectType.MeshShape][0]) == 2


_WITHOUT_EXTRA = r"""
import sys
sys.modules["physx_usd_schemas"] = None  # as if the extra were not installed
sys.path.insert(0, sys.argv[2])
from pxr import Usd, UsdPhysics
from builder.synthetic import load_physics, ring_meshes
from roboracer_arena.config.build import BuildConfig
from roboracer_arena.usd import physx_schemas, validate_stage, write_stage
assert not physx_schemas.available()
meta = {"source_map": "/maps/ring.yaml", "resolution": 0.05, "origin": [-5.0, -5.0, 0.0], "build_config": "{}"}
out = write_stage(sys.argv[1] + "/plain.usdc", ring_meshes(), BuildConfig(), meta).path
for path in (str(out), sys.argv[1] + "/with_physx.usdc"):
    stage = Usd.Stage.Open(path)
    assert validate_stage(stage) == [], (path, [str(f) for f in validate_stage(stage)])
    parsed = load_physics(stage)
    assert len(parsed[UsdPhysics.ObjectType.MeshShape][0]) == 2, path
plain = Usd.Stage.Open(str(out))
assert not any(s.startswith("Physx") for s in plain.GetPrimAtPath("/World/PhysicsScene").GetAppliedSchemas())
print("ok")
"""


def test_without_the_extra_stages_load_validate_and_parse(tmp_path):
    from pathlib import Path

    write_stage(tmp_path / "with_physx.usdc", ring_meshes(), BuildConfig(), META)
    tests_dir = str(Path(__file__).resolve().parent.parent)
    run = subprocess.run(
        [sys.executable, "-c", _WITHOUT_EXTRA, str(tmp_path), tests_dir], capture_output=True, text=True, timeout=300
    )
    assert run.returncode == 0 and run.stdout.strip().endswith("ok"), run.stderr[-2000:]
