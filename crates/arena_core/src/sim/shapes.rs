//! Analytic test geometry: a stadium (two straights joined by half circles), used by
//! tests and benches before any map is loaded, and by users who want a trivial track.

use std::f64::consts::PI;

/// Closed stadium polyline centred at the origin: straights of length `straight` along
/// x, half circles of radius `r`, counter-clockwise, `n_arc` points per half circle.
pub fn stadium(straight: f64, r: f64, n_arc: usize) -> Vec<[f64; 2]> {
    let h = straight / 2.0;
    let mut pts = Vec::with_capacity(2 * n_arc + 2);
    for (cx, a0) in [(h, -PI / 2.0), (-h, PI / 2.0)] {
        for k in 0..=n_arc {
            let a = a0 + PI * k as f64 / n_arc as f64;
            pts.push([cx + r * a.cos(), r * a.sin()]);
        }
    }
    pts
}

/// The door of [`stadium_track`] for sizes from outside: `straight` ≥ 0, `r` > 0 and
/// 0 < `width` < 2 `r` (so the inner wall keeps a positive radius), all finite.
pub fn check_stadium(straight: f64, r: f64, width: f64) -> crate::Result<()> {
    let ok = |x: f64| x.is_finite() && x > 0.0;
    if !(ok(r) && ok(width) && straight.is_finite() && straight >= 0.0 && width < 2.0 * r) {
        return Err(crate::ArenaError::invalid(
            "stadium_track needs straight >= 0, radius > 0 and 0 < width < 2 radius",
        ));
    }
    Ok(())
}

/// A stadium track: (walls [outer, inner], centreline) for a corridor of width `width`
/// around a centreline stadium of straight `straight` and radius `r`.
pub fn stadium_track(straight: f64, r: f64, width: f64) -> (Vec<Vec<[f64; 2]>>, Vec<[f64; 2]>) {
    let walls = vec![
        stadium(straight, r + width / 2.0, 48),
        stadium(straight, r - width / 2.0, 48),
    ];
    (walls, stadium(straight, r, 96))
}

/// An axis-aligned square room of half-side `h` centred at the origin (one closed wall).
pub fn square_room(h: f64) -> Vec<[f64; 2]> {
    vec![[-h, -h], [h, -h], [h, h], [-h, h]]
}
