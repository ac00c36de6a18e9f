//! The polyline toolbox: length, cumulative arc length, signed area, uniform resampling,
//! discrete curvature and minimum radius, and self-intersections. The one owner of these
//! measures: the builder, the curve analysis and (through `_core`) the Python layer all
//! call these.
//!
//! A *closed* polyline does not repeat its first point at the end; the `check_*` doors
//! used by the binding drop one exactly repeated closing point.

use crate::error::{ArenaError, Result};

/// Euclidean distance between two points.
#[inline]
pub fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Length of a polyline, counting the closing edge when `closed`.
pub fn polyline_length(p: &[[f64; 2]], closed: bool) -> f64 {
    let n = p.len();
    if n < 2 {
        return 0.0;
    }
    let edges = if closed { n } else { n - 1 };
    (0..edges).map(|i| dist(p[i], p[(i + 1) % n])).sum()
}

/// Bounding-box size (x, y) of a point set.
pub fn extent(p: &[[f64; 2]]) -> [f64; 2] {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in p {
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    [hi[0] - lo[0], hi[1] - lo[1]]
}

/// Arc length at each vertex, starting at 0. Open: `n` values ending with the length;
/// closed: `n + 1` values, the last being the full loop (back at point 0).
pub fn cumulative_length(p: &[[f64; 2]], closed: bool) -> Vec<f64> {
    let n = p.len();
    let edges = match (n, closed) {
        (0, _) => 0,
        (_, true) => n,
        (_, false) => n - 1,
    };
    let mut cum = Vec::with_capacity(edges + 1);
    cum.push(0.0);
    for i in 0..edges {
        cum.push(cum[i] + dist(p[i], p[(i + 1) % n]));
    }
    if n == 0 {
        cum.clear();
    }
    cum
}

/// Signed area (m²) of a closed polyline: positive when counter-clockwise.
pub fn signed_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    0.5 * (0..n)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
}

/// Where `m` evenly spaced stations fall on a closed polyline: (segment, fraction).
/// `None` when there is nothing to resample (fewer than 2 points, zero length or a
/// spacing that is not positive).
fn stations(p: &[[f64; 2]], spacing: f64) -> Option<Vec<(usize, f64)>> {
    let n = p.len();
    if n < 2 || spacing.is_nan() || spacing <= 0.0 {
        return None;
    }
    let cum = cumulative_length(p, true);
    let total = cum[n];
    if total.is_nan() || total <= 0.0 {
        return None;
    }
    let m = ((total / spacing).round() as usize).max(MIN_RESAMPLED);
    let step = total / m as f64;
    let mut seg = 0;
    let out = (0..m)
        .map(|k| {
            let s = k as f64 * step;
            while seg + 1 < n && cum[seg + 1] < s {
                seg += 1;
            }
            let len = cum[seg + 1] - cum[seg];
            let t = if len > 0.0 {
                ((s - cum[seg]) / len).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (seg, t)
        })
        .collect();
    Some(out)
}

/// Fewest points a resampled loop has (a triangle is the smallest closed polygon).
pub const MIN_RESAMPLED: usize = 3;

fn lerp(a: [f64; 2], b: [f64; 2], t: f64) -> [f64; 2] {
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
}

/// Points evenly spaced by arc length along a closed polyline, about `spacing` apart (at
/// least [`MIN_RESAMPLED`]), starting at point 0. Degenerate input comes back unchanged.
pub fn resample_closed(p: &[[f64; 2]], spacing: f64) -> Vec<[f64; 2]> {
    let n = p.len();
    match stations(p, spacing) {
        None => p.to_vec(),
        Some(st) => st
            .into_iter()
            .map(|(i, t)| lerp(p[i], p[(i + 1) % n], t))
            .collect(),
    }
}

/// [`resample_closed`] carrying a per-vertex value (e.g. a corridor width) along: each
/// value is interpolated linearly in arc length like the points. `values` has one entry
/// per point (periodic: the closing edge runs back to `values[0]`), or one more, the
/// value on returning to point 0, for an unwrapped quantity such as a curve parameter.
pub fn resample_closed_values(
    p: &[[f64; 2]],
    values: &[f64],
    spacing: f64,
) -> (Vec<[f64; 2]>, Vec<f64>) {
    let n = p.len();
    assert!(
        values.len() == n || values.len() == n + 1,
        "one value per point (or one more)"
    );
    match stations(p, spacing) {
        None => (p.to_vec(), values[..n].to_vec()),
        Some(st) => st
            .into_iter()
            .map(|(i, t)| {
                let (a, b) = (values[i], values.get(i + 1).copied().unwrap_or(values[0]));
                (lerp(p[i], p[(i + 1) % n], t), a + t * (b - a))
            })
            .unzip(),
    }
}

/// Typical vertex spacing: the median edge length of the closed polyline.
fn median_step(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    let mut steps: Vec<f64> = (0..n).map(|i| dist(p[i], p[(i + 1) % n])).collect();
    if steps.is_empty() {
        return 0.0;
    }
    let mid = steps.len() / 2;
    let (_, m, _) = steps.select_nth_unstable_by(mid, f64::total_cmp);
    *m
}

/// Vertex offset that spans about `span_m` of arc at the polyline's median spacing (≥ 1).
fn span_offset(p: &[[f64; 2]], span_m: f64) -> usize {
    let step = median_step(p).max(1e-9);
    let k = (span_m / step).round();
    if k.is_finite() && k >= 1.0 {
        (k as usize).min(p.len().saturating_sub(1) / 2).max(1)
    } else {
        1
    }
}

/// Signed curvature (1/m, + = left) at each vertex of a closed polyline: the circle
/// through the vertex and its neighbours about `span_m` of arc before and after (the
/// three-point circumradius, exact for points on any circle whatever the span).
/// A longer span smooths out raster staircase noise. Collinear or coincident triples
/// give 0.
pub fn curvature_closed(p: &[[f64; 2]], span_m: f64) -> Vec<f64> {
    let n = p.len();
    if n < 3 {
        return vec![0.0; n];
    }
    let k = span_offset(p, span_m);
    (0..n)
        .map(|i| {
            let (a, b, c) = (p[(i + n - k) % n], p[i], p[(i + k) % n]);
            let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            let lengths = dist(a, b) * dist(b, c) * dist(a, c);
            if lengths > 0.0 && cross != 0.0 {
                2.0 * cross / lengths
            } else {
                0.0
            }
        })
        .collect()
}

/// Smallest three-point circumradius (m) of a closed polyline over chords of about
/// `span_m` (see [`curvature_closed`]); infinite for a polyline without any bend.
pub fn min_radius_closed(p: &[[f64; 2]], span_m: f64) -> f64 {
    let k_max = curvature_closed(p, span_m)
        .into_iter()
        .fold(0.0f64, |m, k| m.max(k.abs()));
    if k_max > 0.0 {
        1.0 / k_max
    } else {
        f64::INFINITY
    }
}

/// A crossing of segment `i` (from point `i` to `i + 1`) with a later, non-adjacent
/// segment `j` of the same closed polyline, at `point`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    pub i: usize,
    pub j: usize,
    pub point: [f64; 2],
}

