//! N independent worlds stepped in parallel with rayon.
//!
//! Determinism: each world only reads its own actions and owns its own rapier state and
//! per-vehicle RNGs (seeded from (seed, env index, vehicle index)); rapier runs
//! single-threaded inside a world. Hence results are bit-identical for the same seed
//! whatever the number of environments or threads.
//!
//! Bad actions: NaN or ±inf become 0 (straight / stop); finite values are clipped to
//! ±max_steer and [min_speed, max_speed]. Nothing an action can hold raises or panics.

use std::sync::Arc;

use rayon::prelude::*;

use super::lidar::Scanner;
use super::params::SimParams;
use super::track::Track;
use super::vehicle::{CarParams, VehicleModel};
use super::world::{World, STATE_SIZE};
use crate::error::{ArenaError, Result};

/// One world with its slices of the state, events and (optional) scan buffers.
type WorldOutputs<'a> = (
    ((&'a mut World, &'a mut [f64]), &'a mut [u8]),
    Option<&'a mut [f32]>,
);

pub struct Simulator {
    params: SimParams,
    model: VehicleModel,
    scanner: Scanner,
    tracks: Vec<Arc<Track>>,
    worlds: Vec<World>,
    vehicles_per_env: usize,
}

impl Simulator {
    /// `num_envs` worlds of `vehicles_per_env` cars, all on track 0 until
    /// [`Simulator::set_tracks`].
    pub fn new(
        tracks: Vec<Arc<Track>>,
        num_envs: usize,
        vehicles_per_env: usize,
        params: SimParams,
        seed: u64,
    ) -> Result<Self> {
        params.validate()?;
        if tracks.is_empty() {
            return Err(ArenaError::invalid("Simulator needs at least one track"));
        }
        if num_envs == 0 || vehicles_per_env == 0 {
            return Err(ArenaError::invalid(
                "num_envs and vehicles_per_env must be at least 1",
            ));
        }
        if num_envs.saturating_mul(vehicles_per_env) > 1 << 20 {
            return Err(ArenaError::invalid(
                "num_envs * vehicles_per_env must be at most 2^20",
            ));
        }
        let model = VehicleModel::new(&params.vehicle, &params.physics);
        let scanner = Scanner::new(&params.lidar);
        let worlds = (0..num_envs)
            .into_par_iter()
            .map(|e| {
                World::new(
                    tracks[0].clone(),
                    0,
                    vehicles_per_env,
                    &model,
                    &params.physics,
                    seed,
                    e,
                )
            })
            .collect();
        Ok(Simulator {
            params,
            model,
            scanner,
            tracks,
            worlds,
            vehicles_per_env,
        })
    }

    pub fn num_envs(&self) -> usize {
        self.worlds.len()
    }
    pub fn vehicles_per_env(&self) -> usize {
        self.vehicles_per_env
    }
    pub fn num_beams(&self) -> usize {
        self.scanner.num_beams()
    }
    pub fn params(&self) -> &SimParams {
        &self.params
    }
    pub fn tracks(&self) -> &[Arc<Track>] {
        &self.tracks
    }
    /// Summed over worlds: (steps through the rapier pipeline, contact-free shortcut steps).
    pub fn step_counts(&self) -> [u64; 2] {
        self.worlds.iter().fold([0, 0], |a, w| {
            let c = w.step_counts();
            [a[0] + c[0], a[1] + c[1]]
        })
    }

    pub fn track_of(&self, env: usize) -> usize {
        self.worlds[env].track_id()
    }

    pub fn track(&self, id: usize) -> Result<&Arc<Track>> {
        self.tracks.get(id).ok_or_else(|| {
            ArenaError::invalid(format!(
                "track id {id} out of range (have {})",
                self.tracks.len()
            ))
        })
    }

