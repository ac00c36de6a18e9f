//! The core's view of a `TrackSpec` (validated in Python by pydantic, passed across the
//! binding as an object and checked again here with the same ranges) and of the
//! constructor's own constants.

use crate::error::{ArenaError, Result};
use crate::track::features::FeatureKind;
use serde::{Deserialize, Serialize};

/// Largest straight cap a spec may state (m), the schema's bound (`TrackSpec`).
pub const MAX_STRAIGHT_CAP_M: f64 = 1_000.0;

/// Share of the straight cap (`max_straight_m`) the constructors aim under: the raster
/// validator measures the straight on the rasterised corridor, which may read a few
/// centimetres longer than the analytic curve.
pub const STRAIGHT_CAP_MARGIN: f64 = 0.95;

/// Driving direction seen from above (`TrackSpec.direction`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    Clockwise,
    Counterclockwise,
}

/// Longest spec name (characters), the schema's bound (`TrackSpec.name`).
pub const MAX_NAME_CHARS: usize = 120;

/// Largest feature count of each kind, the schema's bound (`TrackSpec.hairpins` …).
pub const MAX_FEATURES: u32 = 50;

/// The requirement specification (SI units): the paper's 12 fields and the optional
/// speed cap `max_straight_m`. See `roboracer_arena.spec`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    pub name: String,
    pub lap_length_m: f64,
    pub corridor_width_m: f64,
    pub hall_x_m: f64,
    pub hall_y_m: f64,
    pub direction: Direction,
    pub hairpins: u32,
    pub chicanes: u32,
    pub sweepers: u32,
    #[serde(default)]
    pub feature_order: Vec<FeatureKind>,
    #[serde(default)]
    pub min_radius_m: f64,
    #[serde(default)]
    pub longest_straight_m: f64,
    /// Upper bound on every straight (m): the indoor speed cap. `None` = no cap.
    #[serde(default)]
    pub max_straight_m: Option<f64>,
}

impl Spec {
    /// A featureless counter-clockwise spec (tests): a `lap` m lap, `width` m wide, in a
    /// `hall_x` × `hall_y` m hall.
    #[cfg(test)]
    pub(crate) fn plain(lap: f64, width: f64, hall_x: f64, hall_y: f64) -> Spec {
        Spec {
            name: "test".into(),
            lap_length_m: lap,
            corridor_width_m: width,
            hall_x_m: hall_x,
            hall_y_m: hall_y,
            direction: Direction::Counterclockwise,
            hairpins: 0,
            chicanes: 0,
            sweepers: 0,
            feature_order: vec![],
            min_radius_m: 0.0,
            longest_straight_m: 0.0,
            max_straight_m: None,
        }
    }

    /// Parse the JSON produced by `TrackSpec.model_dump_json()` and [`check`](Self::check) it.
    pub fn from_json(text: &str) -> Result<Spec> {
        let s: Spec =
            serde_json::from_str(text).map_err(|e| ArenaError::Spec(format!("spec JSON: {e}")))?;
        s.check()
    }

    /// The schema's ranges (`TrackSpec`, held equal by `tests/test_config_parity.py`):
    /// a spec outside them is a `SpecError` naming the field.
    pub fn check(self) -> Result<Spec> {
        let s = self;
        let bad = |name: &str, rule: String, got: String| {
            Err(ArenaError::Spec(format!(
                "{name}: must be {rule} (got {got})"
            )))
        };
        let chars = s.name.chars().count();
        if !(1..=MAX_NAME_CHARS).contains(&chars)
            || s.name.trim().is_empty()
            || s.name.chars().any(|c| (c as u32) < 32)
        {
            return bad(
                "name",
                format!("non-blank printable text of 1 to {MAX_NAME_CHARS} characters"),
                format!("{:?}", s.name),
            );
        }
        for (name, v, lo, hi) in [
            ("lap_length_m", s.lap_length_m, 1.0, 2_000.0),
            ("corridor_width_m", s.corridor_width_m, 0.2, 20.0),
            ("hall_x_m", s.hall_x_m, 1.0, 1_000.0),
            ("hall_y_m", s.hall_y_m, 1.0, 1_000.0),
            ("min_radius_m", s.min_radius_m, 0.0, 100.0),
            (
                "longest_straight_m",
                s.longest_straight_m,
                0.0,
                MAX_STRAIGHT_CAP_M,
            ),
        ] {
            if !(lo..=hi).contains(&v) {
                return bad(
                    name,
                    format!("a finite number in [{lo}, {hi}]"),
                    v.to_string(),
                );
            }
        }
        for (name, n) in [
            ("hairpins", s.hairpins),
            ("chicanes", s.chicanes),
            ("sweepers", s.sweepers),
        ] {
            if n > MAX_FEATURES {
                return bad(name, format!("in 0..={MAX_FEATURES}"), n.to_string());
            }
        }
        if let Some(cap) = s.max_straight_m {
            if !(cap.is_finite() && cap > 0.0 && cap <= MAX_STRAIGHT_CAP_M) {
                return bad(
                    "max_straight_m",
                    format!("in (0, {MAX_STRAIGHT_CAP_M}] m or null"),
                    cap.to_string(),
                );
            }
        }
        if !s.feature_order.is_empty() {
            for kind in [
                FeatureKind::Hairpin,
                FeatureKind::Chicane,
                FeatureKind::Sweeper,
            ] {
                let listed = s.feature_order.iter().filter(|k| **k == kind).count();
                if listed != s.target(kind) as usize {
                    let (f, n) = (kind.name(), s.target(kind));
                    return Err(ArenaError::Spec(format!(
                        "feature_order lists {listed} {f}(s) but {f}s = {n}; \
                         the order must name every requested feature exactly once"
                    )));
                }
            }
        }
        Ok(s)
    }