/// Where segments `i` and `j` cross, with each segment half-open (its end point belongs
/// to the next segment, so a crossing through a vertex counts once). Parallel segments
/// never cross.
fn segment_crossing(p: &[[f64; 2]], i: usize, j: usize) -> Option<[f64; 2]> {
    let n = p.len();
    let (a, b) = (p[i], p[(i + 1) % n]);
    let (c, d) = (p[j], p[(j + 1) % n]);
    let r = [b[0] - a[0], b[1] - a[1]];
    let s = [d[0] - c[0], d[1] - c[1]];
    let denom = r[0] * s[1] - r[1] * s[0];
    if denom.abs() <= 1e-12 * r[0].hypot(r[1]) * s[0].hypot(s[1]) {
        return None;
    }
    let q = [c[0] - a[0], c[1] - a[1]];
    let t = (q[0] * s[1] - q[1] * s[0]) / denom;
    let u = (q[0] * r[1] - q[1] * r[0]) / denom;
    ((0.0..1.0).contains(&t) && (0.0..1.0).contains(&u)).then(|| lerp(a, b, t))
}

/// Segments `i < j` share a vertex on a closed polyline of `n` points.
fn adjacent(i: usize, j: usize, n: usize) -> bool {
    j == i + 1 || (i == 0 && j == n - 1)
}

/// Most candidate segment pairs [`self_intersections_closed`] tests: a loop folded onto
/// itself thousands of times (or a hostile one) is refused instead of taking O(n²).
pub const MAX_CANDIDATE_PAIRS: usize = crate::limits::MAX_DERIVED_COUNT as usize;

