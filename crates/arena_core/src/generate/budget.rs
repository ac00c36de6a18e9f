//! The generator's work bounds: a wall-clock deadline and a cancellation flag, checked
//! between candidates and inside lattice growth, and the size limits a spec must meet
//! before any loop bound is derived from it.

use super::spec::{ConstructorConfig, Spec};
use crate::error::{ArenaError, Result};
use serde::Serialize;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Largest raster (cells) a generated map may need: hall area / Δ². 4·10⁷ cells at the
/// default Δ = 0.05 m is a 316 m × 316 m hall; the validator's distance transform and
/// labels take ~15 bytes per cell, so this keeps one candidate under ~0.6 GB.
pub const MAX_RASTER_CELLS: f64 = 4.0e7;

/// Why a generation stopped before its candidate cap (`"timeout"`, `"cancelled"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Stop {
    /// The wall-clock budget ran out.
    Timeout,
    /// The caller set the cancellation flag (Ctrl-C).
    Cancelled,
}

/// Deadline and cancellation flag; the default never stops.
#[derive(Debug, Clone, Default)]
pub struct Budget {
    deadline: Option<Instant>,
    cancel: Option<Arc<AtomicBool>>,
}

impl Budget {
    /// A budget of `seconds` from now (`None` = unbounded) with an optional flag.
    pub fn new(seconds: Option<f64>, cancel: Option<Arc<AtomicBool>>) -> Budget {
        let deadline = seconds
            .filter(|s| s.is_finite() && *s >= 0.0)
            .map(|s| Instant::now() + Duration::from_secs_f64(s.min(1.0e7)));
        Budget { deadline, cancel }
    }

    /// [`Budget::new`] for a caller's timeout, refused unless positive and finite.
    pub fn with_timeout(seconds: Option<f64>, cancel: Option<Arc<AtomicBool>>) -> Result<Budget> {
        if let Some(t) = seconds {
            if !(t.is_finite() && t > 0.0) {
                return Err(ArenaError::invalid(format!(
                    "timeout: must be a positive finite number of seconds (got {t})"
                )));
            }
        }
        Ok(Budget::new(seconds, cancel))
    }

    /// `Some(reason)` once the work must stop.
    pub fn stopped(&self) -> Option<Stop> {
        if self
            .cancel
            .as_ref()
            .is_some_and(|c| c.load(Ordering::Relaxed))
        {
            return Some(Stop::Cancelled);
        }
        if self.deadline.is_some_and(|d| Instant::now() >= d) {
            return Some(Stop::Timeout);
        }
        None
    }
}

/// A bounded generation that ended without a track: candidates tried, each reason
/// counted, and what stopped it early (`None` = it reached its candidate cap).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Failure {
    pub tried: u32,
    pub reasons: BTreeMap<String, u32>,
    pub stopped: Option<Stop>,
}

impl Failure {
    /// The failure a caller reports when the deadline passed inside one candidate and it
    /// stopped waiting (how many candidates were tried is unknown).
    pub fn abandoned() -> Failure {
        let why = "time budget ran out inside one candidate (rasterising or validating)";
        Failure {
            tried: 0,
            reasons: BTreeMap::from([(why.to_string(), 1)]),
            stopped: Some(Stop::Timeout),
        }
    }
}

/// Refuse specs whose raster or loop bounds the generator cannot hold, before any
/// allocation or loop: the hall's raster must stay within [`MAX_RASTER_CELLS`].
pub fn check_limits(spec: &Spec, cfg: &ConstructorConfig) -> Result<()> {
    let pad = 2.0 * (cfg.map_margin_m + cfg.wall_thickness_m) + spec.corridor_width_m;
    let cells =
        ((spec.hall_x_m + pad) / cfg.resolution_m) * ((spec.hall_y_m + pad) / cfg.resolution_m);
    if !(cells.is_finite() && cells <= MAX_RASTER_CELLS) {
        let side = MAX_RASTER_CELLS.sqrt() * cfg.resolution_m;
        return Err(ArenaError::Spec(format!(
            "hall_x_m × hall_y_m: a {}×{} m hall needs {cells:.3e} raster cells at {} m; \
             the generator allows at most {MAX_RASTER_CELLS:.0e} (about {side:.0}×{side:.0} m)",
            spec.hall_x_m, spec.hall_y_m, cfg.resolution_m
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cancelled_flag_and_zero_deadline_stop() {
        let flag = Arc::new(AtomicBool::new(false));
        let b = Budget::new(None, Some(flag.clone()));
        assert_eq!(b.stopped(), None);
        flag.store(true, Ordering::Relaxed);
        assert_eq!(b.stopped(), Some(Stop::Cancelled));
        assert_eq!(Budget::new(Some(0.0), None).stopped(), Some(Stop::Timeout));
        assert_eq!(Budget::default().stopped(), None);
    }

    #[test]
    fn a_callers_timeout_is_checked_and_a_failure_reads_as_json() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = Budget::with_timeout(Some(bad), None).unwrap_err();
            assert!(matches!(e, ArenaError::InvalidArgument(_)), "{bad}: {e}");
            assert!(e.to_string().starts_with("timeout:"), "{e}");
        }
        assert!(Budget::with_timeout(None, None).is_ok());
        assert!(Budget::with_timeout(Some(0.5), None).is_ok());
        let v = serde_json::to_value(Failure::abandoned()).unwrap();
        assert_eq!(v["tried"], 0);
        assert_eq!(v["stopped"], "timeout");
        assert_eq!(v["reasons"].as_object().unwrap().len(), 1);
        let v = serde_json::to_value(Failure::default()).unwrap();
        assert!(v["stopped"].is_null());
    }
}
