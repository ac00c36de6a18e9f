//! Exact Euclidean distance transform in linear time: the column distances by two row
//! sweeps (Meijster et al. 2000, phase 1), then the 1-D lower envelope of parabolas along
//! every row (Felzenszwalb & Huttenlocher 2012), rows in parallel with rayon.
//! Distances are in cell units between cell centres.

use rayon::prelude::*;

const INF: f32 = 1e20;

/// Squared distance from every cell to the nearest cell where `feature` is true.
/// Cells of an image without any feature get a huge value (≥ 1e20).
pub fn edt_squared(feature: &[bool], width: usize, height: usize) -> Vec<f32> {
    transform(feature, width, height, f64::INFINITY, Finish::Squared)
}

/// Like [`edt_squared`], but exact only where the distance is at most `cap` (cells):
/// elsewhere the value is some number above `cap²` (often ≥ 1e20). Work beyond the cap
/// is skipped, which makes narrow bands around the features cheap.
pub fn edt_squared_within(feature: &[bool], width: usize, height: usize, cap: f64) -> Vec<f32> {
    transform(feature, width, height, cap, Finish::Squared)
}

/// Euclidean distance (cell units) to the nearest feature cell.
pub fn edt(feature: &[bool], width: usize, height: usize) -> Vec<f32> {
    transform(feature, width, height, f64::INFINITY, Finish::Sqrt)
}

/// Euclidean distance (cells) where it is at most `cap`; `cap` elsewhere.
pub fn edt_within(feature: &[bool], width: usize, height: usize, cap: f64) -> Vec<f32> {
    transform(feature, width, height, cap, Finish::SqrtMin(cap as f32))
}

/// Column distances (phase 1) are stored in the narrowest type that holds the cap.
trait ColumnDist: Copy + Send + Sync {
    const FAR: Self;
    fn zero() -> Self;
    /// `self + 1`, saturating at FAR.
    fn next(self) -> Self;
    /// Squared value, or None when FAR (no feature within the cap in this column).
    fn square(self) -> Option<f64>;
}

/// Column distances as saturating unsigned integers (u8 for capped transforms).
macro_rules! unsigned_column_dist {
    ($t:ty) => {
        impl ColumnDist for $t {
            const FAR: $t = <$t>::MAX;
            fn zero() -> Self {
                0
            }
            #[inline]
            fn next(self) -> Self {
                self.saturating_add(1)
            }
            #[inline]
            fn square(self) -> Option<f64> {
                (self != <$t>::MAX).then_some((self as f64) * (self as f64))
            }
        }
    };
}
unsigned_column_dist!(u8);
unsigned_column_dist!(u32);

/// What is stored for each squared distance.
#[derive(Clone, Copy)]
enum Finish {
    Squared,
    Sqrt,
    SqrtMin(f32),
}

impl Finish {
    /// Apply to a whole row (one tight, vectorisable loop per variant).
    fn apply(self, row: &mut [f32]) {
        match self {
            Finish::Squared => {}
            Finish::Sqrt => row.iter_mut().for_each(|x| *x = x.sqrt()),
            Finish::SqrtMin(c) => row.iter_mut().for_each(|x| *x = x.sqrt().min(c)),
        }
    }
}

/// Both phases; `finish` maps each squared distance to the stored value.
fn transform(feature: &[bool], width: usize, height: usize, cap: f64, finish: Finish) -> Vec<f32> {
    assert_eq!(
        feature.len(),
        width * height,
        "mask size does not match width × height"
    );
    if width == 0 || height == 0 {
        return Vec::new();
    }
    if cap < (u8::MAX - 1) as f64 {
        transform_with::<u8>(feature, width, height, cap.max(0.0).floor() as u32, finish)
    } else {
        let c = if cap.is_finite() {
            cap.floor().min((u32::MAX - 1) as f64) as u32
        } else {
            u32::MAX - 1
        };
        transform_with::<u32>(feature, width, height, c, finish)
    }
}

