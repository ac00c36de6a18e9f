"""Issue 28: what the validator's own rules prove about short laps with a chicane, and
what loops with the detector's *measured* spacing need. (Not in the wheel.)

For the 20 m laps at w = 2 m with a chicane (the practical region's short misses) it prints:

* ``proven``: the floor that follows from rules the validator states. The measured
  curvature is bounded by the min-radius check (|κ| ≤ 1 / r_b, r_b = 0.95 r_min − Δ), so
  the lap is at least r_b times its absolute turning. A counter-clockwise lap turns 2π;
  a chicane has a right turn of ≥ 45°, so the absolute turning is ≥ 2π + 2·π/4. Turns of
  one sense closer than 0.8 r_c are merged; a turn of ≥ 135° is a hairpin; so the left
  turning 2π + π/4 needs ≥ 3 separate left turns besides a hairpin (each < 135°), and each
  pair of them that is not split by the chicane's right turn needs ≥ 0.8 r_c of gap (whose
  own turning, below 1/(8 r_c), is taken off the turning floor). This assumes the smoothed
  centreline turns once (Σ κ ds = 2π), which the validator does not check.
  Turning hidden in runs that never reach 1/(3 r_c) costs more length per radian, so it
  cannot lower the floor.
* ``polygon``: the shortest closed polygon loop (fillets of r_c, straights of 1.5 r_c
  between same-sense turns, 0.3 r_c links next to opposite turns, corner angles free in
  [55°, 128°], chicane turns free in [60°, 128°], spare length only on the long straights)
  over 20 000 random angle draws per layout, closure solved as a linear programme. This
  is a construction's need under the detector's *measured* spacing, not a proof.
* ``taper``: the detector's own analysis (``_core.analyse_curve``) of a rectangle whose
  two short sides are 90° corner pairs at a given straight, with plain arcs and with
  linear curvature ramps: whether the pair reads as one hairpin. The straight that keeps
  two corners apart depends on the curvature profile, so it is not a rule that bounds
  every curve.

Usage: ``python -m benchmarks.spacing_floor``.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import linprog

from roboracer_arena import _core
from roboracer_arena.config.constructor import ConstructorConfig
from roboracer_arena.generate import derived_geometry
from roboracer_arena.spec import TrackSpec

LONG, LINK = 1.5, 0.3  # straights in r_c: between same-sense turns, next to an opposite turn
CORNER, CHICANE = (55.0, 128.0), (60.0, 128.0)  # degrees


def proven_floor(spec: TrackSpec, cfg: ConstructorConfig) -> float:
    """Least lap (m) the validator's stated rules allow for one chicane and h ≤ 1 hairpins."""
    d = derived_geometry(spec, cfg)
    r_b = 0.95 * d.r_min - cfg.resolution_m
    turning = 2 * math.pi + 2 * (math.pi / 4)
    # Left turning 2π + π/4 in turns < 135° (a hairpin may take any amount): the chicane's
    # left turn and ≥ 2 more without a hairpin (3 × 135° = 405° is not enough strictly),
    # 1 more with one; separations between consecutive left turns not split by the right turn.
    separations = 2 if spec.hairpins == 0 else 1
    # A gap may still turn below 1/(8 r_c): its length counts, less the turning it takes.
    gap = 0.8 * d.corner_radius * (1 - r_b / (8 * d.corner_radius))
    return r_b * turning + separations * gap


