"""USD authoring (usd-core): the track stage, its materials and textures, validation and
read-back. :func:`write_stage` takes world-frame :class:`StageMesh` records; the builder
(:mod:`roboracer_arena.builder`) makes them from the corridor geometry."""

from . import physx_schemas

# Before any stage is read or authored: USD ignores schema plugins registered after its
# first schema lookup (see physx_schemas). A no-op without the `physx` extra.
physx_schemas.register()

from .readback import open_stage, read_meshes, stage_metadata  # noqa: E402
from .stage import METADATA_KEY, StageMesh, WrittenStage, author_stage, write_stage  # noqa: E402
from .validate import Finding, validate_stage, validation_errors  # noqa: E402

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
