//! Progress along the centreline and lap counting.
//!
//! `s` is the arc length of the car's projection on the centreline, found by a local
//! search around the previous projection (so a car never jumps to a neighbouring pass
//! of the track). `travel` accumulates the wrapped change of `s` since reset (negative
//! when driving backwards). The start/finish line is the reset pose: `laps` is the number
//! of times the line was crossed forwards minus the times it was crossed backwards
//! (`floor(travel / length)`), so it counts down, below zero too, when the car drives
//! backwards through the line. A lap is *completed* (the event, and `last_lap_time`)
//! only when `laps` exceeds its highest value so far: backing over the line and driving
//! over it again does not complete a lap twice.

use super::shared_track::Centreline;
use crate::error::{ArenaError, Result};

#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Progress {
    pub segment: usize,
    pub s: f64,
    pub travel: f64,
    pub laps: i32,
    /// Highest `laps` reached since reset.
    pub best_laps: i32,
    pub lap_time: f64,
    pub last_lap_time: f64,
}

impl Progress {
    /// Start at position `xy` (global projection).
    pub fn reset(c: &Centreline, xy: [f64; 2]) -> Self {
        let (segment, s) = c.project_global(xy);
        Progress {
            segment,
            s,
            ..Default::default()
        }
    }

    /// Update after the car moved to `xy` during `elapsed` seconds, having moved at most
    /// `max_move` metres. Returns true when a lap was completed.
    pub fn update(&mut self, c: &Centreline, xy: [f64; 2], elapsed: f64, max_move: f64) -> bool {
        if c.is_anchor() {
            // An open map: no reference path, so no progress and no laps (the lap time
            // is the episode's time).
            self.lap_time += elapsed;
            return false;
        }
        let window = 2.0 + 2.0 * max_move;
        let (segment, s) = c.project_local(xy, self.segment, window);
        let len = c.length();
        let mut ds = s - self.s;
        if ds > 0.5 * len {
            ds -= len;
        } else if ds < -0.5 * len {
            ds += len;
        }
        self.segment = segment;
        self.s = s;
        self.travel += ds;
        self.lap_time += elapsed;
        // One crossing per update at most in practice (max_move << len); loops keep the
        // count exact whatever the step.
        while self.travel < self.laps as f64 * len {
            self.laps -= 1;
        }
        let mut completed = false;
        while self.travel >= (self.laps as f64 + 1.0) * len {
            self.laps += 1;
            if self.laps > self.best_laps {
                self.best_laps = self.laps;
                self.last_lap_time = self.lap_time;
                self.lap_time = 0.0;
                completed = true;
            }
        }
        completed
    }
}

/// Progress of a car the simulator does not step (the PhysX drive loop): the same
/// [`Progress`] on its own centreline, fed positions from outside.
#[derive(Debug, Clone)]
pub struct ProgressTracker {
    line: Centreline,
    progress: Progress,
}

impl ProgressTracker {
    /// Start at `xy` on the closed centreline `points` (an open map's two-point anchor
    /// gives no progress and no laps).
    pub fn new(points: &[[f64; 2]], xy: [f64; 2]) -> Result<Self> {
        let line = Centreline::new(points)?;
        check_finite(xy, 0.0, 0.0)?;
        let progress = Progress::reset(&line, xy);
        Ok(ProgressTracker { line, progress })
    }

    /// The car moved to `xy` in `elapsed` seconds, at most `max_move` metres (see
    /// [`Progress::update`]); true when this completed a lap.
    pub fn update(&mut self, xy: [f64; 2], elapsed: f64, max_move: f64) -> Result<bool> {
        check_finite(xy, elapsed, max_move)?;
        if elapsed < 0.0 || max_move < 0.0 {
            return Err(ArenaError::invalid(format!(
                "elapsed and max_move must be >= 0, got {elapsed} and {max_move}"
            )));
        }
        Ok(self.progress.update(&self.line, xy, elapsed, max_move))
    }

    /// The progress so far (travel, laps, lap times).
    pub fn progress(&self) -> &Progress {
        &self.progress
    }

    /// Lap length (m); 0 for an open map's anchor.
    pub fn length(&self) -> f64 {
        self.line.length()
    }
}