    /// Choose the track of every environment (length num_envs). Reset afterwards.
    pub fn set_tracks(&mut self, ids: &[i64]) -> Result<()> {
        self.check_len("track_ids", ids.len(), self.num_envs())?;
        for &id in ids {
            if id < 0 || id as usize >= self.tracks.len() {
                return Err(ArenaError::invalid(format!(
                    "track id {id} out of range (have {})",
                    self.tracks.len()
                )));
            }
        }
        for (w, &id) in self.worlds.iter_mut().zip(ids) {
            w.set_track(self.tracks[id as usize].clone(), id as usize);
        }
        Ok(())
    }

    /// Put every vehicle of each env whose mask is true at rest at its pose
    /// (`poses`: num_envs × vehicles × 3, x y yaw). Non-finite poses are refused.
    pub fn reset(&mut self, mask: &[bool], poses: &[f64]) -> Result<()> {
        let v = self.vehicles_per_env;
        self.check_len("env_mask", mask.len(), self.num_envs())?;
        self.check_len("poses", poses.len(), self.num_envs() * v * 3)?;
        for (e, &m) in mask.iter().enumerate() {
            if m && poses[e * v * 3..(e + 1) * v * 3]
                .iter()
                .any(|x| !x.is_finite())
            {
                return Err(ArenaError::invalid(format!(
                    "reset pose of env {e} is not finite"
                )));
            }
        }
        let model = &self.model;
        let run = |((w, &m), p): ((&mut World, &bool), &[f64])| {
            if m {
                for k in 0..v {
                    w.reset_vehicle(k, [p[3 * k], p[3 * k + 1], p[3 * k + 2]], model);
                }
            }
        };
        if self.worlds.len() == 1 {
            self.worlds
                .iter_mut()
                .zip(mask.iter())
                .zip(poses.chunks(v * 3))
                .for_each(run);
        } else {
            self.worlds
                .par_iter_mut()
                .zip(mask.par_iter())
                .zip(poses.par_chunks(v * 3))
                .for_each(run);
        }
        Ok(())
    }

    /// Give every vehicle of each env whose mask is true a forward speed (`speeds`:
    /// num_envs × vehicles, m/s) after [`Simulator::reset`]: a rolling start. Speeds must
    /// be finite and within the vehicle's [min_speed, max_speed].
    pub fn set_speeds(&mut self, mask: &[bool], speeds: &[f64]) -> Result<()> {
        let v = self.vehicles_per_env;
        self.check_len("env_mask", mask.len(), self.num_envs())?;
        self.check_len("speeds", speeds.len(), self.num_envs() * v)?;
        let (lo, hi) = (self.params.vehicle.min_speed, self.params.vehicle.max_speed);
        for (e, &m) in mask.iter().enumerate() {
            if let Some(&s) = speeds[e * v..(e + 1) * v]
                .iter()
                .find(|s| m && !(s.is_finite() && (lo..=hi).contains(*s)))
            {
                return Err(ArenaError::invalid(format!(
                    "start speed {s} of env {e} is not finite or outside [{lo}, {hi}] m/s"
                )));
            }
        }
        for ((w, &m), s) in self.worlds.iter_mut().zip(mask).zip(speeds.chunks(v)) {
            if m {
                for (k, &speed) in s.iter().enumerate() {
                    w.set_forward_speed(k, speed, &self.model);
                }
            }
        }
        Ok(())
    }

    /// Set the per-episode vehicle parameters of every vehicle of each env whose mask is
    /// true (`friction`, `mass`, `steer_lag`, `throttle_lag`: one value per env) for
    /// domain randomisation; they hold until set again. Values must be finite, friction
    /// and mass positive, lags >= 0.
    pub fn set_vehicle_params(
        &mut self,
        mask: &[bool],
        friction: &[f64],
        mass: &[f64],
        steer_lag: &[f64],
        throttle_lag: &[f64],
    ) -> Result<()> {
        let e = self.num_envs();
        self.check_len("env_mask", mask.len(), e)?;
        for (name, a) in [
            ("friction", friction),
            ("mass", mass),
            ("steer_lag", steer_lag),
            ("throttle_lag", throttle_lag),
        ] {
            self.check_len(name, a.len(), e)?;
        }
        let params: Vec<CarParams> = (0..e)
            .map(|i| CarParams {
                friction: friction[i],
                mass: mass[i],
                steer_lag: steer_lag[i],
                throttle_lag: throttle_lag[i],
            })
            .collect();
        for (i, (p, &m)) in params.iter().zip(mask).enumerate() {
            if m {
                p.validate().map_err(|msg| {
                    ArenaError::invalid(format!("vehicle params of env {i}: {msg}"))
                })?;
            }
        }
        for ((w, &m), p) in self.worlds.iter_mut().zip(mask).zip(&params) {
            if m {
                for k in 0..self.vehicles_per_env {
                    w.set_car_params(k, *p, &self.model);
                }
            }
        }
        Ok(())
    }

