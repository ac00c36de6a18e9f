"""WGS84 geodesy for the GeoJSON circuits: a transverse Mercator projection (Krüger's
series, as in Karney 2011, accurate to well under a millimetre within a few hundred
kilometres of the central meridian) centred on each circuit, and Vincenty's inverse
formula for geodesic distances, used to check the projection.

Transverse Mercator is conformal, so shapes (corner radii, angles) are kept; with scale
factor 1 on the central meridian, the scale error at a circuit's edge (≤ 2 km away) is
below 1 + x²/(2R²) ≈ 1 + 5·10⁻⁸, far below anything a 1:10 raster can show.
"""

from __future__ import annotations

import math

import numpy as np

WGS84_A = 6378137.0
WGS84_F = 1 / 298.257223563

_N = WGS84_F / (2 - WGS84_F)
_E = math.sqrt(WGS84_F * (2 - WGS84_F))
_A_RECT = WGS84_A / (1 + _N) * (1 + _N**2 / 4 + _N**4 / 64 + _N**6 / 256)
_ALPHA = (
    _N / 2 - 2 * _N**2 / 3 + 5 * _N**3 / 16 + 41 * _N**4 / 180,
    13 * _N**2 / 48 - 3 * _N**3 / 5 + 557 * _N**4 / 1440,
    61 * _N**3 / 240 - 103 * _N**4 / 140,
    49561 * _N**4 / 161280,
)


def _tm_raw(lat_deg: np.ndarray, dlon_deg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(easting, northing) in metres for longitudes relative to the central meridian."""
    phi = np.radians(lat_deg)
    lam = np.radians(dlon_deg)
    s = np.sin(phi)
    t = np.sinh(np.arctanh(s) - _E * np.arctanh(_E * s))
    xi_p = np.arctan2(t, np.cos(lam))
    eta_p = np.arctanh(np.sin(lam) / np.sqrt(1 + t * t))
    xi, eta = xi_p.copy(), eta_p.copy()
    for j, a in enumerate(_ALPHA, start=1):
        xi += a * np.sin(2 * j * xi_p) * np.cosh(2 * j * eta_p)
        eta += a * np.cos(2 * j * xi_p) * np.sinh(2 * j * eta_p)
    return _A_RECT * eta, _A_RECT * xi


def project_local(lonlat: np.ndarray, centre: tuple[float, float] | None = None) -> np.ndarray:
    """Project ``(N, 2)`` WGS84 ``[lon, lat]`` degrees to local metres ``(x east, y north)``.

    Transverse Mercator (scale 1) with its central meridian through ``centre`` (default:
    the centre of the bounding box); the centre maps to (0, 0).
    """
    ll = np.asarray(lonlat, dtype=float)
    if ll.ndim != 2 or ll.shape[1] != 2:
        raise ValueError(f"lonlat must have shape (N, 2), got {ll.shape}")
    if centre is None:
        centre = (float((ll[:, 0].min() + ll[:, 0].max()) / 2), float((ll[:, 1].min() + ll[:, 1].max()) / 2))
    lon0, lat0 = centre
    dlon = (ll[:, 0] - lon0 + 180.0) % 360.0 - 180.0
    x, y = _tm_raw(ll[:, 1], dlon)
    _, y0 = _tm_raw(np.array([lat0]), np.array([0.0]))
    return np.column_stack([x, y - y0[0]])


def geodesic_distance(lon1: float, lat1: float, lon2: float, lat2: float) -> float:
    """Geodesic distance (m) on the WGS84 ellipsoid, Vincenty's inverse formula."""
    a, f = WGS84_A, WGS84_F
    b = a * (1 - f)
    L = math.radians(lon2 - lon1)
    U1 = math.atan((1 - f) * math.tan(math.radians(lat1)))
    U2 = math.atan((1 - f) * math.tan(math.radians(lat2)))
    sinU1, cosU1, sinU2, cosU2 = math.sin(U1), math.cos(U1), math.sin(U2), math.cos(U2)
    lam = L
    for _ in range(200):
        sin_lam, cos_lam = math.sin(lam), math.cos(lam)
        sin_sigma = math.hypot(cosU2 * sin_lam, cosU1 * sinU2 - sinU1 * cosU2 * cos_lam)
        if sin_sigma == 0:
            return 0.0
        cos_sigma = sinU1 * sinU2 + cosU1 * cosU2 * cos_lam
        sigma = math.atan2(sin_sigma, cos_sigma)
        sin_alpha = cosU1 * cosU2 * sin_lam / sin_sigma
        cos2_alpha = 1 - sin_alpha**2
        cos_2sm = cos_sigma - 2 * sinU1 * sinU2 / cos2_alpha if cos2_alpha else 0.0
        C = f / 16 * cos2_alpha * (4 + f * (4 - 3 * cos2_alpha))
        lam_prev = lam
        lam = L + (1 - C) * f * sin_alpha * (sigma + C * sin_sigma * (cos_2sm + C * cos_sigma * (-1 + 2 * cos_2sm**2)))
        if abs(lam - lam_prev) < 1e-13:
            break
    u2 = cos2_alpha * (a * a - b * b) / (b * b)
    A = 1 + u2 / 16384 * (4096 + u2 * (-768 + u2 * (320 - 175 * u2)))
    B = u2 / 1024 * (256 + u2 * (-128 + u2 * (74 - 47 * u2)))
    d_sigma = (
        B
        * sin_sigma
        * (
            cos_2sm
            + B
            / 4
            * (cos_sigma * (-1 + 2 * cos_2sm**2) - B / 6 * cos_2sm * (-3 + 4 * sin_sigma**2) * (-3 + 4 * cos_2sm**2))
        )
    )
    return b * A * (sigma - d_sigma)


def geodesic_length(lonlat: np.ndarray, closed: bool = True) -> float:
    """Geodesic length (m) of a polyline of ``[lon, lat]`` vertices."""
    ll = np.asarray(lonlat, dtype=float)
    pts = np.vstack([ll, ll[:1]]) if closed else ll
    return float(sum(geodesic_distance(*pts[i], *pts[i + 1]) for i in range(len(pts) - 1)))
