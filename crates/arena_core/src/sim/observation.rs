//! Normalised observations (`ObservationConfig(normalise=True)` in Python), written
//! straight into the envs' float32 observation buffers after every step and reset.
//!
//! Per vehicle, from its state row and its episode's start pose (x0, y0, yaw0):
//!
//! ```text
//! x, y        start-relative position rotated into the start frame, / position_scale
//!             (not clipped: the only unbounded columns)
//! yaw         two columns: sin and cos of (yaw - yaw0) (no wrap)
//! vx, vy, speed / max_speed;  yaw_rate / 2 pi;  steer / max_steer   (clipped to ±1)
//! scan        range * (1 / min(horizon, range_max)) in float32, clipped to 1
//! ```
//!
//! Every value is computed in f64 in the order the Python env's numpy code used (each
//! numpy operation is one IEEE operation; `sin`/`cos` are the platform libm's, as
//! numpy's) and cast to f32 at the end, so the observations are the same bit for bit
//! (`tests/envs/observation_oracle.py`); NaN stays NaN.

use super::world::{STATE_FIELDS, STATE_SIZE};
use crate::error::{ArenaError, Result};

/// An odometry column of the observation: a state field as the observation reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OdometryField {
    X,
    Y,
    Yaw,
    Vx,
    Vy,
    YawRate,
    Steer,
    Speed,
}

impl OdometryField {
    /// Every field, in state-column order (field `i` is state column `i`).
    pub const ALL: [OdometryField; 8] = [
        OdometryField::X,
        OdometryField::Y,
        OdometryField::Yaw,
        OdometryField::Vx,
        OdometryField::Vy,
        OdometryField::YawRate,
        OdometryField::Steer,
        OdometryField::Speed,
    ];

    /// Its state column (the index in [`STATE_FIELDS`]).
    pub fn state_column(self) -> usize {
        self as usize
    }

    /// Its name (the state field's).
    pub fn name(self) -> &'static str {
        STATE_FIELDS[self.state_column()]
    }

    /// The field named `name`, or `InvalidArgument` naming the allowed names.
    pub fn parse(name: &str) -> Result<Self> {
        Self::ALL
            .into_iter()
            .find(|f| f.name() == name)
            .ok_or_else(|| {
                let names: Vec<&str> = Self::ALL.iter().map(|f| f.name()).collect();
                ArenaError::invalid(format!(
                    "unknown odometry field {name:?}; choose from {names:?}"
                ))
            })
    }
}

// Field i reads state column i, and the normaliser indexes rows of STATE_SIZE.
const _: () = {
    let mut i = 0;
    while i < OdometryField::ALL.len() {
        assert!(OdometryField::ALL[i] as usize == i);
        i += 1;
    }
    assert!(OdometryField::ALL.len() <= STATE_SIZE);
};

/// The scales of a normalised observation (from `ObservationConfig` and the vehicle and
/// lidar parameters).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObservationScales {
    /// Metres from the start pose that map to ±1 (x, y).
    pub position_scale: f64,
    /// Ranges are clipped to min(horizon, range_max), then scaled to [0, 1].
    pub horizon: f64,
    /// The lidar's maximum range (m).
    pub range_max: f64,
    /// vx, vy and speed are divided by this (m/s).
    pub max_speed: f64,
    /// steer is divided by this (rad).
    pub max_steer: f64,
}

impl ObservationScales {
    /// Every scale finite and positive (horizon may be infinite), else `Config`.
    pub fn validate(&self) -> Result<()> {
        let finite = [
            ("position_scale", self.position_scale),
            ("range_max", self.range_max),
            ("max_speed", self.max_speed),
            ("max_steer", self.max_steer),
        ];
        for (name, v) in finite {
            if !(v.is_finite() && v > 0.0) {
                return Err(ArenaError::config(format!(
                    "observation {name} must be finite and > 0, got {v}"
                )));
            }
        }
        if self.horizon.is_nan() || self.horizon <= 0.0 {
            return Err(ArenaError::config(format!(
                "observation horizon must be > 0, got {}",
                self.horizon
            )));
        }
        Ok(())
    }
}