fn check_finite(xy: [f64; 2], elapsed: f64, max_move: f64) -> Result<()> {
    if xy
        .iter()
        .chain([&elapsed, &max_move])
        .all(|v| v.is_finite())
    {
        Ok(())
    } else {
        Err(ArenaError::invalid(format!(
            "progress needs finite positions and times, got {xy:?}, {elapsed}, {max_move}"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn laps_count_across_the_wrap() {
        let c = Centreline::new(&[[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]).unwrap();
        let mut p = Progress::reset(&c, [5.0, 0.1]);
        assert!((p.s - 5.0).abs() < 1e-12);
        let mut laps = 0;
        // Drive 1.5 laps forwards in 0.5 m steps along the square.
        for k in 1..=120 {
            let pose = c.pose_at(5.0 + 0.5 * k as f64);
            laps += p.update(&c, [pose[0], pose[1]], 0.1, 0.5) as u32;
        }
        assert_eq!(laps, 1);
        assert_eq!(p.laps, 1);
        assert!((p.travel - 60.0).abs() < 1e-9);
        assert!((p.last_lap_time - 8.0).abs() < 1e-9);
        // Backwards reduces travel and never completes a lap.
        for k in 1..=20 {
            let pose = c.pose_at(65.0 - 0.5 * k as f64);
            assert!(!p.update(&c, [pose[0], pose[1]], 0.1, 0.5));
        }
        assert!((p.travel - 50.0).abs() < 1e-9);
    }

    #[test]
    fn a_tracker_counts_as_the_simulator_does() {
        let sq = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
        let c = Centreline::new(&sq).unwrap();
        let mut t = ProgressTracker::new(&sq, [5.0, 0.1]).unwrap();
        let mut p = Progress::reset(&c, [5.0, 0.1]);
        for k in 1..=90 {
            let pose = c.pose_at(5.0 + 0.5 * k as f64);
            let done = t.update([pose[0], pose[1]], 0.1, 0.5).unwrap();
            assert_eq!(done, p.update(&c, [pose[0], pose[1]], 0.1, 0.5));
        }
        assert_eq!(*t.progress(), p);
        assert_eq!((t.progress().laps, t.length()), (1, 40.0));
        assert!(t.update([f64::NAN, 0.0], 0.1, 0.5).is_err());
        assert!(t.update([0.0, 0.0], -0.1, 0.5).is_err());
        assert!(ProgressTracker::new(&sq, [f64::INFINITY, 0.0]).is_err());
    }

    #[test]
    fn laps_count_down_backwards_through_the_line() {
        let c = Centreline::new(&[[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]).unwrap();
        let mut p = Progress::reset(&c, [5.0, 0.0]);
        // Backwards from the start crosses the line at once: laps = -1, no lap event.
        for k in 1..=10 {
            let pose = c.pose_at(5.0 - 0.5 * k as f64 + 40.0);
            assert!(!p.update(&c, [pose[0], pose[1]], 0.1, 0.5));
        }
        assert_eq!(p.laps, -1);
        assert!((p.travel + 5.0).abs() < 1e-9);
        // Forwards again: back over the line restores 0 but completes nothing.
        for k in 1..=20 {
            let pose = c.pose_at(0.5 * k as f64);
            assert!(!p.update(&c, [pose[0], pose[1]], 0.1, 0.5));
        }
        assert_eq!(p.laps, 0);
        assert_eq!(p.last_lap_time, 0.0);
        // One full lap forwards (from s = 10) completes lap 1 exactly once.
        let mut events = 0;
        for k in 1..=80 {
            let pose = c.pose_at(10.0 + 0.5 * k as f64);
            events += p.update(&c, [pose[0], pose[1]], 0.1, 0.5) as u32;
        }
        assert_eq!((events, p.laps), (1, 1));
        // Back over the line (laps 0) and forwards over it again: still one completed lap.
        for k in 1..=12 {
            let pose = c.pose_at(50.0 - 0.5 * k as f64);
            assert!(!p.update(&c, [pose[0], pose[1]], 0.1, 0.5));
        }
        assert_eq!(p.laps, 0);
        for k in 1..=4 {
            let pose = c.pose_at(44.0 + 0.5 * k as f64);
            assert!(!p.update(&c, [pose[0], pose[1]], 0.1, 0.5));
        }
        assert_eq!(p.laps, 1);
    }
}
