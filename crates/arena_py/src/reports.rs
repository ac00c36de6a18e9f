//! The core's reports as typed, read-only Python objects (issue 37): the admissibility
//! screen, the derived geometry, the raster validator's report, the curve analysis and a
//! map file's metadata.
//! Each is a [`mirror!`] of its core struct (exhaustive, so they cannot drift); the
//! package's pydantic models (`generate/report.py`) are built from their attributes.

use arena_core::generate::screen::ScreenResult as CoreScreen;
use arena_core::generate::spec::Derived as CoreDerived;
use arena_core::grid::mapfile::MapMeta as CoreMapMeta;
use arena_core::track::features::{
    CurveAnalysis as CoreCurve, CurveReport, Feature as CoreFeature, Turn as CoreTurn,
};
use arena_core::track::validate::{
    Check as CoreCheck, FeatureAt as CoreFeatureAt, Measurements as CoreMeasurements,
    ValidationReport as CoreReport,
};
use pyo3::prelude::*;

use crate::mirror::mirror;

mirror!(
    /// The admissibility screen (Eqs. 1–2): ``passed`` or the ``violations`` stated with
    /// numbers, and every quantity the bounds use (m).
    ScreenResult {
        passed: bool,
        violations: Vec<String>,
        r_min_m: f64,
        pitch_m: f64,
        l_max_m: f64,
        l_min_m: f64,
        feature_length_m: f64,
        feature_budget_m: f64,
    } from CoreScreen
);

mirror!(
    /// Lengths derived from a spec (m), read-only: r_min and pitch p (Eq. 1), L_max, the
    /// lattice pitch bound s_min = max(p, 2 r_min) and the corner radius r_c = s_min / 2.
    Derived {
        r_min: f64,
        pitch: f64,
        l_max: f64,
        s_min: f64,
        corner_radius: f64,
    } from CoreDerived
);

mirror!(
    /// One acceptance test: ``measured`` and ``bound`` are for people, ``passed`` decides.
    Check {
        name: String,
        measured: String,
        bound: String,
        passed: bool,
    } from CoreCheck
);

mirror!(
    /// A detected feature (``kind`` hairpin, chicane or sweeper), ``at_m`` metres along
    /// the lap in the driving direction, at (``x``, ``y``).
    FeatureAt {
        kind: String,
        at_m: f64,
        x: f64,
        y: f64,
    } from CoreFeatureAt, CoreFeature
);

mirror!(
    /// What the validator measured, in SI units; ``self_clearance_m`` is None when the
    /// lap has no non-local passes.
    Measurements {
        corridor_components: usize,
        infields: usize,
        lap_length_m: f64,
        width_mean_m: f64,
        width_min_m: f64,
        min_radius_m: f64,
        hairpins: usize,
        chicanes: usize,
        sweepers: usize,
        longest_straight_m: f64,
        self_clearance_m: Option<f64>,
        extent_m: (f64, f64),
    } from CoreMeasurements
);

mirror!(
    /// The raster validator's verdict on one map: ``measurements`` is None when the map
    /// has no measurable corridor (the ``corridor`` check says why).
    ValidationReport {
        valid: bool,
        checks: Vec<Py<Check>>,
        measurements: Option<Py<Measurements>>,
        features: Vec<Py<FeatureAt>>,
    } from CoreReport = CoreReport {
        valid, checks, measurements, features,
        centreline: _, // crosses beside the report, as an array (`validate_map`)
    }
);

mirror!(
    /// One turn of a closed curve: where it runs (m along the lap), by how much (rad,
    /// + = left) and its tightest radius (m).
    Turn {
        start_m: f64,
        end_m: f64,
        angle_rad: f64,
        peak_radius_m: f64,
    } from CoreTurn
);

mirror!(
    /// The curvature analysis of a closed curve in its driving direction: turns, detected
    /// features, minimum radius, longest straight, total turn (rad), and the
    /// self-clearance outside the excluded arc (None when no other pass comes near).
    CurveAnalysis {
        length_m: f64,
        min_radius_m: f64,
        turns: Vec<Py<Turn>>,
        features: Vec<Py<FeatureAt>>,
        longest_straight_m: f64,
        total_turn_rad: f64,
        self_clearance_m: Option<f64>,
    } from CurveReport = CurveReport {
        analysis: CoreCurve {
            length_m, min_radius_m, turns, features, longest_straight_m, total_turn_rad,
        },
        self_clearance_m,
    }
);

mirror!(
    /// What a map file said besides the grid: the files, the image's encoding
    /// (``image_format`` png or pgm), channels and bit depth, the nav2 ``mode``
    /// (trinary, scale or raw), ``negate``, the thresholds and the optional keys that
    /// were absent and took their default (``defaulted``).
    MapMeta {
        yaml_path: String,
        image_path: String,
        image_format: String,
        image_channels: usize,
        image_bit_depth: u8,
        mode: String,
        negate: bool,
        occupied_thresh: f64,
        free_thresh: f64,
        defaulted: Vec<String>,
    } from CoreMapMeta
);

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<ScreenResult>()?;
    m.add_class::<Derived>()?;
    m.add_class::<ValidationReport>()?;
    m.add_class::<Check>()?;
    m.add_class::<Measurements>()?;
    m.add_class::<FeatureAt>()?;
    m.add_class::<CurveAnalysis>()?;
    m.add_class::<Turn>()?;
    m.add_class::<MapMeta>()?;
    Ok(())
}
