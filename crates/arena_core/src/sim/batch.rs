//! N independent worlds stepped in parallel with rayon.
//!
//! Determinism: each world only reads its own actions and owns its own rapier state and
//! per-vehicle RNGs (seeded from (seed, env index, vehicle index)); rapier runs
//! single-threaded inside a world. Hence results are bit-identical for the same seed
//! whatever the number of environments or threads.
//!
//! Bad actions: the one action rule ([`VehicleModel::sanitise`]): NaN becomes 0
//! (straight / stop), every other value (±inf included) is clipped to ±max_steer and
//! [min_speed, max_speed]. Nothing an action can hold raises or panics; callers that keep
//! the applied actions (the envs' previous action) get the same rule from
//! [`Simulator::sanitise_actions`].
//!
//! Every other input is checked at the door (before anything changes): lengths against
//! the batch's shape, track ids in range, poses finite and within [`POSE_MARGIN`] of the
//! tracks' bounding box with |yaw| <= [`MAX_ABS_YAW`], speeds finite and within the
//! vehicle's range. A bad input is an `InvalidArgument` error naming it; nothing panics.
//!
//! Episodes: with [`Simulator::set_episode`], every step also runs the episode step
//! ([`super::episode`]: progress, reward, wrong-way, termination, truncation) and every
//! reset restarts the reset envs' episodes; [`Simulator::step_episode`] and
//! [`Simulator::observe_episode`] copy the results out with the state.
//!
//! Masks: `reset*` and `observe_masked` touch only the worlds whose mask is true (and
//! their rows of the output buffers), so a partial reset costs what it resets and never
//! advances another env's noise stream.

use std::sync::Arc;

use rayon::prelude::*;

use super::episode::{EpisodeOut, EpisodeParams, Episodes};
use super::lidar::Scanner;
use super::params::SimParams;
use super::shared_track::Track;
use super::starts::{draw_start, draw_track, StartSpec};
use super::vehicle::{CarParams, VehicleModel};
use super::world::{World, STATE_SIZE};
use crate::error::{ArenaError, Result};

/// One world with its reset outputs: track id, poses, speeds.
type ResetRow<'a> = (((&'a mut World, &'a mut i64), &'a mut [f64]), &'a mut [f64]);

/// One world with its slices of the state, events and (optional) scan buffers.
type WorldOutputs<'a> = (
    ((&'a mut World, &'a mut [f64]), &'a mut [u8]),
    Option<&'a mut [f32]>,
);

/// Reset poses may lie at most this far (m) outside the bounding box of the tracks' walls.
pub const POSE_MARGIN: f64 = 100.0;
/// Largest |yaw| (rad) a reset pose may have.
pub const MAX_ABS_YAW: f64 = 1.0e4;

/// Values a caller fixes for a [`Simulator::reset_drawn`] (None: drawn), each the full
/// batch shape (rows of envs that are not reset are ignored).
#[derive(Default, Clone, Copy)]
pub struct ResetGiven<'a> {
    /// E track ids.
    pub tracks: Option<&'a [i64]>,
    /// E × V × 3 poses (x, y, yaw).
    pub poses: Option<&'a [f64]>,
    /// E × V forward speeds (m/s).
    pub speeds: Option<&'a [f64]>,
}

/// Where [`Simulator::reset_drawn`] writes what each reset env got (rows of the envs not
/// reset are left alone): E track ids, E × V × 3 poses, E × V speeds.
pub struct ResetOut<'a> {
    pub tracks: &'a mut [i64],
    pub poses: &'a mut [f64],
    pub speeds: &'a mut [f64],
}

