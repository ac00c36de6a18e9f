//! Polygon fill (even–odd rule) of closed polylines onto a grid, sampled at cell
//! centres: the round-trip check re-rasterises the collision walls with it.

/// Cells (row-major, row 0 at the top) whose centre lies inside an odd number of the
/// closed `loops`, given in grid units (u right, v up from the lower-left corner).
pub fn fill_even_odd(loops: &[Vec<[f64; 2]>], width: usize, height: usize) -> Vec<bool> {
    let mut out = vec![false; width * height];
    if width == 0 || height == 0 {
        return out;
    }
    // Crossing abscissae per scanline vv (centre v = vv + 0.5).
    let mut xs: Vec<Vec<f64>> = vec![Vec::new(); height];
    for l in loops {
        let n = l.len();
        for i in 0..n {
            let (a, b) = (l[i], l[(i + 1) % n]);
            if a[1] == b[1] {
                continue;
            }
            let (lo, hi) = if a[1] < b[1] { (a, b) } else { (b, a) };
            // scanlines with lo.v <= v < hi.v (half-open: vertices count once)
            let first = (lo[1] - 0.5).ceil().max(0.0) as usize;
            let last = ((hi[1] - 0.5).ceil() as i64).min(height as i64);
            for vv in first as i64..last {
                let v = vv as f64 + 0.5;
                let t = (v - lo[1]) / (hi[1] - lo[1]);
                xs[vv as usize].push(lo[0] + t * (hi[0] - lo[0]));
            }
        }
    }
    for (vv, row_xs) in xs.iter_mut().enumerate() {
        row_xs.sort_by(f64::total_cmp);
        let row = height - 1 - vv;
        for pair in row_xs.chunks_exact(2) {
            // cell centres col + 0.5 in [x0, x1)
            let c0 = (pair[0] - 0.5).ceil().max(0.0) as usize;
            let c1 = ((pair[1] - 0.5).ceil().max(0.0) as usize).min(width);
            for c in c0..c1 {
                out[row * width + c] = true;
            }
        }
    }
    out
}

/// Intersection over union of two masks (1 when both are empty).
pub fn iou(a: &[bool], b: &[bool]) -> f64 {
    let (mut inter, mut uni) = (0usize, 0usize);
    for (&x, &y) in a.iter().zip(b) {
        inter += (x && y) as usize;
        uni += (x || y) as usize;
    }
    if uni == 0 {
        1.0
    } else {
        inter as f64 / uni as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_with_a_hole() {
        let outer = vec![[1.0, 1.0], [9.0, 1.0], [9.0, 9.0], [1.0, 9.0]];
        let hole = vec![[3.0, 3.0], [3.0, 7.0], [7.0, 7.0], [7.0, 3.0]];
        let m = fill_even_odd(&[outer, hole], 10, 10);
        assert_eq!(m.iter().filter(|&&x| x).count(), 64 - 16);
        assert!(m[5 * 10 + 1] && !m[5 * 10 + 5] && !m[0]);
        assert_eq!(iou(&m, &m), 1.0);
        let none = vec![false; 100];
        assert_eq!(iou(&m, &none), 0.0);
    }
}
