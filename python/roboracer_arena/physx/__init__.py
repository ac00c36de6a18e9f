"""PhysX (ovphysx on the CPU) as a second judge of the stages ``build`` writes: the
``physx`` extra (``pip install 'roboracer-arena[physx]'``). :func:`check_stage` is the
``roboracer-arena physx-check`` command; :class:`PhysxScene` is a stage loaded in PhysX.
Nothing here is imported by the rest of the package unless asked for."""

from .runtime import PhysxScene, available, require

__all__ = ["PhysxScene", "available", "check_stage", "require"]


def __getattr__(name: str):  # the check pulls in the env and the corridor: load on use
    if name == "check_stage":
        from .check import check_stage

        return check_stage
    raise AttributeError(name)