pub struct Simulator {
    params: SimParams,
    model: VehicleModel,
    scanner: Scanner,
    tracks: Vec<Arc<Track>>,
    worlds: Vec<World>,
    vehicles_per_env: usize,
    /// Bounding box of all tracks' walls grown by [`POSE_MARGIN`]: ([x lo, y lo], [x hi, y hi]).
    pose_box: ([f64; 2], [f64; 2]),
    starts: Option<StartSpec>,
    /// The episode bookkeeping, once [`Simulator::set_episode`] configured it.
    episodes: Option<Episodes>,
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
        Self::with_env_offset(tracks, num_envs, vehicles_per_env, params, seed, 0)
    }

    /// [`Simulator::new`] for a batch that is the slice `env_offset..env_offset + num_envs`
    /// of a larger one (e.g. one Ray actor's share): env `e` draws from the streams of
    /// env `env_offset + e`, so the slice sees exactly the larger batch's episodes.
    pub fn with_env_offset(
        tracks: Vec<Arc<Track>>,
        num_envs: usize,
        vehicles_per_env: usize,
        params: SimParams,
        seed: u64,
        env_offset: usize,
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
        // Before any world or buffer exists: a failed allocation would abort the process.
        super::budget::check_size(
            num_envs as u64,
            vehicles_per_env as u64,
            params.lidar.num_beams as u64,
            1,
        )?;
        let model = VehicleModel::new(&params.vehicle, &params.physics);
        let mut scanner = Scanner::new(&params.lidar);
        scanner.split = num_envs == 1;
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
                    env_offset + e,
                )
            })
            .collect();
        let mut pose_box = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for t in &tracks {
            let (lo, hi) = t.grid.bounds();
            for k in 0..2 {
                pose_box.0[k] = pose_box.0[k].min(lo[k] - POSE_MARGIN);
                pose_box.1[k] = pose_box.1[k].max(hi[k] + POSE_MARGIN);
            }
        }
        Ok(Simulator {
            params,
            model,
            scanner,
            tracks,
            worlds,
            vehicles_per_env,
            pose_box,
            starts: None,
            episodes: None,
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
        self.check_tracks(&vec![true; self.num_envs()], ids)?;
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
        self.check_poses(mask, poses)?;
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
        self.reset_episodes(mask);
        Ok(())
    }

    /// Configure how [`Simulator::reset_drawn`] draws (checked against the tracks).
    pub fn set_start_spec(&mut self, spec: StartSpec) -> Result<()> {
        spec.validate(self.tracks.len())?;
        self.starts = Some(spec);
        Ok(())
    }

    /// Reset each env whose mask is true, drawing from its own reset stream (see
    /// [`super::starts`]) its track, start poses, speeds and lidar randomisation, except
    /// what `given` fixes (the draws are made all the same, so the stream advances alike).
    /// Writes what each reset env got into `out`. Needs [`Simulator::set_start_spec`].
    pub fn reset_drawn(
        &mut self,
        mask: &[bool],
        given: ResetGiven<'_>,
        out: ResetOut<'_>,
    ) -> Result<()> {
        let (e, v) = (self.num_envs(), self.vehicles_per_env);
        let Some(spec) = self.starts.as_ref() else {
            return Err(ArenaError::invalid(
                "reset_drawn needs a start spec (set_start_spec) first",
            ));
        };
        self.check_len("env_mask", mask.len(), e)?;
        self.check_len("track_ids", out.tracks.len(), e)?;
        self.check_len("poses", out.poses.len(), e * v * 3)?;
        self.check_len("speeds", out.speeds.len(), e * v)?;
        if let Some(t) = given.tracks {
            self.check_tracks(mask, t)?;
        }
        if let Some(p) = given.poses {
            self.check_poses(mask, p)?;
        }
        if let Some(sp) = given.speeds {
            self.check_speeds(mask, sp)?;
        }
        let (tracks, model) = (&self.tracks, &self.model);
        let one = |(i, (((w, t), p), sp)): (usize, ResetRow<'_>)| {
            if !mask[i] {
                return;
            }
            let fixed = given.tracks.map(|g| g[i] as usize);
            let rng = w.reset_rng();
            let tid = draw_track(spec, fixed, tracks.len(), rng);
            let noise = draw_start(spec, &tracks[tid], tid, rng, p, sp);
            if let Some(g) = given.poses {
                p.copy_from_slice(&g[i * v * 3..(i + 1) * v * 3]);
            }
            if let Some(g) = given.speeds {
                sp.copy_from_slice(&g[i * v..(i + 1) * v]);
            }
            *t = tid as i64;
            w.set_track(tracks[tid].clone(), tid);
            w.set_scan_noise(noise);
            for k in 0..v {
                w.reset_vehicle(k, [p[3 * k], p[3 * k + 1], p[3 * k + 2]], model);
                if sp[k] != 0.0 {
                    w.set_forward_speed(k, sp[k], model);
                }
            }
        };
        if e == 1 {
            self.worlds
                .iter_mut()
                .zip(out.tracks.iter_mut())
                .zip(out.poses.chunks_mut(v * 3))
                .zip(out.speeds.chunks_mut(v))
                .enumerate()
                .for_each(one);
        } else {
            self.worlds
                .par_iter_mut()
                .zip(out.tracks.par_iter_mut())
                .zip(out.poses.par_chunks_mut(v * 3))
                .zip(out.speeds.par_chunks_mut(v))
                .enumerate()
                .for_each(one);
        }
        self.reset_episodes(mask);
        Ok(())
    }

    /// Run the episode step ([`super::episode`]) with `params` from now on: every step
    /// updates it and every reset restarts the reset envs' episodes. A first call starts
    /// every env's episode afresh; a later one changes the parameters and keeps the state
    /// (e.g. dropping the step limit when gymnasium's TimeLimit takes over).
    pub fn set_episode(&mut self, params: EpisodeParams) -> Result<()> {
        match self.episodes.as_mut() {
            Some(ep) => {
                params.validate()?;
                ep.params = params;
            }
            None => {
                self.episodes = Some(Episodes::new(
                    params,
                    self.num_envs(),
                    self.vehicles_per_env,
                )?)
            }
        }
        Ok(())
    }

    /// The episode state, when configured.
    pub fn episodes(&self) -> Option<&Episodes> {
        self.episodes.as_ref()
    }

    fn reset_episodes(&mut self, mask: &[bool]) {
        if let Some(ep) = self.episodes.as_mut() {
            ep.reset(mask);
        }
    }

    /// [`Simulator::step`], then the episode results of every env into `out` (needs
    /// [`Simulator::set_episode`]).
    pub fn step_episode(
        &mut self,
        actions: &[f64],
        substeps: usize,
        scans: Option<&mut [f32]>,
        state: &mut [f64],
        events: &mut [u8],
        out: EpisodeOut<'_>,
    ) -> Result<()> {
        self.episodes_checked(&out)?;
        self.step(actions, substeps, scans, state, events)?;
        self.write_episodes(None, out)
    }

    /// [`Simulator::observe_masked`], then the episode results of the same envs into
    /// `out` (needs [`Simulator::set_episode`]).
    pub fn observe_episode(
        &mut self,
        mask: Option<&[bool]>,
        scans: Option<&mut [f32]>,
        state: &mut [f64],
        events: &mut [u8],
        out: EpisodeOut<'_>,
    ) -> Result<()> {
        self.episodes_checked(&out)?;
        self.observe_masked(mask, scans, state, events)?;
        self.write_episodes(mask, out)
    }

    fn episodes_checked(&self, out: &EpisodeOut<'_>) -> Result<&Episodes> {
        let ep = self.episodes.as_ref().ok_or_else(|| {
            ArenaError::invalid("episode outputs need set_episode (the episode parameters) first")
        })?;
        ep.check_out(out)?;
        Ok(ep)
    }

    fn write_episodes(&self, mask: Option<&[bool]>, out: EpisodeOut<'_>) -> Result<()> {
        self.episodes_checked(&out)?.write(mask, out);
        Ok(())
    }

    /// Give every vehicle of each env whose mask is true a forward speed (`speeds`:
    /// num_envs × vehicles, m/s) after [`Simulator::reset`]: a rolling start. Speeds must
    /// be finite and within the vehicle's [min_speed, max_speed].
    pub fn set_speeds(&mut self, mask: &[bool], speeds: &[f64]) -> Result<()> {
        let v = self.vehicles_per_env;
        self.check_len("env_mask", mask.len(), self.num_envs())?;
        self.check_speeds(mask, speeds)?;
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

    /// Apply the action rule ([`VehicleModel::sanitise`]) in place to `actions`
    /// (E × V × 2: steering, speed), as [`Self::step`] applies it to what it is given.
    pub fn sanitise_actions(&self, actions: &mut [f64]) -> Result<()> {
        let n = self.num_envs() * self.vehicles_per_env * 2;
        self.check_len("actions", actions.len(), n)?;
        for c in actions.chunks_exact_mut(2) {
            (c[0], c[1]) = self.model.sanitise(c[0], c[1]);
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
        self.observe(scans, state, events)?;
        if let Some(ep) = self.episodes.as_mut() {
            ep.update(state, events);
        }
        Ok(())
    }

    /// Write the outputs of every env without stepping.
    pub fn observe(
        &mut self,
        scans: Option<&mut [f32]>,
        state: &mut [f64],
        events: &mut [u8],
    ) -> Result<()> {
        self.observe_masked(None, scans, state, events)
    }

    /// Write the outputs (state, events and, if given, scans) of the envs whose mask is
    /// true (all when None) without stepping; the other envs' rows are left alone and
    /// their noise streams untouched.
    pub fn observe_masked(
        &mut self,
        mask: Option<&[bool]>,
        scans: Option<&mut [f32]>,
        state: &mut [f64],
        events: &mut [u8],
    ) -> Result<()> {
        let v = self.vehicles_per_env;
        if let Some(m) = mask {
            self.check_len("env_mask", m.len(), self.num_envs())?;
        }
        self.check_outputs(scans.as_deref().map(|s| s.len()), state.len(), events.len())?;
        let (model, scanner) = (&self.model, &self.scanner);
        let b = scanner.num_beams();
        let wanted = |i: usize| mask.is_none_or(|m| m[i]);
        let one = |(((w, st), ev), sc): WorldOutputs<'_>| {
            w.write_state(st, ev);
            if let Some(sc) = sc {
                w.scan(scanner, model, sc);
            }
        };
        if self.worlds.len() == 1 {
            if wanted(0) {
                one((((&mut self.worlds[0], state), events), scans));
            }
            return Ok(());
        }
        let worlds = self
            .worlds
            .par_iter_mut()
            .zip(state.par_chunks_mut(v * STATE_SIZE))
            .zip(events.par_chunks_mut(v))
            .enumerate();
        match scans {
            Some(scans) => worlds
                .zip(scans.par_chunks_mut(v * b))
                .for_each(|((i, a), sc)| {
                    if wanted(i) {
                        one((a, Some(sc)))
                    }
                }),
            None => worlds.for_each(|(i, a)| {
                if wanted(i) {
                    one((a, None))
                }
            }),
        }
        Ok(())
    }

    /// Track ids of the masked envs (length num_envs) are in range.
    fn check_tracks(&self, mask: &[bool], ids: &[i64]) -> Result<()> {
        self.check_len("track_ids", ids.len(), self.num_envs())?;
        let n = self.tracks.len();
        match ids
            .iter()
            .zip(mask)
            .position(|(&id, &m)| m && !(0..n as i64).contains(&id))
        {
            Some(e) => Err(ArenaError::invalid(format!(
                "track_ids[{e}] = {} out of range (have {n} tracks)",
                ids[e]
            ))),
            None => Ok(()),
        }
    }

    /// Poses (num_envs × vehicles × 3) of the masked envs are finite, within
    /// [`POSE_MARGIN`] of the tracks' bounding box and |yaw| <= [`MAX_ABS_YAW`].
    fn check_poses(&self, mask: &[bool], poses: &[f64]) -> Result<()> {
        let v = self.vehicles_per_env;
        self.check_len("poses", poses.len(), self.num_envs() * v * 3)?;
        let (lo, hi) = self.pose_box;
        for (i, p) in poses.chunks_exact(3).enumerate() {
            if !mask[i / v] {
                continue;
            }
            let (e, k) = (i / v, i % v);
            if p.iter().any(|x| !x.is_finite()) {
                return Err(ArenaError::invalid(format!(
                    "poses[{e}][{k}] = ({}, {}, {}) is not finite",
                    p[0], p[1], p[2]
                )));
            }
            let inside = (lo[0]..=hi[0]).contains(&p[0]) && (lo[1]..=hi[1]).contains(&p[1]);
            if !inside || p[2].abs() > MAX_ABS_YAW {
                return Err(ArenaError::invalid(format!(
                    "poses[{e}][{k}] = ({}, {}, {}) is out of range: x must be in \
                     [{:.1}, {:.1}], y in [{:.1}, {:.1}] (the tracks' extent plus \
                     {POSE_MARGIN} m) and |yaw| <= {MAX_ABS_YAW}",
                    p[0], p[1], p[2], lo[0], hi[0], lo[1], hi[1]
                )));
            }
        }
        Ok(())
    }

    /// Speeds (num_envs × vehicles) of the masked envs are finite and within the
    /// vehicle's [min_speed, max_speed].
    fn check_speeds(&self, mask: &[bool], speeds: &[f64]) -> Result<()> {
        let v = self.vehicles_per_env;
        self.check_len("speeds", speeds.len(), self.num_envs() * v)?;
        let (lo, hi) = (self.params.vehicle.min_speed, self.params.vehicle.max_speed);
        match speeds
            .iter()
            .enumerate()
            .find(|(i, s)| mask[i / v] && !(s.is_finite() && (lo..=hi).contains(*s)))
        {
            Some((i, s)) => Err(ArenaError::invalid(format!(
                "speeds[{}][{}] = {s} is not finite or outside [{lo}, {hi}] m/s",
                i / v,
                i % v
            ))),
            None => Ok(()),
        }
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
