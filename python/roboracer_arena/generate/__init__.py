"""Requirements → track: :func:`generate_track` (screen, constructor, rasteriser and raster
validator; Algorithm 1), the three typed outcomes and output writing. (The paper's DE /
random baselines live in a checkout's ``benchmarks/``, not in the package.)"""

from .nearest import NearestSpecs, Suggestion, nearest_specs
from .outcomes import Acceptance, GenerationFailure, Outcome, Rejection
from .outputs import write_outputs
from .pipeline import CONSTRUCTORS, derived_geometry, generate_track, rasterise, screen, validate_map
from .report import Check, CurveAnalysis, DerivedGeometry, FeatureAt, Measurements, ScreenResult, ValidationReport

__all__ = [
    "Acceptance",
    "CONSTRUCTORS",
    "Check",
    "CurveAnalysis",
    "DerivedGeometry",
    "FeatureAt",
    "Measurements",
    "ScreenResult",
    "ValidationReport",
    "GenerationFailure",
    "NearestSpecs",
    "Suggestion",
    "nearest_specs",
    "Outcome",
    "Rejection",
    "derived_geometry",
    "generate_track",
    "rasterise",
    "screen",
    "validate_map",
    "write_outputs",
]
