//! Geometry parameters of the map-to-environment builder. JSON in and out; field names
//! are mirrored by the Python `BuildConfig.geometry`.

use crate::error::{ArenaError, Result};
use serde::{Deserialize, Serialize};

/// Height of the extruded collision walls (m) unless the build says otherwise: the one
/// default for the USD walls and the simulator's walls alike.
pub const DEFAULT_WALL_HEIGHT_M: f64 = 0.5;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BuildParams {
    /// Height of the extruded collision walls (m).
    pub wall_height_m: f64,
    /// Offset of the collision walls from the corridor boundary (m); positive moves
    /// them away from the free space (into the walls), negative narrows the corridor.
    pub wall_offset_m: f64,
    /// Outer diameter of the visual air-duct tubes (m).
    pub tube_diameter_m: f64,
    /// Vertices per tube cross-section (n-gon).
    pub tube_segments: usize,
    /// Arc-length spacing of the rings along each duct (m); 0 disables rings.
    pub ring_spacing_m: f64,
    /// Length of each ring band along the duct (m).
    pub ring_width_m: f64,
    /// Ring radius as a multiple of the tube radius.
    pub ring_scale: f64,
    /// Douglas–Peucker tolerance for walls and ducts (m); 0 = half a map cell.
    pub simplify_tolerance_m: f64,
    /// Taubin smoothing passes applied to the duct paths (the centreline gets 5 × as many).
    pub smoothing_iterations: usize,
    /// Spacing of the resampled centreline (m).
    pub centreline_spacing_m: f64,
    /// Margin of the floor quad around the barriers (m).
    pub floor_margin_m: f64,
}

impl Default for BuildParams {
    fn default() -> Self {
        BuildParams {
            wall_height_m: DEFAULT_WALL_HEIGHT_M,
            wall_offset_m: 0.0,
            tube_diameter_m: 0.33,
            tube_segments: 12,
            ring_spacing_m: 1.0,
            ring_width_m: 0.05,
            ring_scale: 1.12,
            simplify_tolerance_m: 0.0,
            smoothing_iterations: 2,
            centreline_spacing_m: 0.1,
            floor_margin_m: 0.5,
        }
    }
}

impl BuildParams {
    /// Parse JSON (missing fields take their defaults; unknown fields are an error).
    pub fn from_json(s: &str) -> Result<Self> {
        let p: BuildParams = if s.trim().is_empty() {
            BuildParams::default()
        } else {
            serde_json::from_str(s).map_err(|e| ArenaError::config(format!("build params: {e}")))?
        };
        p.validate()?;
        Ok(p)
    }

    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("params serialise")
    }

    /// The simplification tolerance in metres after resolving the "0 = half a cell" rule.
    pub fn simplify_tolerance(&self, resolution: f64) -> f64 {
        if self.simplify_tolerance_m > 0.0 {
            self.simplify_tolerance_m
        } else {
            0.5 * resolution
        }
    }

    /// A copy with every automatic value resolved for a map of `resolution`.
    pub fn effective(&self, resolution: f64) -> Self {
        BuildParams {
            simplify_tolerance_m: self.simplify_tolerance(resolution),
            ..self.clone()
        }
    }

    /// Every field within its plausible range (NaN refused), each error naming the field
    /// and the range. Counts derived from a map's lengths are checked by the builder
    /// (`limits::derived_count`) once those lengths are known.
    pub fn validate(&self) -> Result<()> {
        // The same ranges as the pydantic GeometryConfig (tests/test_config_parity.py).
        let ranges = [
            ("wall_height_m", self.wall_height_m, 1e-3, 10.0),
            ("wall_offset_m", self.wall_offset_m, -1.0, 1.0),
            ("tube_diameter_m", self.tube_diameter_m, 1e-3, 2.0),
            ("ring_width_m", self.ring_width_m, 1e-3, 10.0),
            ("ring_scale", self.ring_scale, 0.1, 3.0),
            (
                "centreline_spacing_m",
                self.centreline_spacing_m,
                1e-3,
                10.0,
            ),
            ("ring_spacing_m", self.ring_spacing_m, 0.0, 1000.0),
            ("simplify_tolerance_m", self.simplify_tolerance_m, 0.0, 10.0),
            ("floor_margin_m", self.floor_margin_m, 0.0, 100.0),
        ];
        for (k, v, lo, hi) in ranges {
            crate::limits::check_range(&format!("build params: geometry.{k}"), v, lo, hi, " m")
                .map_err(|e| ArenaError::config(e.to_string()))?;
        }
        if self.ring_spacing_m > 0.0 && self.ring_spacing_m < self.ring_width_m {
            return Err(ArenaError::config(format!(
                "build params: geometry.ring_spacing_m must be 0 (no rings) or in [{}, 1000] m \
                 (at least ring_width_m), got {}",
                self.ring_width_m,
                crate::limits::show(self.ring_spacing_m)
            )));
        }
        if !(3..=64).contains(&self.tube_segments) {
            return Err(ArenaError::config(format!(
                "build params: geometry.tube_segments must be in 3..=64, got {}",
                self.tube_segments
            )));
        }
        if self.smoothing_iterations > 100 {
            return Err(ArenaError::config(format!(
                "build params: geometry.smoothing_iterations must be in 0..=100, got {}",
                self.smoothing_iterations
            )));
        }
        Ok(())
    }
}