/// Every crossing of a closed polyline with itself, sorted by `(i, j)`.
///
/// Uniform-grid broad phase: segments are cut into pieces no longer than the cell (the
/// mean edge length, so the pieces number at most about 2n) and each piece is entered
/// in the cells its bounding box touches; only segments sharing a cell are tested.
/// Near-linear for the evenly spaced loops of real tracks, where O(n²) pair tests are not.
/// Refuses (`InvalidArgument`) when more than [`MAX_CANDIDATE_PAIRS`] pairs share cells.
pub fn self_intersections_closed(p: &[[f64; 2]]) -> Result<Vec<Crossing>> {
    let n = p.len();
    let total = polyline_length(p, true);
    if n < 4 || !total.is_finite() || total <= 0.0 {
        return Ok(Vec::new());
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in p {
        for a in 0..2 {
            lo[a] = lo[a].min(q[a]);
            hi[a] = hi[a].max(q[a]);
        }
    }
    let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    // The extent bound keeps cell indices small whatever the spacing.
    let cell = (total / n as f64).max(extent / 65_536.0);
    let pad = cell * 1e-9;
    let index = |v: f64, a: usize| ((v - lo[a]) / cell).floor() as i64;
    let mut entries: Vec<(i64, i64, usize)> = Vec::with_capacity(4 * n);
    for i in 0..n {
        let (a, b) = (p[i], p[(i + 1) % n]);
        let len = dist(a, b);
        if len == 0.0 {
            continue;
        }
        let pieces = (len / cell).ceil().max(1.0) as usize;
        for k in 0..pieces {
            let (q0, q1) = (
                lerp(a, b, k as f64 / pieces as f64),
                lerp(a, b, (k + 1) as f64 / pieces as f64),
            );
            let x0 = index(q0[0].min(q1[0]) - pad, 0);
            let x1 = index(q0[0].max(q1[0]) + pad, 0);
            let y0 = index(q0[1].min(q1[1]) - pad, 1);
            let y1 = index(q0[1].max(q1[1]) + pad, 1);
            for x in x0..=x1 {
                for y in y0..=y1 {
                    entries.push((x, y, i));
                }
            }
        }
    }
    entries.sort_unstable();
    entries.dedup();
    let candidates: usize = entries
        .chunk_by(|a, b| (a.0, a.1) == (b.0, b.1))
        .map(|g| g.len() * (g.len() - 1) / 2)
        .fold(0usize, usize::saturating_add);
    if candidates > MAX_CANDIDATE_PAIRS {
        return Err(ArenaError::invalid(format!(
            "self_intersections: {candidates} segment pairs of the {n}-point polyline lie \
             close together (at most {MAX_CANDIDATE_PAIRS}); is it folded onto itself?"
        )));
    }
    let mut pairs = Vec::with_capacity(candidates);
    for group in entries.chunk_by(|a, b| (a.0, a.1) == (b.0, b.1)) {
        for (x, ea) in group.iter().enumerate() {
            for eb in &group[x + 1..] {
                // Sorted within the cell: ea.2 < eb.2.
                if !adjacent(ea.2, eb.2, n) {
                    pairs.push((ea.2, eb.2));
                }
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    Ok(pairs
        .into_iter()
        .filter_map(|(i, j)| segment_crossing(p, i, j).map(|point| Crossing { i, j, point }))
        .collect())
}

/// Most points a polyline handed to the toolbox may have.
pub const MAX_POINTS: usize = crate::limits::MAX_DERIVED_COUNT as usize;

/// The door for polylines from outside: at least `min_points` (after dropping one exactly
/// repeated closing point when `closed`), at most [`MAX_POINTS`], all finite. Returns the
/// number of points to use (the prefix of `p`).
pub fn check_points(p: &[[f64; 2]], min_points: usize, closed: bool, what: &str) -> Result<usize> {
    if p.len() > MAX_POINTS {
        return Err(ArenaError::invalid(format!(
            "{what} has {} points, at most {MAX_POINTS} are allowed",
            p.len()
        )));
    }
    if let Some((i, q)) = p
        .iter()
        .enumerate()
        .find(|(_, q)| !(q[0].is_finite() && q[1].is_finite()))
    {
        return Err(ArenaError::invalid(format!(
            "{what} point {i} must be finite, got [{}, {}]",
            crate::limits::show(q[0]),
            crate::limits::show(q[1])
        )));
    }
    let mut n = p.len();
    if closed && n >= 2 && p[0] == p[n - 1] {
        n -= 1;
    }
    if n < min_points {
        let kind = if closed {
            "closed polyline"
        } else {
            "polyline"
        };
        return Err(ArenaError::invalid(format!(
            "{what} must be a {kind} of at least {min_points} points, got {n}"
        )));
    }
    Ok(n)
}

/// The door for the values [`resample_closed_values`] carries along `given` points of
/// which [`check_points`] kept the first `kept`: all finite, and one per given point or
/// one more than kept (a dropped repeated closing point keeps its value as the closing
/// value, which is also how an unwrapped parameter is passed).
pub fn check_values(values: &[f64], given: usize, kept: usize) -> Result<()> {
    if let Some(i) = values.iter().position(|x| !x.is_finite()) {
        return Err(ArenaError::invalid(format!(
            "values[{i}] must be finite, got {}",
            crate::limits::show(values[i])
        )));
    }
    if !(values.len() == given || values.len() == kept + 1) {
        return Err(ArenaError::invalid(format!(
            "values must have one entry per point of xy ({given}) or one more, got {}",
            values.len()
        )));
    }
    Ok(())
}

/// The door for a resampling spacing (m) on a loop of `length_m`: finite, > 0, and not
/// so fine that the point count exceeds the derived-count budget.
pub fn check_spacing(spacing: f64, length_m: f64) -> Result<()> {
    if !(spacing.is_finite() && spacing > 0.0) {
        return Err(ArenaError::invalid(format!(
            "spacing must be a finite length > 0 m, got {}",
            crate::limits::show(spacing)
        )));
    }
    crate::limits::derived_count("spacing", length_m, spacing).map(|_| ())
}

/// The door for a curvature span (m): finite and > 0.
pub fn check_span(span_m: f64) -> Result<()> {
    if !(span_m.is_finite() && span_m > 0.0) {
        return Err(ArenaError::invalid(format!(
            "span_m must be a finite length > 0 m, got {}",
            crate::limits::show(span_m)
        )));
    }
    Ok(())
}

#[cfg(test)]
#[path = "polyline_tests.rs"]
mod tests;
