"""Minimum-curvature raceline: a quadratic programme in the lateral offsets ``alpha`` of a
reference line's points along their normals, solved with OSQP, then re-linearised
about its own solution a few times (TUM's iterative ``mincurv_iqp``).

With the reference sampled every ``h`` metres, unit tangents ``t_i`` and left normals
``n_i``, the moved points are ``p_i = r_i + alpha_i n_i`` and their curvature is
linearised as TUM does -- the second derivative from the moved points, the first
derivative frozen at the reference:

    kappa_i ~ t_i x (p_{i+1} - 2 p_i + p_{i-1}) / h^2,

which is linear in ``alpha``. The QP minimises ``sum kappa_i^2`` subject to
``-right_i <= alpha_i <= left_i`` (:mod:`.bounds`). The frozen first derivative is exact
only for small moves, so the solution becomes the next reference (resampled, with new
normals and new bounds) and the QP is solved again.

The optional weights make it a minimum-*time* heuristic (:mod:`.plan`): the curvature at
slow points costs more, since that is where a smaller curvature buys lap time.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import osqp
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import SimulationError
from .bounds import Clearance, lateral_bounds
from .geometry import ClosedPath, closed_path, smoothed

#: Gaussian smoothing (m) of the first reference line (a raster centreline zigzags).
REFERENCE_SMOOTHING_M = 0.6
#: Largest offset towards a curve's centre, as a fraction of the reference's radius there.
FOLD_FRACTION = 0.7
#: Re-linearising stops once no point moves more than this (m).
SETTLED_M = 0.005
#: OSQP's tolerances (polishing then makes the active set exact).
EPS = 1e-6


@dataclass(frozen=True)
class OffsetSolution:
    """The QP's offsets ``alpha`` (N,) along the reference normals, within ``[-right, left]``."""

    alpha: np.ndarray
    left: np.ndarray
    right: np.ndarray
    status: str


def curvature_matrix(ref: ClosedPath) -> tuple[sp.csc_matrix, np.ndarray]:
    """``(A, c)`` with the linearised curvature ``kappa = A @ alpha + c`` of the reference
    ``ref`` moved by ``alpha`` along its normals (cyclic tridiagonal ``A``)."""
    n = len(ref.xy)
    h2 = float(np.mean(ref.ds)) ** 2
    t = np.column_stack([np.cos(ref.psi), np.sin(ref.psi)])
    nrm = ref.normals
    nxt, prv = np.roll(np.arange(n), -1), np.roll(np.arange(n), 1)

    def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]

    second = ref.xy[nxt] - 2.0 * ref.xy + ref.xy[prv]
    c = cross(t, second) / h2
    rows = np.tile(np.arange(n), 3)
    cols = np.concatenate([prv, np.arange(n), nxt])
    vals = np.concatenate([cross(t, nrm[prv]), -2.0 * cross(t, nrm), cross(t, nrm[nxt])]) / h2
    return sp.csc_matrix((vals, (rows, cols)), shape=(n, n)), c


def solve_offsets(
    ref: ClosedPath, left: np.ndarray, right: np.ndarray, weights: np.ndarray | None = None
) -> np.ndarray:
    """The offsets minimising ``sum w_i kappa_i^2`` within ``[-right, left]``."""
    a, c = curvature_matrix(ref)
    n = len(c)
    w = sp.diags(np.ones(n) if weights is None else np.asarray(weights, dtype=np.float64))
    scale = float(np.mean(ref.ds)) ** 2  # objective in (h^2 kappa)^2: numbers near 1
    a, c = a * scale, c * scale
    p = (a.T @ w @ a + sp.identity(n, format="csc") * 1e-10).tocsc()
    q = a.T @ (w @ c)
    lo, hi = -np.asarray(right, dtype=np.float64), np.asarray(left, dtype=np.float64)
    x = _interior_point(p, q, lo, hi)
    if x is None:
        x = _osqp(p, q, lo, hi)
    return np.clip(x, lo, hi)


