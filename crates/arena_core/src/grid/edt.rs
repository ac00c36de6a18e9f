//! Exact Euclidean distance transform in linear time: the column distances by two row
//! sweeps (Meijster et al. 2000, phase 1), then the 1-D lower envelope of parabolas along
//! every row (Felzenszwalb & Huttenlocher 2012), rows in parallel with rayon.
//! Distances are in cell units between cell centres.

use rayon::prelude::*;

const INF: f32 = 1e20;

/// Squared distance from every cell to the nearest cell where `feature` is true.
/// Cells of an image without any feature get a huge value (≥ 1e20).
pub fn edt_squared(feature: &[bool], width: usize, height: usize) -> Vec<f32> {
    transform(feature, width, height, f64::INFINITY, |d2| d2)
}

/// Like [`edt_squared`], but exact only where the distance is at most `cap` (cells):
/// elsewhere the value is some number above `cap²` (often ≥ 1e20). Work beyond the cap
/// is skipped, which makes narrow bands around the features cheap.
pub fn edt_squared_within(feature: &[bool], width: usize, height: usize, cap: f64) -> Vec<f32> {
    transform(feature, width, height, cap, |d2| d2)
}

/// Euclidean distance (cell units) to the nearest feature cell.
pub fn edt(feature: &[bool], width: usize, height: usize) -> Vec<f32> {
    transform(feature, width, height, f64::INFINITY, f32::sqrt)
}

/// Euclidean distance (cells) where it is at most `cap`; `cap` elsewhere.
pub fn edt_within(feature: &[bool], width: usize, height: usize, cap: f64) -> Vec<f32> {
    let c = cap as f32;
    transform(feature, width, height, cap, move |d2| d2.sqrt().min(c))
}

/// Both phases; `finish` maps each squared distance to the stored value.
fn transform(feature: &[bool], width: usize, height: usize, cap: f64, finish: impl Fn(f32) -> f32 + Sync) -> Vec<f32> {
    assert_eq!(feature.len(), width * height, "mask size does not match width × height");
    if width == 0 || height == 0 {
        return Vec::new();
    }
    // Phase 1: distance to the nearest feature in the same column, by a downward sweep
    // (fused with reading the mask) and an upward sweep (fused with squaring and the
    // cap) over whole rows: cache-friendly, no transpose.
    const FAR: u32 = 1 << 30;
    let mut g = vec![0u32; width * height];
    for (c, &f) in feature[..width].iter().enumerate() {
        g[c] = if f { 0 } else { FAR };
    }
    for r in 1..height {
        let (above, row) = g[(r - 1) * width..(r + 1) * width].split_at_mut(width);
        for ((x, &a), &f) in row.iter_mut().zip(above.iter()).zip(&feature[r * width..(r + 1) * width]) {
            *x = if f { 0 } else { (a + 1).min(FAR) };
        }
    }
    let cap_cells = if cap.is_finite() { cap.max(0.0).floor().min(FAR as f64) as u32 } else { FAR - 1 };
    let mut d = vec![0f32; width * height];
    for r in (0..height).rev() {
        if r + 1 < height {
            let (row, below) = g[r * width..(r + 2) * width].split_at_mut(width);
            for (x, &b) in row.iter_mut().zip(below.iter()) {
                *x = (*x).min(b + 1);
            }
        }
        for (o, &v) in d[r * width..(r + 1) * width].iter_mut().zip(&g[r * width..(r + 1) * width]) {
            *o = if v > cap_cells { INF } else { (v as f32) * (v as f32) };
        }
    }
    drop(g);
    // Phase 2: lower envelope of parabolas along each row, rows in parallel.
    d.par_chunks_mut(width).for_each_init(|| Scratch::new(width), |scratch, row| transform_1d(row, scratch, &finish));
    d
}

struct Scratch {
    /// Roots of the envelope's parabolas, their sample values, and the boundaries.
    v: Vec<u32>,
    fv: Vec<f32>,
    z: Vec<f64>,
}

impl Scratch {
    fn new(n: usize) -> Self {
        Scratch { v: vec![0; n], fv: vec![0.0; n], z: vec![0.0; n + 1] }
    }
}

