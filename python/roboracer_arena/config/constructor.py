"""The constructor's own constants (not part of a request): wall thickness t_w,
inter-corridor clearance d_c, hall margin m_h, raster resolution and the candidate cap.

Defaults reproduce the paper: with the default 1.5 m corridor the pitch is
p = w + 2 t_w + d_c = 1.5 + 0.30 + 0.35 = 2.15 m, and m_h = 0.5 m gives
L_max ≈ 123.7 m for a 20 × 15 m hall.
"""

from __future__ import annotations

from pydantic import ConfigDict, Field

from ..foundation.strict import NumbersAreNumbers


class ConstructorConfig(NumbersAreNumbers):
    """Geometry constants shared by the screen, the constructors and the validator."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    wall_thickness_m: float = Field(
        0.15, gt=0, description="Wall thickness t_w (m): about one air-duct radius (0.33 m ducts)."
    )
    clearance_m: float = Field(
        0.35,
        ge=0,
        description="Inter-corridor clearance d_c (m) between walls of neighbouring passes; with t_w gives p = 2.15 m at w = 1.5 m.",
    )
    hall_margin_m: float = Field(0.5, ge=0, description="Hall margin m_h (m) kept clear on every side of the hall.")
    resolution_m: float = Field(
        0.05, ge=1e-4, le=1.0, description="Raster resolution Δ (m per cell), the usual RoboRacer SLAM resolution."
    )
    map_margin_m: float = Field(0.25, ge=0, description="Unknown border (m) around the outer wall in the written map.")
    max_candidates: int = Field(800, ge=1, le=800, description="Candidate cap of Algorithm 1 (the paper's 800).")

    def pitch(self, corridor_width_m: float) -> float:
        """Centreline pitch p = w + 2 t_w + d_c (Eq. 1)."""
        return corridor_width_m + 2 * self.wall_thickness_m + self.clearance_m
