//! Vehicle simulation: rapier3d worlds (one per environment) with 1:10 cars, exact 2D
//! lidar, contact events, odometry, progress and laps, stepped in parallel.
//!
//! * [`params`]: the JSON configuration (mirrors `roboracer_arena.envs.config`)
//! * [`shared_track`]: shared wall mesh, lidar grid and centreline of one track
//! * [`vehicle`]: chassis, suspension, tyres, Ackermann steering, speed controller
//! * [`segments`]: wall segments indexed for beam walks, clearance and segment-scan culling
//! * [`lidar`]: exact ray casting against wall segments and other vehicles
//! * [`segment_scan`]: the same scan segment by segment, in angular order (chosen for small tracks)
//! * [`start_grid`]: the grid start of a track (clearance, free run ahead, grid poses)
//! * [`starts`]: reset draws (track, start poses, speeds, lidar randomisation) per env
//! * [`progress`]: arc length along the centreline and lap counting
//! * [`world`]: one rapier world per environment
//! * [`episode`]: progress since reset, reward terms, wrong-way, termination, truncation
//! * [`observation`]: normalised odometry and scans, written into the observation buffers
//! * [`batch`]: N worlds stepped with rayon, deterministic for any N and thread count
//! * [`budget`]: the size budget of a simulator, checked before allocation

pub mod batch;
pub mod budget;
pub mod episode;
pub mod lidar;
pub mod observation;
pub mod params;
pub mod progress;
pub mod segment_scan;
pub mod segments;
pub mod shapes;
pub mod shared_track;
pub mod start_grid;
pub mod starts;
pub mod vehicle;
pub mod world;

#[cfg(test)]
mod fidelity_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_resets;

pub use batch::{ResetGiven, ResetOut, Simulator, MAX_ABS_YAW, POSE_MARGIN};
pub use budget::{check_size, MAX_SCAN_VALUES, MAX_VEHICLES};
pub use episode::{EpisodeOut, EpisodeParams, Episodes, BACKWARDS_EPS};
pub use observation::{Frames, ObservationNormaliser, ObservationScales, OdometryField};
pub use params::{LateralTyre, LidarParams, PhysicsParams, SimParams, VehicleParams};
pub use progress::ProgressTracker;
pub use shared_track::{Centreline, Track};
pub use start_grid::StartGrid;
pub use starts::StartSpec;
pub use world::{EVENT_FAULT, EVENT_LAP, EVENT_VEHICLE, EVENT_WALL, STATE_FIELDS, STATE_SIZE};
