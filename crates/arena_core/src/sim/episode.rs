//! The episode step: per (env, vehicle) progress since reset, the reward terms,
//! wrong-way driving, termination and truncation, updated from the simulator's state
//! after every step (any number of envs) and restarted with an env's reset.
//!
//! Per vehicle and step of `dt` seconds the reward is
//!
//! ```text
//! progress * ds
//! - stall_penalty * dt      if ds < stall_speed * dt
//! - time_penalty * dt
//! - collision_penalty       on a wall or vehicle contact
//! - wrong_way_penalty       while driving the wrong way
//! ```
//!
//! where `ds` is the change of the vehicle's `travel` (signed metres along the
//! centreline, wrapped at the lap by [`super::progress`]) during the step. A vehicle
//! drives the wrong way when it loses more than [`BACKWARDS_EPS`] of progress in a step
//! while more than `wrong_way_distance` behind its furthest progress since reset:
//! +1 nose first (a U-turn), -1 reversing. An env's reward is the sum over its vehicles;
//! it terminates when any vehicle does (a contact with `collision_ends_episode`, wrong
//! way with `wrong_way_ends_episode`) and is truncated at `max_steps` steps unless it
//! terminated. The order of the operations is the one the Python env used, so the
//! numbers are the same bit for bit (tests/envs/episode_oracle.py).

use super::world::{EVENT_VEHICLE, EVENT_WALL, STATE_FIELDS, STATE_SIZE};
use crate::error::{ArenaError, Result};

/// A step that loses more than this (m) of centreline progress counts as moving backwards.
pub const BACKWARDS_EPS: f64 = 1e-3;

/// Column of `travel` and of `vx` in a state row.
const TRAVEL: usize = 9;
const VX: usize = 3;
const _: () = assert!(STATE_FIELDS.len() == STATE_SIZE && TRAVEL < STATE_SIZE && VX < STATE_SIZE);

/// Reward weights and episode ends (mirrors `envs.env_config.RewardConfig` and the
/// episode fields of `EnvConfig`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EpisodeParams {
    /// Weight of centreline progress (per metre).
    pub progress: f64,
    /// Subtracted on a step with a wall or vehicle contact.
    pub collision_penalty: f64,
    /// Subtracted per second below `stall_speed` of progress.
    pub stall_penalty: f64,
    /// Progress rate (m/s) below which the stall penalty applies.
    pub stall_speed: f64,
    /// Subtracted per second.
    pub time_penalty: f64,
    /// Subtracted on each wrong-way step.
    pub wrong_way_penalty: f64,
    /// Metres behind the furthest progress before backwards driving is wrong-way.
    pub wrong_way_distance: f64,
    /// Seconds per agent step.
    pub dt: f64,
    pub collision_ends_episode: bool,
    pub wrong_way_ends_episode: bool,
    /// Steps before truncation (None: never).
    pub max_steps: Option<u64>,
}

impl Default for EpisodeParams {
    /// The env's defaults (`RewardConfig()`, 20 Hz, no time limit).
    fn default() -> Self {
        EpisodeParams {
            progress: 1.0,
            collision_penalty: 10.0,
            stall_penalty: 1.0,
            stall_speed: 0.5,
            time_penalty: 0.0,
            wrong_way_penalty: 0.0,
            wrong_way_distance: 2.0,
            dt: 0.05,
            collision_ends_episode: true,
            wrong_way_ends_episode: false,
            max_steps: None,
        }
    }
}

impl EpisodeParams {
    /// Every number finite, the penalties, stall speed and wrong-way distance >= 0, dt > 0,
    /// max_steps >= 1.
    pub fn validate(&self) -> Result<()> {
        let fields = [
            ("progress", self.progress, f64::NEG_INFINITY),
            ("collision_penalty", self.collision_penalty, 0.0),
            ("stall_penalty", self.stall_penalty, 0.0),
            ("stall_speed", self.stall_speed, 0.0),
            ("time_penalty", self.time_penalty, 0.0),
            ("wrong_way_penalty", self.wrong_way_penalty, 0.0),
            ("wrong_way_distance", self.wrong_way_distance, 0.0),
        ];
        for (name, v, lo) in fields {
            if !v.is_finite() || v < lo {
                return Err(ArenaError::invalid(format!(
                    "episode {name} must be finite{}, got {v}",
                    if lo == 0.0 { " and >= 0" } else { "" }
                )));
            }
        }
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return Err(ArenaError::invalid(format!(
                "episode dt must be finite and > 0, got {}",
                self.dt
            )));
        }
        if self.max_steps == Some(0) {
            return Err(ArenaError::invalid(
                "episode max_steps must be >= 1 or None",
            ));
        }
        Ok(())
    }
}

/// One vehicle's episode state.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CarEpisode {
    /// `travel` after the previous step (or the reset).
    pub prev_travel: f64,
    /// Metres along the centreline since reset (the sum of the steps' `ds`).
    pub progress: f64,
    pub best_progress: f64,
    /// 0, +1 nose first, -1 reversing.
    pub wrong_way: i8,
    pub terminated: bool,
    /// This step's reward.
    pub reward: f64,
}

/// Where [`Episodes::write`] copies the results: per env (E) and per vehicle (E × V).
pub struct EpisodeOut<'a> {
    pub reward: &'a mut [f64],
    pub terminated: &'a mut [bool],
    pub truncated: &'a mut [bool],
    pub elapsed: &'a mut [i64],
    pub vehicle_reward: &'a mut [f64],
    pub vehicle_terminated: &'a mut [bool],
    pub progress: &'a mut [f64],
    pub wrong_way: &'a mut [i8],
}