    /// Step every env: `actions` (E × V × 2: steering, speed), `substeps` physics steps,
    /// then (if `scans` is given, E × V × B) one scan per vehicle; writes `state`
    /// (E × V × STATE_SIZE) and `events` (E × V).
    pub fn step(
        &mut self,
        actions: &[f64],
        substeps: usize,
        scans: Option<&mut [f32]>,
        state: &mut [f64],
        events: &mut [u8],
    ) -> Result<()> {
        let v = self.vehicles_per_env;
        self.check_len("actions", actions.len(), self.num_envs() * v * 2)?;
        if substeps == 0 || substeps > 100_000 {
            return Err(ArenaError::invalid(format!(
                "substeps must be in 1..=100000, got {substeps}"
            )));
        }
        self.check_outputs(scans.as_deref().map(|s| s.len()), state.len(), events.len())?;
        let model = &self.model;
        let run = |(w, a): (&mut World, &[f64])| {
            let cmds: Vec<(f64, f64)> = a
                .chunks_exact(2)
                .map(|c| model.sanitise(c[0], c[1]))
                .collect();
            w.step(&cmds, substeps, model);
        };
        // One env: stay on the calling thread (a rayon hand-off costs microseconds).
        if self.worlds.len() == 1 {
            self.worlds
                .iter_mut()
                .zip(actions.chunks(v * 2))
                .for_each(run);
        } else {
            self.worlds
                .par_iter_mut()
                .zip(actions.par_chunks(v * 2))
                .for_each(run);
        }
        self.observe(scans, state, events)
    }

    /// Write the outputs without stepping.
    pub fn observe(
        &mut self,
        scans: Option<&mut [f32]>,
        state: &mut [f64],
        events: &mut [u8],
    ) -> Result<()> {
        let v = self.vehicles_per_env;
        self.check_outputs(scans.as_deref().map(|s| s.len()), state.len(), events.len())?;
        let (model, scanner) = (&self.model, &self.scanner);
        let b = scanner.num_beams();
        let one = |(((w, st), ev), sc): WorldOutputs<'_>| {
            w.write_state(st, ev);
            if let Some(sc) = sc {
                w.scan(scanner, model, sc);
            }
        };
        if self.worlds.len() == 1 {
            one((((&mut self.worlds[0], state), events), scans));
            return Ok(());
        }
        let worlds = self
            .worlds
            .par_iter_mut()
            .zip(state.par_chunks_mut(v * STATE_SIZE))
            .zip(events.par_chunks_mut(v));
        match scans {
            Some(scans) => worlds
                .zip(scans.par_chunks_mut(v * b))
                .for_each(|(a, sc)| one((a, Some(sc)))),
            None => worlds.for_each(|a| one((a, None))),
        }
        Ok(())
    }

    fn check_len(&self, name: &str, got: usize, want: usize) -> Result<()> {
        if got == want {
            Ok(())
        } else {
            Err(ArenaError::invalid(format!(
                "{name} has {got} elements, expected {want}"
            )))
        }
    }

    fn check_outputs(&self, scans: Option<usize>, state: usize, events: usize) -> Result<()> {
        let n = self.num_envs() * self.vehicles_per_env;
        if let Some(s) = scans {
            self.check_len("scans", s, n * self.num_beams())?;
        }
        self.check_len("state", state, n * STATE_SIZE)?;
        self.check_len("events", events, n)
    }
}
