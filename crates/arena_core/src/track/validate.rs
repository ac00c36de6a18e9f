//! The raster validator: every acceptance test of the paper, measured on the occupancy
//! grid (never on the analytic curve). Each check reports its measured value, its bound
//! and pass/fail, so a report explains itself.

use super::features::{
    analyse_closed_curve, is_cyclic_order, self_clearance, CurveAnalysis, FeatureKind,
};
use super::metrics::{measure_raster, RasterTrack};
use crate::generate::spec::{derive, ConstructorConfig, Derived, Spec};
use crate::grid::OccupancyGrid;
use crate::limits::VALIDATOR_RESOLUTION_RANGE_M;
use serde::Serialize;
use std::f64::consts::PI;

/// Lap length tolerance (relative) and width tolerance (relative), from the paper.
pub const LAP_TOLERANCE: f64 = 0.03;
pub const WIDTH_TOLERANCE: f64 = 0.05;

/// One acceptance test.
#[derive(Debug, Clone, Serialize)]
pub struct Check {
    pub name: String,
    pub measured: String,
    pub bound: String,
    pub passed: bool,
}

/// Detected feature in the driving direction, for reports and previews.
#[derive(Debug, Clone, Serialize)]
pub struct FeatureAt {
    pub kind: FeatureKind,
    pub at_m: f64,
    pub x: f64,
    pub y: f64,
}

/// What the validator measured, as numbers (the checks' `measured` strings are for
/// people; code reads these). SI units; `self_clearance_m` is `None` when the lap has no
/// non-local passes.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Measurements {
    pub corridor_components: usize,
    pub infields: usize,
    pub lap_length_m: f64,
    pub width_mean_m: f64,
    pub width_min_m: f64,
    pub min_radius_m: f64,
    pub hairpins: usize,
    pub chicanes: usize,
    pub sweepers: usize,
    pub longest_straight_m: f64,
    pub self_clearance_m: Option<f64>,
    pub extent_m: [f64; 2],
}

/// The validator's verdict on one map.
#[derive(Debug, Clone, Serialize)]
pub struct ValidationReport {
    pub valid: bool,
    pub checks: Vec<Check>,
    /// `None` when the map has no measurable corridor (the `corridor` check says why).
    pub measurements: Option<Measurements>,
    pub features: Vec<FeatureAt>,
    /// Measured centreline in the driving direction (map metres).
    #[serde(skip)]
    pub centreline: Vec<[f64; 2]>,
}

impl ValidationReport {
    pub fn failed(&self) -> Vec<&Check> {
        self.checks.iter().filter(|c| !c.passed).collect()
    }
}

fn check(name: &str, measured: String, bound: String, passed: bool) -> Check {
    Check {
        name: name.into(),
        measured,
        bound,
        passed,
    }
}

/// Largest origin coordinate (m) the validator measures at: beyond it the arithmetic of
/// the measurement loses meaning (the resolution's bound is
/// [`VALIDATOR_RESOLUTION_RANGE_M`]).
pub const MAX_ORIGIN_M: f64 = 1e7;

/// Refuse a map frame the validator cannot measure: a resolution outside
/// [`VALIDATOR_RESOLUTION_RANGE_M`] or an origin beyond ±[`MAX_ORIGIN_M`] or not finite.
pub fn check_frame(resolution: f64, origin: [f64; 3]) -> crate::Result<()> {
    let (lo, hi) = VALIDATOR_RESOLUTION_RANGE_M;
    if !(resolution.is_finite() && (lo..=hi).contains(&resolution)) {
        return Err(crate::ArenaError::invalid(format!(
            "resolution: must be within [{lo}, {hi}] m per cell (got {resolution})"
        )));
    }
    for (name, v, bound) in [
        ("origin x", origin[0], MAX_ORIGIN_M),
        ("origin y", origin[1], MAX_ORIGIN_M),
        ("origin yaw", origin[2], 1e3),
    ] {
        if !(v.is_finite() && v.abs() <= bound) {
            return Err(crate::ArenaError::invalid(format!(
                "{name}: must be a finite number within ±{bound:e} (got {v})"
            )));
        }
    }
    Ok(())
}