    pub fn clockwise(&self) -> bool {
        self.direction == Direction::Clockwise
    }

    pub fn target(&self, kind: FeatureKind) -> u32 {
        match kind {
            FeatureKind::Hairpin => self.hairpins,
            FeatureKind::Chicane => self.chicanes,
            FeatureKind::Sweeper => self.sweepers,
        }
    }
}

/// The constructor's constants (not part of the request). Defaults are the paper's:
/// `p = w + 2 t_w + d_c = 2.15 m` at the default 1.5 m width, `m_h = 0.5 m`, Δ = 0.05 m.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ConstructorConfig {
    /// Wall thickness t_w (m): one air-duct radius.
    pub wall_thickness_m: f64,
    /// Inter-corridor clearance d_c (m) between the walls of neighbouring passes.
    pub clearance_m: f64,
    /// Hall margin m_h (m) kept free on every side of the hall.
    pub hall_margin_m: f64,
    /// Raster resolution Δ (m per cell).
    pub resolution_m: f64,
    /// Unknown border (m) around the outer wall of the written map.
    pub map_margin_m: f64,
    /// Candidate cap of Algorithm 1.
    pub max_candidates: u32,
}

/// The box (x, y; m) the centreline must stay in: the hall less its margins and one
/// wall-to-wall corridor width. Shared by the constructors (lattice, ring, polygon).
pub(crate) fn centreline_box(spec: &Spec, cfg: &ConstructorConfig) -> [f64; 2] {
    let wall = spec.corridor_width_m + 2.0 * cfg.wall_thickness_m;
    [
        spec.hall_x_m - 2.0 * cfg.hall_margin_m - wall,
        spec.hall_y_m - 2.0 * cfg.hall_margin_m - wall,
    ]
}

impl Default for ConstructorConfig {
    fn default() -> Self {
        ConstructorConfig {
            wall_thickness_m: 0.15,
            clearance_m: 0.35,
            hall_margin_m: 0.5,
            resolution_m: 0.05,
            map_margin_m: 0.25,
            max_candidates: 800,
        }
    }
}

impl ConstructorConfig {
    /// Parse a JSON document and [`check`](Self::check) it.
    pub fn from_json(text: &str) -> Result<ConstructorConfig> {
        let c: ConstructorConfig = serde_json::from_str(text)
            .map_err(|e| ArenaError::config(format!("constructor config JSON: {e}")))?;
        c.check()
    }

    /// The schema's ranges (`roboracer_arena.constructor_config`, held equal by the
    /// parity test).
    pub fn check(self) -> Result<ConstructorConfig> {
        let c = self;
        for (name, v) in [
            ("wall_thickness_m", c.wall_thickness_m),
            ("resolution_m", c.resolution_m),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(ArenaError::config(format!(
                    "constructor config {name}: must be > 0 (got {v})"
                )));
            }
        }
        let (lo, _) = crate::limits::VALIDATOR_RESOLUTION_RANGE_M;
        if !(lo..=1.0).contains(&c.resolution_m) || !(1..=800).contains(&c.max_candidates) {
            return Err(ArenaError::config(format!(
                "constructor config: resolution_m must be in [{lo}, 1] m (got {}) and max_candidates in 1..=800 (got {})",
                c.resolution_m, c.max_candidates
            )));
        }
        for (name, v) in [
            ("clearance_m", c.clearance_m),
            ("hall_margin_m", c.hall_margin_m),
            ("map_margin_m", c.map_margin_m),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(ArenaError::config(format!(
                    "constructor config {name}: must be ≥ 0 (got {v})"
                )));
            }
        }
        Ok(c)
    }
}

/// Derived geometry shared by the screen, the constructor and the validator.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Derived {
    /// r_min (Eq. 1).
    pub r_min: f64,
    /// Pitch p (Eq. 1).
    pub pitch: f64,
    /// L_max (Eq. 1).
    pub l_max: f64,
    /// Lattice pitch lower bound s_min = max(p, 2 r_min).
    pub s_min: f64,
    /// Ordinary-corner radius r_c = s_min / 2 (≥ r_min).
    pub corner_radius: f64,
}

pub fn derive(spec: &Spec, cfg: &ConstructorConfig) -> Derived {
    let w = spec.corridor_width_m;
    let r_min = if spec.min_radius_m > 0.0 {
        spec.min_radius_m
    } else {
        (0.75 * w).max(0.9)
    };
    let pitch = w + 2.0 * cfg.wall_thickness_m + cfg.clearance_m;
    let m = cfg.hall_margin_m;
    let l_max = ((spec.hall_x_m - 2.0 * m).max(0.0) * (spec.hall_y_m - 2.0 * m).max(0.0)) / pitch;
    let s_min = pitch.max(2.0 * r_min);
    Derived {
        r_min,
        pitch,
        l_max,
        s_min,
        corner_radius: s_min / 2.0,
    }
}