fn transform_with<T: ColumnDist + PartialOrd>(
    feature: &[bool],
    width: usize,
    height: usize,
    cap_cells: u32,
    finish: Finish,
) -> Vec<f32> {
    // Phase 1: distance to the nearest feature in the same column, by a downward sweep
    // (fused with reading the mask) and an upward sweep over whole rows: cache-friendly,
    // no transpose; stored as u8 when the cap allows (a quarter of the memory traffic).
    let mut g = vec![T::zero(); width * height];
    for (x, &f) in g[..width].iter_mut().zip(&feature[..width]) {
        *x = if f { T::zero() } else { T::FAR };
    }
    for r in 1..height {
        let (above, row) = g[(r - 1) * width..(r + 1) * width].split_at_mut(width);
        for ((x, &a), &f) in row
            .iter_mut()
            .zip(above.iter())
            .zip(&feature[r * width..(r + 1) * width])
        {
            *x = if f { T::zero() } else { a.next() };
        }
    }
    for r in (0..height.saturating_sub(1)).rev() {
        let (row, below) = g[r * width..(r + 2) * width].split_at_mut(width);
        for (x, &b) in row.iter_mut().zip(below.iter()) {
            let nb = b.next();
            if nb < *x {
                *x = nb;
            }
        }
    }
    // Phase 2: lower envelope of parabolas along each row, rows in parallel.
    let cap2 = (cap_cells as f64) * (cap_cells as f64);
    let mut d = vec![0f32; width * height];
    d.par_chunks_mut(width)
        .zip(g.par_chunks(width))
        .for_each_init(
            || Scratch::new(width),
            |scratch, (out, col)| {
                transform_1d(col, out, cap2, scratch);
                finish.apply(out);
            },
        );
    d
}

struct Scratch {
    /// Roots of the envelope's parabolas, their sample values, and the boundaries.
    v: Vec<u32>,
    fv: Vec<f64>,
    z: Vec<f64>,
}

impl Scratch {
    fn new(n: usize) -> Self {
        Scratch {
            v: vec![0; n],
            fv: vec![0.0; n],
            z: vec![0.0; n + 1],
        }
    }
}

/// 1-D squared distance transform of one row whose samples are the column distances
/// `col` (squared, absent when FAR or above `cap2`), written to `out`. f64 arithmetic, so positions beyond 4096 stay exact. Inside a run of zero
/// samples only the run's ends can be nearest to a cell outside it, so interior zeros
/// stay out of the envelope.
fn transform_1d<T: ColumnDist>(col: &[T], out: &mut [f32], cap2: f64, s: &mut Scratch) {
    let n = col.len();
    let sample = |q: usize| col[q].square().filter(|&x| x <= cap2);
    let (v, fv, z) = (&mut s.v, &mut s.fv, &mut s.z);
    let mut k = usize::MAX; // index of the envelope's last parabola; MAX = empty
    for q in 0..n {
        let Some(fq) = sample(q) else { continue };
        if fq == 0.0
            && q > 0
            && q + 1 < n
            && sample(q - 1) == Some(0.0)
            && sample(q + 1) == Some(0.0)
        {
            continue;
        }
        let hq = fq + (q * q) as f64;
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
            let sp = (hq - (fv[k] + (p * p) as f64)) / (2.0 * (q - p) as f64);
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
        out.fill(INF);
        return;
    }
    let mut k = 0usize;
    let (mut p, mut fp) = (v[0] as usize, fv[0]);
    for (q, o) in out.iter_mut().enumerate() {
        let qf = q as f64;
        if z[k + 1] < qf {
            while z[k + 1] < qf {
                k += 1;
            }
            (p, fp) = (v[k] as usize, fv[k]);
        }
        let dq = qf - p as f64;
        let d2 = if col[q].square() == Some(0.0) {
            0.0
        } else {
            (dq * dq + fp) as f32
        };
        *o = d2;
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