def _interior_point(
    p: sp.csc_matrix, q: np.ndarray, lo: np.ndarray, hi: np.ndarray, tol: float = 1e-9, max_iter: int = 80
) -> np.ndarray | None:
    """Primal-dual interior point for ``min 1/2 x'Px + q'x, lo <= x <= hi``: each Newton
    step is one sparse solve of the banded ``P + diag``, and 20-40 steps settle it however
    badly ``P`` is conditioned (a square of second differences is). Variables whose box is
    empty are held fixed. None if it does not converge."""
    fixed = hi - lo <= 1e-9
    x = np.where(fixed, 0.5 * (lo + hi), 0.5 * (lo + hi))
    free = np.flatnonzero(~fixed)
    if len(free) == 0:
        return x
    p_csr = p.tocsr()
    pf = p_csr[free][:, free].tocsc()
    qf = q[free] + p_csr[free][:, np.flatnonzero(fixed)] @ x[fixed]
    lof, hif = lo[free], hi[free]
    xf = 0.5 * (lof + hif)
    z1 = np.ones(len(free))
    z2 = np.ones(len(free))
    eye = sp.identity(len(free), format="csc")
    for _ in range(max_iter):
        s1, s2 = xf - lof, hif - xf
        rd = pf @ xf + qf - z1 + z2
        mu = float(np.dot(s1, z1) + np.dot(s2, z2)) / (2 * len(xf))
        if np.max(np.abs(rd)) < tol and mu < tol:
            break
        sigma_mu = 0.1 * mu
        dmat = z1 / s1 + z2 / s2
        rhs = -rd + (sigma_mu / s1 - z1) - (sigma_mu / s2 - z2)
        dx = spla.spsolve((pf + eye.multiply(dmat[:, None])).tocsc(), rhs)
        if not np.isfinite(dx).all():
            return None
        dz1 = (sigma_mu - z1 * s1 - z1 * dx) / s1
        dz2 = (sigma_mu - z2 * s2 + z2 * dx) / s2
        step = 1.0
        for v, dv in ((s1, dx), (s2, -dx), (z1, dz1), (z2, dz2)):
            neg = dv < 0
            if neg.any():
                step = min(step, 0.99 * float(np.min(-v[neg] / dv[neg])))
        xf, z1, z2 = xf + step * dx, z1 + step * dz1, z2 + step * dz2
    else:
        return None
    x[free] = xf
    return x


def _osqp(p: sp.csc_matrix, q: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """The same QP with OSQP (the fallback should the interior point not converge)."""
    prob = osqp.OSQP()
    prob.setup(
        sp.triu(p, format="csc"),
        q,
        sp.identity(len(q), format="csc"),
        lo,
        hi,
        verbose=False,
        eps_abs=EPS,
        eps_rel=EPS,
        max_iter=50000,
        polishing=True,
    )
    res = prob.solve()
    x = res.x
    if x is None or not np.isfinite(x).all():
        raise SimulationError(f"raceline QP failed: {res.info.status}")
    return np.asarray(x)


def iterate_min_curvature(
    reference: np.ndarray,
    clearance: Clearance,
    half_width: float,
    step: float = 0.2,
    iterations: int = 3,
    max_reach: float = 5.0,
    weights: Callable[[ClosedPath], np.ndarray] | None = None,
    smooth: bool = True,
) -> tuple[ClosedPath, OffsetSolution]:
    """The minimum-curvature line within the walls less ``half_width``, starting from the
    ring ``reference`` (e.g. the centreline), solved ``iterations`` times, each about the
    last solution. Returns the final line (resampled every ``step`` m) and the last QP.
    ``smooth``: smooth the first reference (:data:`REFERENCE_SMOOTHING_M`)."""
    ref = closed_path(reference, step)
    if smooth:  # a raster centreline; a planned line (already inside the margin) is not smoothed
        ref = smoothed(ref, REFERENCE_SMOOTHING_M)
    sol = OffsetSolution(np.zeros(len(ref.xy)), np.zeros(len(ref.xy)), np.zeros(len(ref.xy)), "not run")
    for _ in range(max(1, iterations)):
        left, right = lateral_bounds(ref.xy, ref.normals, clearance, half_width, max_reach)
        # Offsets towards a curve's centre stay short of its radius: beyond it the normals
        # cross and the moved points would fold back on each other.
        inner = FOLD_FRACTION / np.maximum(np.abs(ref.kappa), 1e-9)
        left = np.where(ref.kappa > 0, np.minimum(left, inner), left)
        right = np.where(ref.kappa < 0, np.minimum(right, inner), right)
        alpha = solve_offsets(ref, left, right, None if weights is None else weights(ref))
        sol = OffsetSolution(alpha, left, right, "solved")
        ref = closed_path(ref.xy + alpha[:, None] * ref.normals, step)
        if np.max(np.abs(alpha)) < SETTLED_M:
            break
    return ref, sol