/// One output column: what it divides by and where it is clipped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Column {
    pub name: &'static str,
    /// The value is divided by this (1 for yaw's sin and cos).
    pub scale: f64,
    /// The value is clipped to ±bound (infinite for x and y).
    pub bound: f64,
}

/// The layout of a batch of observation buffers: `envs` × `vehicles` rows, each holding
/// `frames` frames (the newest last); `env_mask` selects the envs written (None: all).
#[derive(Clone, Copy, Debug)]
pub struct Frames<'m> {
    pub envs: usize,
    pub vehicles: usize,
    pub frames: usize,
    pub env_mask: Option<&'m [bool]>,
}

/// The normalised odometry columns and scan of one observation config (see module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct ObservationNormaliser {
    fields: Vec<OdometryField>,
    scales: ObservationScales,
    /// One per output column (yaw has two).
    columns: Vec<Column>,
    /// 1 / min(horizon, range_max), rounded to f32 (numpy's `np.float32(1.0 / ...)`).
    scan_scale: f32,
}

impl ObservationNormaliser {
    /// The normaliser of odometry `fields` (in output order, no repeats) and `scales`.
    pub fn new(fields: Vec<OdometryField>, scales: ObservationScales) -> Result<Self> {
        scales.validate()?;
        for (i, f) in fields.iter().enumerate() {
            if fields[..i].contains(f) {
                return Err(ArenaError::config(format!(
                    "odometry field {:?} repeats",
                    f.name()
                )));
            }
        }
        let columns = fields
            .iter()
            .flat_map(|&f| columns_of(f, &scales))
            .collect();
        Ok(ObservationNormaliser {
            scan_scale: (1.0 / scales.horizon.min(scales.range_max)) as f32,
            fields,
            scales,
            columns,
        })
    }

    /// The output columns, in order (yaw gives `yaw_sin`, `yaw_cos`).
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    pub fn fields(&self) -> &[OdometryField] {
        &self.fields
    }

    /// The scan's factor (float32).
    pub fn scan_scale(&self) -> f32 {
        self.scan_scale
    }

    /// One vehicle's normalised odometry (`columns().len()` values) from its state row
    /// (at least [`STATE_SIZE`] values) and its start pose (x0, y0, yaw0).
    pub fn odometry_row(&self, state: &[f64], start: &[f64; 3], out: &mut [f32]) {
        let col = |f: OdometryField| state[f.state_column()];
        let (dx, dy) = (
            col(OdometryField::X) - start[0],
            col(OdometryField::Y) - start[1],
        );
        let ps = self.scales.position_scale;
        let mut out = out.iter_mut().zip(&self.columns);
        let mut put = |v: f64| {
            if let Some((o, c)) = out.next() {
                *o = clip(v, c.bound) as f32;
            }
        };
        for &f in &self.fields {
            match f {
                OdometryField::X => put((dx * start[2].cos() + dy * start[2].sin()) / ps),
                OdometryField::Y => put((-dx * start[2].sin() + dy * start[2].cos()) / ps),
                OdometryField::Yaw => {
                    let rel = col(OdometryField::Yaw) - start[2];
                    put(rel.sin());
                    put(rel.cos());
                }
                _ => put(col(f) / scale_of(f, &self.scales)),
            }
        }
    }

    /// One vehicle's normalised scan from its ranges (m), as many values.
    pub fn scan_row(&self, ranges: &[f32], out: &mut [f32]) {
        for (o, &r) in out.iter_mut().zip(ranges) {
            let v = r * self.scan_scale;
            *o = if v > 1.0 { 1.0 } else { v }; // (NaN stays NaN, as np.minimum)
        }
    }