/// Validate a map against a spec. Never panics on odd maps: a map without a closed
/// corridor yields a report whose topology check fails.
pub fn validate_map(g: &OccupancyGrid, spec: &Spec, cfg: &ConstructorConfig) -> ValidationReport {
    let d = derive(spec, cfg);
    let res = g.resolution;
    let t = match measure_raster(g) {
        Ok(t) => t,
        Err(e) => return ValidationReport::no_corridor(format!("{e}")),
    };
    let mut line = t.centreline.clone();
    if spec.clockwise() {
        line.reverse();
    }
    let a = analyse_closed_curve(&line, d.corner_radius);
    let min_local = t.widths.iter().cloned().fold(f64::INFINITY, f64::min);
    // Non-local passes must keep the pitch p apart (centreline to centreline); arcs closer
    // than π p / 2 along the lap are local (a hairpin of radius p/2 is still legal).
    let clearance = self_clearance(&line, PI * d.pitch / 2.0, 0.1);
    let mut checks = topology_checks(&t);
    checks.extend(size_checks(spec, &d, &a, t.mean_width_m, min_local, res));
    checks.extend(feature_checks(spec, &a));
    checks.push(clearance_check(clearance, &d, res));
    checks.push(hall_fit_check(spec, cfg, t.extent_m, res));
    let valid = checks.iter().all(|c| c.passed);
    let measurements = Measurements {
        corridor_components: t.corridor_components,
        infields: t.infields,
        lap_length_m: a.length_m,
        width_mean_m: t.mean_width_m,
        width_min_m: min_local,
        min_radius_m: a.min_radius_m,
        hairpins: a.count(FeatureKind::Hairpin),
        chicanes: a.count(FeatureKind::Chicane),
        sweepers: a.count(FeatureKind::Sweeper),
        longest_straight_m: a.longest_straight_m,
        self_clearance_m: clearance.is_finite().then_some(clearance),
        extent_m: t.extent_m,
    };
    let features = a
        .features
        .iter()
        .map(|f| FeatureAt {
            kind: f.kind,
            at_m: f.at_m,
            x: f.x,
            y: f.y,
        })
        .collect();
    ValidationReport {
        valid,
        checks,
        measurements: Some(measurements),
        features,
        centreline: line,
    }
}

impl ValidationReport {
    /// The report on a map without a measurable corridor: one failed `corridor` check
    /// saying why.
    fn no_corridor(why: String) -> ValidationReport {
        ValidationReport {
            valid: false,
            checks: vec![check("corridor", why, "one closed corridor".into(), false)],
            measurements: None,
            features: vec![],
            centreline: vec![],
        }
    }
}

/// One free corridor around exactly one infield.
fn topology_checks(t: &RasterTrack) -> Vec<Check> {
    vec![
        check(
            "corridor",
            format!("{} free component(s)", t.corridor_components),
            "exactly 1".into(),
            t.corridor_components == 1,
        ),
        check(
            "infield",
            format!("{} enclosed region(s)", t.infields),
            "exactly 1".into(),
            t.infields == 1,
        ),
    ]
}

/// Lap length, corridor width (mean, and the local minimum for the report) and the
/// tightest radius, each with the paper's tolerance.
fn size_checks(
    spec: &Spec,
    d: &Derived,
    a: &CurveAnalysis,
    mean_width: f64,
    min_local: f64,
    res: f64,
) -> Vec<Check> {
    let l = spec.lap_length_m;
    let w = spec.corridor_width_m;
    // Raster tolerance on radius: curvature from a staircase centreline is good to ~5 %
    // plus a cell.
    let r_bound = d.r_min * 0.95 - res;
    vec![
        check(
            "lap_length",
            format!("{:.2} m", a.length_m),
            format!(
                "{:.2} m ± 3 % [{:.2}, {:.2}]",
                l,
                l * (1.0 - LAP_TOLERANCE),
                l * (1.0 + LAP_TOLERANCE)
            ),
            (a.length_m - l).abs() <= LAP_TOLERANCE * l,
        ),
        check(
            "width",
            format!("{mean_width:.3} m mean (local min {min_local:.3} m)"),
            format!("{w:.3} m ± 5 %"),
            (mean_width - w).abs() <= WIDTH_TOLERANCE * w,
        ),
        check(
            "min_radius",
            format!("{:.2} m", a.min_radius_m),
            format!("≥ {:.2} m (r_min {:.2} m − 5 % − Δ)", r_bound, d.r_min),
            a.min_radius_m >= r_bound,
        ),
    ]
}