/// In-place 1-D squared distance transform of a sampled function `f`, each result
/// passed through `finish` (f64 arithmetic, so positions beyond 4096 stay exact).
/// Samples ≥ INF are absent; inside a run of zero samples only the run's ends can be
/// nearest to a cell outside it, so interior zeros stay out of the envelope.
fn transform_1d(f: &mut [f32], s: &mut Scratch, finish: &impl Fn(f32) -> f32) {
    let n = f.len();
    let (v, fv, z) = (&mut s.v, &mut s.fv, &mut s.z);
    let mut k = usize::MAX; // index of the envelope's last parabola; MAX = empty
    for q in 0..n {
        let fq = f[q];
        if fq >= INF || (fq == 0.0 && q > 0 && q + 1 < n && f[q - 1] == 0.0 && f[q + 1] == 0.0) {
            continue;
        }
        let hq = fq as f64 + (q * q) as f64;
        if k == usize::MAX {
            k = 0;
            v[0] = q as u32;
            fv[0] = fq;
            z[0] = f64::NEG_INFINITY;
            z[1] = f64::INFINITY;
            continue;
        }
        loop {
            let p = v[k] as usize;
            let sp = (hq - (fv[k] as f64 + (p * p) as f64)) / (2.0 * (q - p) as f64);
            if sp <= z[k] && k > 0 {
                k -= 1;
            } else if sp <= z[k] {
                v[0] = q as u32;
                fv[0] = fq;
                z[1] = f64::INFINITY;
                break;
            } else {
                k += 1;
                v[k] = q as u32;
                fv[k] = fq;
                z[k] = sp;
                z[k + 1] = f64::INFINITY;
                break;
            }
        }
    }
    if k == usize::MAX {
        let none = finish(INF);
        f.iter_mut().for_each(|x| *x = none);
        return;
    }
    // Read the envelope left to right, in place (the parabolas' samples are in `fv`).
    let mut k = 0usize;
    let (mut p, mut fp) = (v[0] as usize, fv[0] as f64);
    for q in 0..n {
        let qf = q as f64;
        if z[k + 1] < qf {
            while z[k + 1] < qf {
                k += 1;
            }
            (p, fp) = (v[k] as usize, fv[k] as f64);
        }
        let out = if f[q] == 0.0 { 0.0 } else { let dq = qf - p as f64; (dq * dq + fp) as f32 };
        f[q] = finish(out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn brute(feature: &[bool], w: usize, h: usize) -> Vec<f32> {
        (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f32, (i / w) as f32);
                feature
                    .iter()
                    .enumerate()
                    .filter(|(_, &f)| f)
                    .map(|(j, _)| {
                        let (fx, fy) = ((j % w) as f32, (j / w) as f32);
                        (x - fx).powi(2) + (y - fy).powi(2)
                    })
                    .fold(INF, f32::min)
            })
            .collect()
    }

    #[test]
    fn single_feature_gives_exact_distances() {
        let (w, h) = (7, 5);
        let mut f = vec![false; w * h];
        f[2 * w + 3] = true;
        let d = edt(&f, w, h);
        assert_eq!(d[2 * w + 3], 0.0);
        assert_eq!(d[2 * w + 6], 3.0);
        assert!((d[0] - (9.0f32 + 4.0).sqrt()).abs() < 1e-6);
    }

    #[test]
    fn long_rows_stay_exact() {
        let w = 6000;
        let mut f = vec![false; w];
        f[0] = true;
        f[w - 1] = true;
        let d = edt_squared(&f, w, 1);
        assert_eq!(d[2999], 2999.0 * 2999.0);
        assert_eq!(d[3000], 2999.0 * 2999.0);
        assert_eq!(d[5000], 999.0 * 999.0);
    }

    #[test]
    fn no_feature_is_infinite() {
        let d = edt_squared(&[false; 6], 3, 2);
        assert!(d.iter().all(|&v| v >= INF));
    }

    proptest! {
        #[test]
        fn capped_transform_is_exact_within_the_cap(w in 1usize..14, h in 1usize..14, cap in 0.0f64..6.0, bits in proptest::collection::vec(0u8..6, 196)) {
            let f: Vec<bool> = (0..w * h).map(|i| bits[i] == 0).collect();
            let capped = edt_squared_within(&f, w, h, cap);
            let exact = brute(&f, w, h);
            for (a, b) in capped.iter().zip(&exact) {
                if (*b as f64) <= cap * cap { prop_assert!((a - b).abs() < 1e-3, "{a} vs {b}"); } else { prop_assert!((*a as f64) > cap * cap); }
            }
        }

        #[test]
        fn matches_brute_force(w in 1usize..14, h in 1usize..14, bits in proptest::collection::vec(0u8..10, 196)) {
            let f: Vec<bool> = (0..w * h).map(|i| bits[i] == 0).collect();
            let fast = edt_squared(&f, w, h);
            let slow = brute(&f, w, h);
            for (a, b) in fast.iter().zip(&slow) {
                if *b >= INF { prop_assert!(*a >= INF); } else { prop_assert!((a - b).abs() < 1e-3, "{a} vs {b}"); }
            }
        }
    }
}
