//! Exact Euclidean distance transform in linear time: the column distances by two row
//! sweeps (Meijster et al. 2000, phase 1), then the 1-D lower envelope of parabolas along
//! every row (Felzenszwalb & Huttenlocher 2012), rows in parallel with rayon.
//! Distances are in cell units between cell centres.

use rayon::prelude::*;

const INF: f32 = 1e20;

/// Squared distance from every cell to the nearest cell where `feature` is true.
/// Cells of an image without any feature get a huge value (≥ 1e20).
pub fn edt_squared(feature: &[bool], width: usize, height: usize) -> Vec<f32> {
    assert_eq!(feature.len(), width * height, "mask size does not match width × height");
    if width == 0 || height == 0 {
        return Vec::new();
    }
    // Phase 1: distance to the nearest feature in the same column, by two sweeps over
    // whole rows (cache-friendly, no transpose).
    const FAR: u32 = 1 << 30;
    let mut g: Vec<u32> = feature.iter().map(|&f| if f { 0 } else { FAR }).collect();
    for r in 1..height {
        let (above, row) = g[(r - 1) * width..(r + 1) * width].split_at_mut(width);
        for (x, &a) in row.iter_mut().zip(above.iter()) {
            *x = (*x).min(a + 1);
        }
    }
    for r in (0..height - 1).rev() {
        let (row, below) = g[r * width..(r + 2) * width].split_at_mut(width);
        for (x, &b) in row.iter_mut().zip(below.iter()) {
            *x = (*x).min(b + 1);
        }
    }
    let mut d: Vec<f32> = g.iter().map(|&v| if v >= FAR { INF } else { (v as f32) * (v as f32) }).collect();
    drop(g);
    // Phase 2: lower envelope of parabolas along each row, rows in parallel.
    d.par_chunks_mut(width).for_each_init(|| Scratch::new(width), |scratch, row| transform_1d(row, scratch));
    d
}

/// Euclidean distance (cell units) to the nearest feature cell.
pub fn edt(feature: &[bool], width: usize, height: usize) -> Vec<f32> {
    let mut d = edt_squared(feature, width, height);
    d.iter_mut().for_each(|v| *v = v.sqrt());
    d
}

struct Scratch {
    v: Vec<usize>,
    z: Vec<f32>,
    out: Vec<f32>,
}

impl Scratch {
    fn new(n: usize) -> Self {
        Scratch { v: vec![0; n], z: vec![0.0; n + 1], out: vec![0.0; n] }
    }
}

/// In-place 1-D squared distance transform of a sampled function `f`.
fn transform_1d(f: &mut [f32], s: &mut Scratch) {
    let n = f.len();
    let (v, z) = (&mut s.v, &mut s.z);
    let mut k = 0usize;
    // Skip leading infinite samples: parabolas rooted at INF never form the envelope,
    // and including them loses precision in f32.
    let Some(first) = f.iter().position(|&x| x < INF) else { return };
    v[0] = first;
    z[0] = f32::NEG_INFINITY;
    z[1] = f32::INFINITY;
    for q in first + 1..n {
        if f[q] >= INF {
            continue;
        }
        let fq = f[q] + (q * q) as f32;
        loop {
            let p = v[k];
            let sp = (fq - (f[p] + (p * p) as f32)) / (2.0 * (q as f32 - p as f32));
            if sp <= z[k] && k > 0 {
                k -= 1;
            } else if sp <= z[k] {
                // k == 0 and the new parabola dominates from -inf
                v[0] = q;
                z[1] = f32::INFINITY;
                break;
            } else {
                k += 1;
                v[k] = q;
                z[k] = sp;
                z[k + 1] = f32::INFINITY;
                break;
            }
        }
    }
    let mut k = 0usize;
    for q in 0..n {
        while z[k + 1] < q as f32 {
            k += 1;
        }
        let p = v[k];
        let dq = q as f32 - p as f32;
        s.out[q] = dq * dq + f[p];
    }
    f.copy_from_slice(&s.out);
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
    fn no_feature_is_infinite() {
        let d = edt_squared(&[false; 6], 3, 2);
        assert!(d.iter().all(|&v| v >= INF));
    }

    proptest! {
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