def _need(angles: np.ndarray, rc: float) -> float:
    """Least closed-loop length (m) of a polygon with these turn angles (rad), or inf."""
    n = len(angles)
    short = [angles[i] * angles[(i + 1) % n] < 0 for i in range(n)]
    tan = rc * np.tan(np.abs(angles) / 2)
    least = np.array([tan[i] + tan[(i + 1) % n] + (LINK if short[i] else LONG) * rc for i in range(n)])
    head = np.cumsum(angles)
    end = [float(np.sum(least * np.cos(head))), float(np.sum(least * np.sin(head)))]
    long_ = [i for i in range(n) if not short[i]]
    a_eq = [[math.cos(head[i]) for i in long_], [math.sin(head[i]) for i in long_]]
    lp = linprog(np.ones(len(long_)), A_eq=a_eq, b_eq=[-end[0], -end[1]], bounds=[(0, None)] * len(long_))
    if not lp.success:
        return math.inf
    saving = float(np.sum(rc * (2 * np.tan(np.abs(angles) / 2) - np.abs(angles))))
    return float(least.sum()) - saving + float(lp.fun)


def polygon_need(rc: float, draws: int = 20_000) -> tuple[float, list[float]]:
    """Shortest loop over three corners and a chicane (both chicane senses, chicane after
    the third corner or between the first two), angles drawn at random."""
    rng = np.random.default_rng(0)
    best = (math.inf, [])
    lo, hi = (math.radians(v) for v in CORNER)
    clo, chi = (math.radians(v) for v in CHICANE)
    for _ in range(draws):
        c1, c2 = rng.uniform(lo, hi, 2)
        a, b = rng.uniform(clo, chi, 2)
        for sense in (1, -1):
            c3 = 2 * math.pi - c1 - c2 - sense * (a - b)
            if not lo <= c3 <= hi:
                continue
            ch = [sense * a, -sense * b]
            for angles in ([c1, c2, c3, *ch], [c1, *ch, c2, c3]):
                v = _need(np.array(angles), rc)
                if v < best[0]:
                    best = (v, [round(math.degrees(x), 1) for x in angles])
    return best


def taper_reads(rc: float) -> list[str]:
    """How the detector reads 90° corner pairs at a few straights, plain or ramped."""
    ds, kmax = 0.005, 1 / rc
    out = []
    for ramp in (0.0, 1.0):
        for gap_rc in (1.0, 1.5):
            up = np.arange(0, ramp, ds) / ramp * kmax if ramp else np.array([])
            arc = np.full(round((math.pi / 2 - kmax * ramp) / kmax / ds), kmax)
            corner = np.concatenate([up, arc, up[::-1]])
            k = np.concatenate(
                [np.concatenate([np.zeros(round(side / ds)), corner]) for side in (12.0, gap_rc * rc) * 2]
            )
            head = np.cumsum(k) * ds
            xy = np.cumsum(np.c_[np.cos(head), np.sin(head)], axis=0) * ds
            a = _core.analyse_curve(xy, rc, 0.0)
            kinds = [f.kind for f in a.features] or ["none"]
            out.append(
                f"ramps {ramp:.1f} m, straight {gap_rc:.1f} r_c: turns "
                f"{[round(math.degrees(t.angle_rad)) for t in a.turns]} → {', '.join(kinds)}"
            )
    return out


def main() -> None:
    cfg = ConstructorConfig()
    for hx, hy, h in ((30.0, 20.0, 0), (20.0, 15.0, 1), (16.0, 12.0, 1)):
        spec = TrackSpec(
            name=f"L20-w2-{hx:g}x{hy:g}-h{h}c1s0",
            lap_length_m=20.0,
            corridor_width_m=2.0,
            hall_x_m=hx,
            hall_y_m=hy,
            hairpins=h,
            chicanes=1,
            sweepers=0,
            direction="counterclockwise",
        )
        print(
            f"{spec.name}: proven floor {proven_floor(spec, cfg):.2f} m; "
            f"validator accepts a lap in [{0.97 * spec.lap_length_m:.2f}, {1.03 * spec.lap_length_m:.2f}] m"
        )
    rc = derived_geometry(spec, cfg).corner_radius
    need, angles = polygon_need(rc)
    print(f"polygon with measured spacing, three corners and a chicane (r_c = {rc:g} m): {need:.2f} m at {angles}°")
    for line in taper_reads(rc):
        print(f"  detector: {line}")


if __name__ == "__main__":
    main()
