"""Formula 1 and other real circuits at 1:10 vehicle scale: converters for the TUM
racetrack database (CSV) and the bacinger GeoJSON circuits, spline smoothing, width
reduction where sections would merge, rasterisation and accuracy measurement.

``roboracer-arena circuits`` builds them all; :func:`build_all` is the Python entry.
"""

from .build import CircuitConfig, build_all, build_circuit
from .geometry import reduce_widths, smooth_resample
from .projection import geodesic_distance, geodesic_length, project_local
from .sources import CircuitInput, circuit_inputs, read_geojson, read_tum_csv

__all__ = [
    "CircuitConfig",
    "CircuitInput",
    "build_all",
    "build_circuit",
    "circuit_inputs",
    "geodesic_distance",
    "geodesic_length",
    "project_local",
    "read_geojson",
    "read_tum_csv",
    "reduce_widths",
    "smooth_resample",
]
