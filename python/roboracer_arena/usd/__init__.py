"""USD authoring (usd-core): the track stage, its materials and textures, validation and
read-back. :func:`write_stage` takes world-frame :class:`StageMesh` records; the builder
(:mod:`roboracer_arena.builder`) makes them from the corridor geometry."""

from .readback import open_stage, read_meshes, stage_metadata
from .stage import METADATA_KEY, StageMesh, WrittenStage, author_stage, write_stage
from .validate import Finding, validate_stage, validation_errors

__all__ = [
    "METADATA_KEY",
    "Finding",
    "StageMesh",
    "WrittenStage",
    "author_stage",
    "open_stage",
    "read_meshes",
    "stage_metadata",
    "validate_stage",
    "validation_errors",
    "write_stage",
]
