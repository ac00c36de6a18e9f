//! Planar lidar by exact 2D ray casting: rays against the wall segments (by the angular
//! segment scan of [`super::segment_scan`] over the segments the scanner can see; the per-beam walk
//! through a uniform grid with a DDA, [`SegmentGrid::cast`], gives the same bits) and
//! against other vehicles' chassis rectangles. Exact up to f64 rounding:
//! no rasterisation, so thin walls can never be slipped through (the weakness of ray
//! marching on a distance field).

use rand_chacha::rand_core::Rng;
use rand_chacha::ChaCha8Rng;

use super::params::LidarParams;
use super::segment_scan::segment_scan;
use super::segments::SegmentGrid;

/// A vehicle's chassis footprint as seen by other vehicles' lidars.
#[derive(Debug, Clone, Copy)]
pub struct Footprint {
    pub x: f64,
    pub y: f64,
    pub cos: f64,
    pub sin: f64,
    pub half_length: f64,
    pub half_width: f64,
}

impl Footprint {
    /// Entry distance of the ray into the rectangle (0 if it starts inside), or infinity.
    #[inline]
    pub fn cast(&self, ox: f64, oy: f64, dx: f64, dy: f64) -> f64 {
        let (rx, ry) = (ox - self.x, oy - self.y);
        let (lx, ly) = (
            rx * self.cos + ry * self.sin,
            -rx * self.sin + ry * self.cos,
        );
        let (ldx, ldy) = (
            dx * self.cos + dy * self.sin,
            -dx * self.sin + dy * self.cos,
        );
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        for (o, d, h) in [(lx, ldx, self.half_length), (ly, ldy, self.half_width)] {
            if d.abs() < 1e-300 {
                if o.abs() > h {
                    return f64::INFINITY;
                }
            } else {
                let (a, b) = ((-h - o) / d, (h - o) / d);
                t0 = t0.max(a.min(b));
                t1 = t1.min(a.max(b));
            }
        }
        if t0 <= t1 {
            t0
        } else {
            f64::INFINITY
        }
    }
}

/// Fewest beams for which [`Scanner::split`] scans the two halves on two rayon tasks.
/// The hand-off (the caller, outside the pool, parks while a worker is woken) costs more
/// than a scan: measured on Spielberg on the shared 2-core machine (issue 24), a split
/// scan took 39-54 µs against 19-28 µs whole at 1080 beams, and was still slower at
/// 16384 beams (165 against 107-140 µs); the gym.make step ran 2.1-2.9x faster without
/// it. So only fans far beyond a real lidar's are split.
pub(crate) const SPLIT_MIN_BEAMS: usize = 32_768;

/// Precomputed beam directions in the sensor frame plus the scan settings.

#[derive(Debug, Clone)]
pub struct Scanner {
    cos: Vec<f64>,
    sin: Vec<f64>,
    /// Angle of beam 0 relative to the heading, and the beam increment (rad).
    angle0: f64,
    inc: f64,
    params: LidarParams,
    /// Scan the two halves of the fan on two rayon tasks (set for a lone world, whose
    /// scan would otherwise leave the second core idle; a batch keeps one world per task),
    /// for fans of at least `SPLIT_MIN_BEAMS` beams.
    pub split: bool,
}

/// Per-scan buffers (beam directions in the world frame, ranges), kept per thread so a
/// scan allocates nothing.
#[derive(Default)]
struct Scratch {
    dirs: Vec<[f64; 2]>,
    ranges: Vec<f64>,
}

thread_local! {
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::default();
}

/// Per-episode observation noise of one world's lidar (domain randomisation), drawn from
/// the world's own stream: extra range noise std (m, on top of `LidarParams::noise_std`)
/// and the probability that a beam reads `range_max` (a lost return).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ScanNoise {
    pub extra_std: f64,
    pub dropout: f64,
}

impl Scanner {
    pub fn new(params: &LidarParams) -> Self {
        let n = params.num_beams;
        let inc = if n > 1 {
            params.fov / (n - 1) as f64
        } else {
            0.0
        };
        let start = if n > 1 { -0.5 * params.fov } else { 0.0 };
        let angles: Vec<f64> = (0..n).map(|k| start + k as f64 * inc).collect();
        Scanner {
            cos: angles.iter().map(|a| a.cos()).collect(),
            sin: angles.iter().map(|a| a.sin()).collect(),
            angle0: start,
            inc,
            params: params.clone(),
            split: false,
        }
    }

    pub fn num_beams(&self) -> usize {
        self.cos.len()
    }

