//! Reset draws of one environment, done natively so that an autoreset costs no Python
//! loop: the track (weighted), the start poses (a random centreline point or a fixed
//! arc length per track, further cars in a staggered grid behind, then lateral and
//! heading noise), rolling-start speeds and this episode's lidar randomisation.
//!
//! Every draw comes from the env's own reset stream, in a fixed order and number per
//! reset, so an env's episodes do not depend on when other envs reset.

use rand_chacha::rand_core::Rng;
use rand_chacha::ChaCha8Rng;

use super::lidar::ScanNoise;
use super::shared_track::Track;
use crate::error::{ArenaError, Result};

/// Largest start distance or noise the core accepts (m, rad, m/s).
pub const MAX_START_VALUE: f64 = 1e4;

/// Largest start heading noise (rad), the env config's bound (`start_heading_noise`).
pub const MAX_HEADING_NOISE_RAD: f64 = 3.2;

/// How resets place the cars (mirrors the env config; see `roboracer_arena.envs`). The
/// binding builds it from keyword arguments (`_core.StartSpec`), checked by [`Self::check`].
#[derive(Debug, Clone, PartialEq)]
pub struct StartSpec {
    /// First grid slot at a uniformly random arc length (else at `s0[track]`).
    pub random_s: bool,
    /// Arc length of the first grid slot per track (when not `random_s`).
    pub s0: Vec<f64>,
    /// Track draw weights (empty: uniform).
    pub track_weights: Vec<f64>,
    pub grid_spacing: f64,
    pub grid_offset: f64,
    pub lateral_noise: f64,
    pub heading_noise: f64,
    /// Half chassis width plus the side margin kept to the wall (m).
    pub side_clearance: f64,
    pub speed_noise: f64,
    /// (low, high) per-episode extra lidar noise std (m).
    pub noise_std: [f64; 2],
    pub dropout: f64,
}

impl StartSpec {
    /// Check against the number of tracks: one `s0` (and weight, if any) per track, and
    /// the ranges of [`Self::check`].
    pub fn validate(&self, num_tracks: usize) -> Result<()> {
        self.check()?;
        let bad = |what: &str| Err(ArenaError::invalid(format!("start spec: {what}")));
        if self.s0.len() != num_tracks {
            return bad(&format!(
                "s0 has {} entries, expected one per track ({num_tracks})",
                self.s0.len()
            ));
        }
        if !self.track_weights.is_empty() && self.track_weights.len() != num_tracks {
            return bad(&format!(
                "track_weights has {} entries, expected one per track ({num_tracks})",
                self.track_weights.len()
            ));
        }
        Ok(())
    }

    /// The ranges, whatever the tracks: finite arc lengths, non-negative weights not all
    /// 0, distances and noises finite in [0, 1e4] (the grid spacing > 0, the heading noise
    /// at most [`MAX_HEADING_NOISE_RAD`]), `noise_std` low <= high <= 1e4, dropout in [0, 1).
    /// The env's pydantic start fields state the same ranges (`tests/test_config_parity.py`).
    pub fn check(&self) -> Result<()> {
        let bad = |what: &str| Err(ArenaError::invalid(format!("start spec: {what}")));
        if self.s0.iter().any(|s| !s.is_finite()) {
            return bad("s0 must be finite");
        }
        let w = &self.track_weights;
        if !w.is_empty()
            && (w.iter().any(|x| !(x.is_finite() && *x >= 0.0)) || w.iter().sum::<f64>() <= 0.0)
        {
            return bad("track_weights must be one finite weight >= 0 per track, not all 0");
        }
        let nonneg = [
            ("grid_spacing", self.grid_spacing),
            ("grid_offset", self.grid_offset),
            ("lateral_noise", self.lateral_noise),
            ("heading_noise", self.heading_noise),
            ("side_clearance", self.side_clearance),
            ("speed_noise", self.speed_noise),
            ("noise_std low", self.noise_std[0]),
        ];
        for (name, v) in nonneg {
            if !(v.is_finite() && (0.0..=MAX_START_VALUE).contains(&v)) {
                return bad(&format!("{name} must be finite and in [0, 1e4], got {v}"));
            }
        }
        if !(self.noise_std[1].is_finite()
            && self.noise_std[1] >= self.noise_std[0]
            && self.noise_std[1] <= MAX_START_VALUE)
        {
            return bad("noise_std must be (low, high) with low <= high <= 1e4");
        }
        if self.grid_spacing <= 0.0 {
            return bad("grid_spacing must be > 0");
        }
        if self.heading_noise > MAX_HEADING_NOISE_RAD {
            return bad(&format!(
                "heading_noise must be at most {MAX_HEADING_NOISE_RAD} rad, got {}",
                self.heading_noise
            ));
        }
        if !(self.dropout.is_finite() && (0.0..1.0).contains(&self.dropout)) {
            return bad("dropout must be in [0, 1)");
        }
        Ok(())
    }
}

/// A uniform draw in [0, 1).
fn unit(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// Draw the track of one env (unless `fixed`) from `rng`; always one draw, so the stream
/// advances the same whatever the pool.
pub fn draw_track(
    spec: &StartSpec,
    fixed: Option<usize>,
    num_tracks: usize,
    rng: &mut ChaCha8Rng,
) -> usize {
    let u = unit(rng);
    if let Some(t) = fixed {
        return t;
    }
    if spec.track_weights.is_empty() {
        return ((u * num_tracks as f64) as usize).min(num_tracks - 1);
    }
    let total: f64 = spec.track_weights.iter().sum();
    let mut acc = 0.0;
    for (i, w) in spec.track_weights.iter().enumerate() {
        acc += w / total;
        if u < acc {
            return i;
        }
    }
    num_tracks - 1
}

/// Start poses (x, y, yaw per car, into `poses`), speeds (into `speeds`) and the lidar
/// randomisation of one env on `track`; a fixed number of draws from `rng` per car.
pub fn draw_start(
    spec: &StartSpec,
    track: &Track,
    track_id: usize,
    rng: &mut ChaCha8Rng,
    poses: &mut [f64],
    speeds: &mut [f64],
) -> ScanNoise {
    let c = &track.centreline;
    let len = c.length();
    let v = speeds.len();
    let u = unit(rng);
    let s0 = if spec.random_s {
        u * len
    } else {
        spec.s0[track_id]
    };
    for (k, (p, sp)) in poses.chunks_exact_mut(3).zip(speeds.iter_mut()).enumerate() {
        let (u_lat, u_yaw, u_speed) = (unit(rng), unit(rng), unit(rng));
        let [cx, cy, yaw] = c.pose_at(s0 - k as f64 * spec.grid_spacing);
        let lat = match (v, k % 2) {
            (1, _) => 0.0,
            (_, 0) => spec.grid_offset,
            _ => -spec.grid_offset,
        };
        let (mut x, mut y) = (cx - lat * yaw.sin(), cy + lat * yaw.cos());
        if spec.lateral_noise > 0.0 {
            let room = (track.grid.clearance(x, y) - spec.side_clearance).max(0.0);
            let off = (2.0 * u_lat - 1.0) * spec.lateral_noise.min(room);
            (x, y) = (x - off * yaw.sin(), y + off * yaw.cos());
        }
        let yaw = yaw + (2.0 * u_yaw - 1.0) * spec.heading_noise;
        p.copy_from_slice(&[x, y, yaw]);
        *sp = u_speed * spec.speed_noise;
    }
    let [lo, hi] = spec.noise_std;
    let extra_std = lo + unit(rng) * (hi - lo);
    ScanNoise {
        extra_std,
        dropout: spec.dropout,
    }
}