/// The episode state of `E` envs × `V` vehicles.
#[derive(Debug, Clone)]
pub struct Episodes {
    pub params: EpisodeParams,
    vehicles: usize,
    cars: Vec<CarEpisode>,
    /// Steps since each env's reset.
    elapsed: Vec<u64>,
}

impl Episodes {
    /// Fresh state (as after a reset at travel 0) for `num_envs` × `vehicles`.
    pub fn new(params: EpisodeParams, num_envs: usize, vehicles: usize) -> Result<Self> {
        params.validate()?;
        Ok(Episodes {
            params,
            vehicles,
            cars: vec![CarEpisode::default(); num_envs * vehicles],
            elapsed: vec![0; num_envs],
        })
    }

    pub fn num_envs(&self) -> usize {
        self.elapsed.len()
    }

    /// Vehicle `v` of env `e`.
    pub fn car(&self, e: usize, v: usize) -> &CarEpisode {
        &self.cars[e * self.vehicles + v]
    }

    pub fn elapsed(&self, e: usize) -> u64 {
        self.elapsed[e]
    }

    /// Restart the episodes of the envs whose mask is true (a reset puts every vehicle's
    /// `travel` at 0: [`super::progress::Progress::reset`]).
    pub fn reset(&mut self, mask: &[bool]) {
        let v = self.vehicles;
        for (e, _) in mask.iter().enumerate().filter(|(_, &m)| m) {
            self.elapsed[e] = 0;
            self.cars[e * v..(e + 1) * v].fill(CarEpisode::default());
        }
    }

    /// One step of every env from the state (E × V × STATE_SIZE) and event bits (E × V)
    /// the simulator wrote after it.
    pub fn update(&mut self, state: &[f64], events: &[u8]) {
        let p = self.params;
        let stall_ds = p.stall_speed * p.dt; // progress per step below which a car stalls
        for e in &mut self.elapsed {
            *e += 1;
        }
        for (k, car) in self.cars.iter_mut().enumerate() {
            let row = &state[k * STATE_SIZE..(k + 1) * STATE_SIZE];
            let travel = row[TRAVEL];
            let ds = travel - car.prev_travel;
            car.prev_travel = travel;
            car.progress += ds;
            let mut r = ds * p.progress;
            if p.stall_penalty != 0.0 && ds < stall_ds {
                r -= p.stall_penalty * p.dt;
            }
            if p.time_penalty != 0.0 {
                r -= p.time_penalty * p.dt;
            }
            let contact = events[k] & (EVENT_WALL | EVENT_VEHICLE) != 0;
            if contact {
                r -= p.collision_penalty;
            }
            car.best_progress = car.best_progress.max(car.progress);
            let wrong =
                ds < -BACKWARDS_EPS && car.best_progress - car.progress > p.wrong_way_distance;
            car.wrong_way = match (wrong, row[VX] >= 0.0) {
                (false, _) => 0,
                (true, true) => 1,
                (true, false) => -1,
            };
            if wrong {
                r -= p.wrong_way_penalty;
            }
            car.terminated =
                (contact && p.collision_ends_episode) || (wrong && p.wrong_way_ends_episode);
            car.reward = r;
        }
    }

    /// Copy the current results into `out` (only the rows of the envs whose mask is true
    /// when a mask is given). Lengths are checked by the caller ([`Self::check_out`]).
    pub fn write(&self, mask: Option<&[bool]>, out: EpisodeOut<'_>) {
        let v = self.vehicles;
        for e in 0..self.num_envs() {
            if mask.is_some_and(|m| !m[e]) {
                continue;
            }
            let cars = &self.cars[e * v..(e + 1) * v];
            let mut reward = 0.0;
            let mut terminated = false;
            for (j, c) in cars.iter().enumerate() {
                let k = e * v + j;
                reward += c.reward;
                terminated |= c.terminated;
                out.vehicle_reward[k] = c.reward;
                out.vehicle_terminated[k] = c.terminated;
                out.progress[k] = c.progress;
                out.wrong_way[k] = c.wrong_way;
            }
            out.reward[e] = if v == 1 { cars[0].reward } else { reward };
            out.terminated[e] = terminated;
            out.truncated[e] =
                !terminated && self.params.max_steps.is_some_and(|m| self.elapsed[e] >= m);
            out.elapsed[e] = self.elapsed[e] as i64;
        }
    }

    /// `out` has E entries per env and E × V per vehicle.
    pub fn check_out(&self, out: &EpisodeOut<'_>) -> Result<()> {
        let (e, n) = (self.num_envs(), self.cars.len());
        let lens = [
            ("reward", out.reward.len(), e),
            ("terminated", out.terminated.len(), e),
            ("truncated", out.truncated.len(), e),
            ("elapsed", out.elapsed.len(), e),
            ("vehicle_reward", out.vehicle_reward.len(), n),
            ("vehicle_terminated", out.vehicle_terminated.len(), n),
            ("progress", out.progress.len(), n),
            ("wrong_way", out.wrong_way.len(), n),
        ];
        for (name, got, want) in lens {
            if got != want {
                return Err(ArenaError::invalid(format!(
                    "episode {name} has {got} elements, expected {want}"
                )));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
#[path = "episode_tests.rs"]
mod tests;
