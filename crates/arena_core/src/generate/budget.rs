//! The generator's work bounds: a wall-clock deadline and a cancellation flag, checked
//! between candidates and inside lattice growth, and the size limits a spec must meet
//! before any loop bound is derived from it.

use super::spec::{ConstructorConfig, Spec};
use crate::error::{ArenaError, Result};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Largest raster (cells) a generated map may need: hall area / Δ². 4·10⁷ cells at the
/// default Δ = 0.05 m is a 316 m × 316 m hall; the validator's distance transform and
/// labels take ~15 bytes per cell, so this keeps one candidate under ~0.6 GB.
pub const MAX_RASTER_CELLS: f64 = 4.0e7;

/// Why a generation stopped before its candidate cap.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
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
}
