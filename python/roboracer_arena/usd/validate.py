"""Run every registered ``pxr.UsdValidation`` validator on a stage."""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from pxr import Usd, UsdValidation


@dataclass(frozen=True)
class Finding:
    """One validation finding: severity (``Error``, ``Warn``, ``Info``), name and message."""

    severity: str
    name: str
    message: str

    def __str__(self) -> str:
        return f"{self.severity} {self.name}: {self.message}"


@lru_cache(maxsize=1)
def _context() -> UsdValidation.ValidationContext:
    validators = UsdValidation.ValidationRegistry().GetOrLoadAllValidators()
    return UsdValidation.ValidationContext(validators)


def validate_stage(stage_or_path: Usd.Stage | str | Path) -> list[Finding]:
    """All findings of every validator usd-core registers (core, geom, shade, physics,
    utils, ...); an empty list or only non-``Error`` entries means the stage is valid."""
    stage = stage_or_path if isinstance(stage_or_path, Usd.Stage) else Usd.Stage.Open(str(stage_or_path))
    out = []
    for err in _context().Validate(stage):
        if err.HasNoError():
            continue
        out.append(Finding(err.GetType().displayName, str(err.GetName()), err.GetMessage()))
    return out


def validation_errors(stage_or_path: Usd.Stage | str | Path) -> list[Finding]:
    """Only the findings of severity ``Error``."""
    return [f for f in validate_stage(stage_or_path) if f.severity == "Error"]