    /// One scan from a vehicle at pose `(x, y, yaw)` (CoM); the sensor sits `mount_x`
    /// ahead of it. `others` are the other vehicles' footprints; noise and dropout draws
    /// come from `rng` (the vehicle's own stream). Writes `out[num_beams]`.
    pub fn scan(
        &self,
        pose: [f64; 3],
        grid: &SegmentGrid,
        others: &[Footprint],
        noise: ScanNoise,
        rng: &mut ChaCha8Rng,
        out: &mut [f32],
    ) {
        let (cy, sy) = (pose[2].cos(), pose[2].sin());
        let (ox, oy) = (
            pose[0] + self.params.mount_x * cy,
            pose[1] + self.params.mount_x * sy,
        );
        let rmax = self.params.range_max;
        let theta0 = pose[2] + self.angle0;
        let mut fresh = Scratch::default();
        SCRATCH.with(|cell| {
            // Busy only when this thread runs a job stolen while its own scan waits in
            // `rayon::join`: that scan then gets buffers of its own.
            let mut held = cell.try_borrow_mut();
            let Scratch { dirs, ranges } = match held.as_deref_mut() {
                Ok(s) => s,
                Err(_) => &mut fresh,
            };
            let n = self.cos.len();
            dirs.resize(n, [0.0; 2]);
            for ((d, &c), &s) in dirs.iter_mut().zip(&self.cos).zip(&self.sin) {
                *d = [c * cy - s * sy, c * sy + s * cy];
            }
            ranges.clear();
            ranges.resize(n, f64::INFINITY);
            if self.split && n >= SPLIT_MIN_BEAMS {
                // Beam k's range depends only on beam k, so the halves are the same scan.
                let h = n / 2;
                let (ra, rb) = ranges.split_at_mut(h);
                let (da, db) = dirs.split_at(h);
                let theta_b = theta0 + h as f64 * self.inc;
                rayon::join(
                    || segment_scan(grid, ox, oy, theta0, self.inc, da, rmax, ra),
                    || segment_scan(grid, ox, oy, theta_b, self.inc, db, rmax, rb),
                );
            } else {
                segment_scan(grid, ox, oy, theta0, self.inc, dirs, rmax, ranges);
            }
            if others.is_empty() {
                for (o, &r) in out.iter_mut().zip(ranges.iter()) {
                    *o = r.min(rmax) as f32;
                }
            } else {
                for ((o, &r), d) in out.iter_mut().zip(ranges.iter()).zip(dirs.iter()) {
                    let mut t = r;
                    for f in others {
                        t = t.min(f.cast(ox, oy, d[0], d[1]));
                    }
                    *o = t.min(rmax) as f32;
                }
            }
        });
        let sd = self.params.noise_std.hypot(noise.extra_std);
        if sd > 0.0 {
            let mut k = 0;
            while k < out.len() {
                let (z0, z1) = gaussian_pair(rng);
                out[k] += (sd * z0) as f32;
                if k + 1 < out.len() {
                    out[k + 1] += (sd * z1) as f32;
                }
                k += 2;
            }
        }
        let (lo, hi) = (self.params.range_min as f32, rmax as f32);
        for o in out.iter_mut() {
            *o = o.clamp(lo, hi);
        }
        if noise.dropout > 0.0 {
            for o in out.iter_mut() {
                if unit(rng) < noise.dropout {
                    *o = hi;
                }
            }
        }
    }
}

