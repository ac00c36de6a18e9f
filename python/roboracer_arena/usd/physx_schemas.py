"""PhysX settings on the stage, authored through ``physx-usd-schemas`` (the ``physx`` extra).

The package registers the codeless ``Physx*`` schemas with stock usd-core. USD builds
its schema registry once, at the first schema lookup of the process, and ignores plugins
registered later: :func:`register` must therefore run before any stage is authored or
opened. ``roboracer_arena.usd`` calls it when it is first imported (the package's own
``import roboracer_arena`` does not import pxr). Without the extra the stage carries the
UsdPhysics schemas only and still loads, validates and parses in usd-core.

Authored (see :class:`~roboracer_arena.config.build.StagePhysicsConfig`):

* ``/World/PhysicsScene``: ``PhysxSceneAPI`` with the TGS solver (the paper's), the
  simulator's steps per second, CCD enabled, CPU dynamics;
* every collider: ``PhysxCollisionAPI`` contact and rest offsets for a 1:10 car.
"""

from __future__ import annotations

import warnings
from typing import Any

from pxr import Usd

from ..config.build import StagePhysicsConfig

_STATE: dict[str, bool] = {}


def register() -> bool:
    """Register the PhysX schemas with usd-core if ``physx-usd-schemas`` is installed;
    True when they are usable in this process. Idempotent and cheap after the first call."""
    if "ok" not in _STATE:
        try:
            import physx_usd_schemas  # noqa: F401  (its import registers the plugins)
        except ImportError:
            _STATE["ok"] = False
        else:
            _STATE["ok"] = bool(Usd.SchemaRegistry().FindAppliedAPIPrimDefinition("PhysxSceneAPI"))
            if not _STATE["ok"]:
                warnings.warn(
                    "physx-usd-schemas is installed but usd-core built its schema registry before the PhysX "
                    "schemas were registered (import roboracer_arena.usd before other pxr use); the stage gets "
                    "UsdPhysics settings only",
                    RuntimeWarning,
                    stacklevel=2,
                )
    return _STATE["ok"]


def available() -> bool:
    """True when PhysX settings will be authored (the extra is installed and registered)."""
    return register()


def apply_scene(scene_prim: Usd.Prim, physics: StagePhysicsConfig) -> bool:
    """PhysxSceneAPI on the physics scene; False (nothing authored) without the extra."""
    if not register():
        return False
    from physx_usd_schemas import PhysxSchema

    api: Any = PhysxSchema.PhysxSceneAPI.Apply(scene_prim)
    api.CreateSolverTypeAttr("TGS")
    api.CreateTimeStepsPerSecondAttr(int(physics.time_steps_per_second))
    api.CreateEnableCCDAttr(True)
    api.CreateEnableGPUDynamicsAttr(False)
    api.CreateBroadphaseTypeAttr("MBP")
    return True


def apply_collider(prim: Usd.Prim, physics: StagePhysicsConfig) -> bool:
    """PhysxCollisionAPI contact and rest offsets on a collider; False without the extra."""
    if not register():
        return False
    from physx_usd_schemas import PhysxSchema

    api: Any = PhysxSchema.PhysxCollisionAPI.Apply(prim)
    api.CreateContactOffsetAttr(float(physics.contact_offset_m))
    api.CreateRestOffsetAttr(float(physics.rest_offset_m))
    return True
