"""Simulation environments: native simulator configuration (:mod:`.config`) and the
gymnasium ``RoboRacerArena-v0`` env / vector env built on ``_core.Simulator``."""

from .config import LidarConfig, PhysicsConfig, SimConfig, VehicleConfig

__all__ = ["LidarConfig", "PhysicsConfig", "SimConfig", "VehicleConfig"]