/// A uniform draw in [0, 1).
fn unit(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// Two independent standard normal draws (Box–Muller).
fn gaussian_pair(rng: &mut ChaCha8Rng) -> (f64, f64) {
    let u1 = ((rng.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
    let u2 = unit(rng);
    let r = (-2.0 * u1.ln()).sqrt();
    let a = std::f64::consts::TAU * u2;
    (r * a.cos(), r * a.sin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_chacha::rand_core::SeedableRng;

    fn square(h: f64) -> Vec<[f64; 2]> {
        vec![[-h, -h], [h, -h], [h, h], [-h, h]]
    }

    /// Inside an axis-aligned square room of half-side h, a beam at angle a from a point
    /// (px, py) has the exact range min over the walls of the slab distances.
    fn square_reference(h: f64, px: f64, py: f64, a: f64) -> f64 {
        let (dx, dy) = (a.cos(), a.sin());
        let tx = if dx > 0.0 {
            (h - px) / dx
        } else if dx < 0.0 {
            (-h - px) / dx
        } else {
            f64::INFINITY
        };
        let ty = if dy > 0.0 {
            (h - py) / dy
        } else if dy < 0.0 {
            (-h - py) / dy
        } else {
            f64::INFINITY
        };
        tx.min(ty)
    }

    #[test]
    fn square_room_matches_exact_ranges() {
        let grid = SegmentGrid::new(&[square(5.0)]);
        let params = LidarParams::default();
        let sc = Scanner::new(&params);
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        let mut out = vec![0.0f32; sc.num_beams()];
        let pose = [0.7, -1.3, 0.4];
        sc.scan(pose, &grid, &[], ScanNoise::default(), &mut rng, &mut out);
        let (ox, oy) = (
            pose[0] + params.mount_x * pose[2].cos(),
            pose[1] + params.mount_x * pose[2].sin(),
        );
        let inc = params.fov / (params.num_beams - 1) as f64;
        for (k, &r) in out.iter().enumerate() {
            let a = pose[2] - 0.5 * params.fov + k as f64 * inc;
            let exact = square_reference(5.0, ox, oy, a);
            // f32 output: relative 1e-6 of a <= 30 m range, i.e. < 1e-5 m.
            assert!((r as f64 - exact).abs() < 1e-5, "beam {k}: {r} vs {exact}");
        }
    }

    #[test]
    fn circle_room_matches_chord_length() {
        // Walls: a 2000-gon of circumradius R; from the centre every range is between the
        // apothem R cos(pi/n) and R.
        let (r, n) = (4.0, 2000);
        let poly: Vec<[f64; 2]> = (0..n)
            .map(|i| {
                let a = i as f64 / n as f64 * std::f64::consts::TAU;
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        let grid = SegmentGrid::new(&[poly]);
        let p = LidarParams {
            mount_x: 0.0,
            ..Default::default()
        };
        let sc = Scanner::new(&p);
        let mut out = vec![0.0f32; sc.num_beams()];
        sc.scan(
            [0.0, 0.0, 1.0],
            &grid,
            &[],
            ScanNoise::default(),
            &mut ChaCha8Rng::seed_from_u64(1),
            &mut out,
        );
        let apothem = r * (std::f64::consts::PI / n as f64).cos();
        assert!(out
            .iter()
            .all(|&x| (x as f64) >= apothem - 1e-5 && (x as f64) <= r + 1e-5));
    }

    #[test]
    fn split_scan_equals_the_single_scan_bit_for_bit() {
        // A wiggly room, so the two halves of the fan see very different walls.
        let poly: Vec<[f64; 2]> = (0..720)
            .map(|i| {
                let a = i as f64 / 720.0 * std::f64::consts::TAU;
                let r = 6.0 + 1.5 * (5.0 * a).sin() + 0.4 * (23.0 * a).cos();
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        let grid = SegmentGrid::new(&[poly]);
        let n = SPLIT_MIN_BEAMS + 1;
        let one = Scanner::new(&LidarParams {
            num_beams: n,
            ..Default::default()
        });
        let mut two = one.clone();
        two.split = true;
        for pose in [[0.0, 0.0, 0.3], [1.0, -2.0, 2.5], [-2.5, 1.0, -1.2]] {
            let (mut a, mut b) = (vec![0.0f32; n], vec![0.0f32; n]);
            let mut rng = ChaCha8Rng::seed_from_u64(3);
            one.scan(pose, &grid, &[], ScanNoise::default(), &mut rng, &mut a);
            let mut rng = ChaCha8Rng::seed_from_u64(3);
            two.scan(pose, &grid, &[], ScanNoise::default(), &mut rng, &mut b);
            assert_eq!(a, b, "pose {pose:?}");
        }
    }

    #[test]
    fn misses_read_range_max_and_vehicles_are_seen() {
        let grid = SegmentGrid::new(&[vec![[10.0, -1.0], [10.0, 1.0]]]);
        assert!((grid.cast(0.0, 0.0, 1.0, 0.0, 30.0) - 10.0).abs() < 1e-12);
        assert_eq!(grid.cast(0.0, 0.0, -1.0, 0.0, 30.0), f64::INFINITY);
        assert_eq!(grid.cast(0.0, 0.0, 1.0, 0.0, 5.0), f64::INFINITY);
        assert!(grid.clear_of(9.0, 0.0, 0.99) && !grid.clear_of(9.0, 0.0, 1.01));
        assert!(!grid.clear_of(10.5, 1.2, 0.55) && grid.clear_of(10.5, 1.2, 0.5));
        assert!(grid.clear_of(-100.0, 0.0, 5.0));
        let car = Footprint {
            x: 3.0,
            y: 0.0,
            cos: 1.0,
            sin: 0.0,
            half_length: 0.25,
            half_width: 0.15,
        };
        assert!((car.cast(0.0, 0.0, 1.0, 0.0) - 2.75).abs() < 1e-12);
        assert_eq!(car.cast(0.0, 0.0, 0.0, 1.0), f64::INFINITY);
    }

    #[test]
    fn noise_is_seeded_and_clamped() {
        let grid = SegmentGrid::new(&[square(2.0)]);
        let p = LidarParams {
            noise_std: 0.05,
            ..Default::default()
        };
        let sc = Scanner::new(&p);
        let (mut a, mut b) = (vec![0.0f32; sc.num_beams()], vec![0.0f32; sc.num_beams()]);
        sc.scan(
            [0.0, 0.0, 0.0],
            &grid,
            &[],
            ScanNoise::default(),
            &mut ChaCha8Rng::seed_from_u64(7),
            &mut a,
        );
        sc.scan(
            [0.0, 0.0, 0.0],
            &grid,
            &[],
            ScanNoise::default(),
            &mut ChaCha8Rng::seed_from_u64(7),
            &mut b,
        );
        assert_eq!(a, b);
        assert!(a.iter().all(|&x| (0.0..=30.0).contains(&x)));
    }
}
