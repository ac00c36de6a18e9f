//! The generator's deadline: a wall-clock time and a cancellation flag, checked between
//! candidates and inside lattice growth, and the failure a stopped search reports.

use crate::error::{ArenaError, Result};
use serde::Serialize;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Why a generation stopped before its candidate cap (`"timeout"`, `"cancelled"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Stop {
    /// The wall-clock deadline passed.
    Timeout,
    /// The caller set the cancellation flag (Ctrl-C).
    Cancelled,
}

/// Deadline and cancellation flag; the default never stops.
#[derive(Debug, Clone, Default)]
pub struct Deadline {
    at: Option<Instant>,
    cancel: Option<Arc<AtomicBool>>,
}

impl Deadline {
    /// A deadline `seconds` from now (`None` = unbounded) with an optional flag.
    pub fn new(seconds: Option<f64>, cancel: Option<Arc<AtomicBool>>) -> Deadline {
        let at = seconds
            .filter(|s| s.is_finite() && *s >= 0.0)
            .map(|s| Instant::now() + Duration::from_secs_f64(s.min(1.0e7)));
        Deadline { at, cancel }
    }

    /// [`Deadline::new`] for a caller's timeout, refused unless positive and finite.
    pub fn with_timeout(seconds: Option<f64>, cancel: Option<Arc<AtomicBool>>) -> Result<Deadline> {
        if let Some(t) = seconds {
            if !(t.is_finite() && t > 0.0) {
                return Err(ArenaError::invalid(format!(
                    "timeout: must be a positive finite number of seconds (got {t})"
                )));
            }
        }
        Ok(Deadline::new(seconds, cancel))
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
        if self.at.is_some_and(|d| Instant::now() >= d) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cancelled_flag_and_zero_deadline_stop() {
        let flag = Arc::new(AtomicBool::new(false));
        let b = Deadline::new(None, Some(flag.clone()));
        assert_eq!(b.stopped(), None);
        flag.store(true, Ordering::Relaxed);
        assert_eq!(b.stopped(), Some(Stop::Cancelled));
        assert_eq!(
            Deadline::new(Some(0.0), None).stopped(),
            Some(Stop::Timeout)
        );
        assert_eq!(Deadline::default().stopped(), None);
    }

    #[test]
    fn a_callers_timeout_is_checked_and_a_failure_reads_as_json() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = Deadline::with_timeout(Some(bad), None).unwrap_err();
            assert!(matches!(e, ArenaError::InvalidArgument(_)), "{bad}: {e}");
            assert!(e.to_string().starts_with("timeout:"), "{e}");
        }
        assert!(Deadline::with_timeout(None, None).is_ok());
        assert!(Deadline::with_timeout(Some(0.5), None).is_ok());
        let v = serde_json::to_value(Failure::abandoned()).unwrap();
        assert_eq!(v["tried"], 0);
        assert_eq!(v["stopped"], "timeout");
        assert_eq!(v["reasons"].as_object().unwrap().len(), 1);
        let v = serde_json::to_value(Failure::default()).unwrap();
        assert!(v["stopped"].is_null());
    }
}