    /// The newest frame of every (selected) row of `out` from `state` (E × V ×
    /// [`STATE_SIZE`]) and `starts` (E × V × 3); other frames and rows are left alone.
    pub fn write_odometry(
        &self,
        state: &[f64],
        starts: &[f64],
        out: &mut [f32],
        frames: Frames<'_>,
    ) -> Result<()> {
        check_len("starts", starts.len(), frames.envs * frames.vehicles * 3)?;
        each_row(
            state,
            STATE_SIZE,
            "state",
            out,
            self.columns.len(),
            frames,
            |r, s, o| {
                let start = [starts[3 * r], starts[3 * r + 1], starts[3 * r + 2]];
                self.odometry_row(s, &start, o)
            },
        )
    }

    /// The newest frame of every (selected) row of `out` from `scans` (E × V × beams).
    pub fn write_scans(
        &self,
        scans: &[f32],
        beams: usize,
        out: &mut [f32],
        frames: Frames<'_>,
    ) -> Result<()> {
        each_row(scans, beams, "scans", out, beams, frames, |_, s, o| {
            self.scan_row(s, o)
        })
    }
}

/// The output columns of field `f` (yaw: sin and cos).
fn columns_of(f: OdometryField, scales: &ObservationScales) -> Vec<Column> {
    let bounded = |name, scale| Column {
        name,
        scale,
        bound: 1.0,
    };
    match f {
        OdometryField::X | OdometryField::Y => vec![Column {
            name: f.name(),
            scale: scales.position_scale,
            bound: f64::INFINITY,
        }],
        OdometryField::Yaw => vec![bounded("yaw_sin", 1.0), bounded("yaw_cos", 1.0)],
        _ => vec![bounded(f.name(), scale_of(f, scales))],
    }
}

/// What a velocity or steering field is divided by.
fn scale_of(f: OdometryField, scales: &ObservationScales) -> f64 {
    match f {
        OdometryField::YawRate => std::f64::consts::TAU, // (== 2 * pi exactly)
        OdometryField::Steer => scales.max_steer,
        OdometryField::X | OdometryField::Y => scales.position_scale,
        OdometryField::Yaw => 1.0,
        OdometryField::Vx | OdometryField::Vy | OdometryField::Speed => scales.max_speed,
    }
}

/// `v` clipped to ±bound as `np.clip` does (NaN stays NaN).
fn clip(v: f64, bound: f64) -> f64 {
    if v < -bound {
        -bound
    } else if v > bound {
        bound
    } else {
        v
    }
}

fn check_len(name: &str, got: usize, want: usize) -> Result<()> {
    if got == want {
        Ok(())
    } else {
        Err(ArenaError::invalid(format!(
            "{name} has {got} elements, expected {want}"
        )))
    }
}

/// Run `f(row, input row, newest output frame)` for every row of the selected envs, after
/// checking every length against `frames`.
fn each_row<I, O>(
    input: &[I],
    in_width: usize,
    in_name: &str,
    out: &mut [O],
    out_width: usize,
    frames: Frames<'_>,
    mut f: impl FnMut(usize, &[I], &mut [O]),
) -> Result<()> {
    let rows = frames.envs * frames.vehicles;
    if frames.frames == 0 {
        return Err(ArenaError::invalid(
            "an observation holds at least one frame",
        ));
    }
    check_len(in_name, input.len(), rows * in_width)?;
    check_len("observation", out.len(), rows * frames.frames * out_width)?;
    if let Some(m) = frames.env_mask {
        check_len("env_mask", m.len(), frames.envs)?;
    }
    if in_width == 0 || out_width == 0 {
        return Ok(());
    }
    let newest = (frames.frames - 1) * out_width;
    let pairs = input
        .chunks_exact(in_width)
        .zip(out.chunks_exact_mut(frames.frames * out_width));
    for (r, (i, o)) in pairs.enumerate() {
        if frames.env_mask.is_none_or(|m| m[r / frames.vehicles]) {
            f(r, i, &mut o[newest..])
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "observation_tests.rs"]
mod tests;