/// Feature counts, then (when the spec asks) their cyclic order and the straights.
fn feature_checks(spec: &Spec, a: &CurveAnalysis) -> Vec<Check> {
    let mut checks = Vec::new();
    for kind in [
        FeatureKind::Hairpin,
        FeatureKind::Chicane,
        FeatureKind::Sweeper,
    ] {
        let (got, want) = (a.count(kind), spec.target(kind) as usize);
        checks.push(check(
            &format!("{}s", kind.name()),
            format!("{got}"),
            format!("= {want}"),
            got == want,
        ));
    }
    if !spec.feature_order.is_empty() {
        let got: Vec<&str> = a.order().iter().map(|k| k.name()).collect();
        let want: Vec<&str> = spec.feature_order.iter().map(|k| k.name()).collect();
        checks.push(check(
            "feature_order",
            got.join(", "),
            format!("cyclic rotation of [{}]", want.join(", ")),
            is_cyclic_order(&a.order(), &spec.feature_order),
        ));
    }
    if spec.longest_straight_m > 0.0 {
        let want = spec.longest_straight_m;
        checks.push(check(
            "longest_straight",
            format!("{:.2} m", a.longest_straight_m),
            format!("≥ {:.2} m (requested {want:.2} m − 5 %)", 0.95 * want),
            a.longest_straight_m >= 0.95 * want,
        ));
    }
    if let Some(cap) = spec.max_straight_m {
        checks.push(check(
            "max_straight",
            format!("{:.2} m", a.longest_straight_m),
            format!("≤ {cap:.2} m (requested cap, no tolerance)"),
            a.longest_straight_m <= cap,
        ));
    }
    checks
}

/// Non-local passes at least the pitch apart (`clearance` is infinite without any).
fn clearance_check(clearance: f64, d: &Derived, res: f64) -> Check {
    let c_bound = d.pitch * 0.97 - res;
    check(
        "self_clearance",
        if clearance.is_finite() {
            format!("{clearance:.2} m")
        } else {
            "no non-local passes".into()
        },
        format!("≥ {c_bound:.2} m (p = {:.2} m − 3 % − Δ)", d.pitch),
        clearance >= c_bound,
    )
}

/// The track's extent within the hall less its margins, in either orientation.
fn hall_fit_check(spec: &Spec, cfg: &ConstructorConfig, [ex, ey]: [f64; 2], res: f64) -> Check {
    let (ux, uy) = (
        spec.hall_x_m - 2.0 * cfg.hall_margin_m,
        spec.hall_y_m - 2.0 * cfg.hall_margin_m,
    );
    let fits = (ex <= ux + res && ey <= uy + res) || (ey <= ux + res && ex <= uy + res);
    check(
        "hall_fit",
        format!("{ex:.2} × {ey:.2} m"),
        format!("within {ux:.2} × {uy:.2} m in either orientation (hall − 2 m_h)"),
        fits,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::construct::{generate, Outcome};
    use crate::generate::deadline::Deadline;

    fn spec() -> Spec {
        Spec {
            direction: crate::generate::spec::Direction::Clockwise,
            hairpins: 1,
            ..Spec::plain(40.0, 1.2, 20.0, 15.0)
        }
    }

    #[test]
    fn measurements_are_the_numbers_the_checks_judge() {
        let (s, cfg) = (spec(), ConstructorConfig::default());
        let Ok(Outcome::Accepted { report, .. }) =
            generate(&s, &cfg, 0, &Deadline::new(None, None))
        else {
            panic!("the 40 m spec should be accepted");
        };
        let m = report.measurements.expect("a valid map is measured");
        assert_eq!((m.corridor_components, m.infields), (1, 1));
        assert!((m.lap_length_m - 40.0).abs() <= LAP_TOLERANCE * 40.0);
        assert!((m.width_mean_m - 1.2).abs() <= WIDTH_TOLERANCE * 1.2);
        assert!(m.width_min_m <= m.width_mean_m && m.width_min_m > 0.0);
        assert_eq!((m.hairpins, m.chicanes, m.sweepers), (1, 0, 0));
        let shown = |name: &str| {
            report
                .checks
                .iter()
                .find(|c| c.name == name)
                .unwrap()
                .measured
                .clone()
        };
        assert_eq!(shown("lap_length"), format!("{:.2} m", m.lap_length_m));
        assert_eq!(shown("min_radius"), format!("{:.2} m", m.min_radius_m));
    }

    #[test]
    fn an_empty_map_has_no_measurements() {
        let g = OccupancyGrid::filled(10, 10, 0.05, [0.0; 3], 205);
        let r = validate_map(&g, &spec(), &ConstructorConfig::default());
        assert!(!r.valid && r.measurements.is_none());
    }
}