/// The door for a start point from outside: `(x, y)` or `(x, y, yaw)`, all finite;
/// returned as `[x, y, yaw]` (yaw 0 when not given).
pub fn start_point(s: &[f64]) -> Result<[f64; 3]> {
    if !((2..=3).contains(&s.len()) && s.iter().all(|v| v.is_finite())) {
        return Err(ArenaError::invalid(format!(
            "start must be (x, y) or (x, y, yaw) finite numbers, got {s:?}"
        )));
    }
    Ok([s[0], s[1], s.get(2).copied().unwrap_or(0.0)])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn start_point_takes_two_or_three_finite_numbers() {
        assert_eq!(start_point(&[1.0, 2.0]).unwrap(), [1.0, 2.0, 0.0]);
        assert_eq!(start_point(&[1.0, 2.0, 0.5]).unwrap(), [1.0, 2.0, 0.5]);
        for bad in [
            &[1.0][..],
            &[1.0, 2.0, 3.0, 4.0],
            &[f64::NAN, 0.0],
            &[0.0, 0.0, f64::INFINITY],
        ] {
            let e = start_point(bad).unwrap_err();
            assert!(matches!(e, ArenaError::InvalidArgument(_)), "{bad:?}: {e}");
        }
    }

    #[test]
    fn json_defaults_unknown_fields_and_validation() {
        let p = BuildParams::from_json(r#"{"wall_height_m": 0.8}"#).unwrap();
        assert_eq!(p.wall_height_m, 0.8);
        assert_eq!(p.tube_diameter_m, 0.33);
        assert_eq!(BuildParams::from_json(&p.to_json()).unwrap(), p);
        assert!(BuildParams::from_json(r#"{"wall_hieght_m": 0.8}"#)
            .unwrap_err()
            .to_string()
            .contains("unknown field"));
        assert!(BuildParams::from_json(r#"{"tube_diameter_m": -1}"#).is_err());
        for bad in [
            r#"{"centreline_spacing_m": 1e-7}"#,
            r#"{"ring_spacing_m": 1e-7}"#,
            r#"{"wall_offset_m": -5}"#,
            r#"{"wall_height_m": 1e300}"#,
        ] {
            let e = BuildParams::from_json(bad).unwrap_err().to_string();
            let field = bad.split('"').nth(1).unwrap();
            assert!(e.contains(field) && e.contains('['), "{bad}: {e}");
        }
        assert_eq!(
            BuildParams::default().effective(0.05).simplify_tolerance_m,
            0.025
        );
        assert_eq!(BuildParams::from_json("").unwrap(), BuildParams::default());
    }
}
