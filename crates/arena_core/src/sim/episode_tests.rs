//! Each reward term, wrong-way, termination, truncation and reset of [`Episodes`] on
//! hand-made state rows (the env-level parity with the old Python is
//! tests/envs/test_episode_step.py).

use super::*;

/// No term but progress, nothing ends, no limit.
fn plain() -> EpisodeParams {
    EpisodeParams {
        progress: 1.0,
        collision_penalty: 0.0,
        stall_penalty: 0.0,
        stall_speed: 0.5,
        time_penalty: 0.0,
        wrong_way_penalty: 0.0,
        wrong_way_distance: 0.95,
        dt: 0.1,
        collision_ends_episode: false,
        wrong_way_ends_episode: false,
        max_steps: None,
    }
}

/// State rows of `travel` and `vx` per vehicle.
fn rows(travel: &[f64], vx: &[f64]) -> Vec<f64> {
    let mut s = vec![0.0; travel.len() * STATE_SIZE];
    for (k, (&t, &v)) in travel.iter().zip(vx).enumerate() {
        s[k * STATE_SIZE + TRAVEL] = t;
        s[k * STATE_SIZE + VX] = v;
    }
    s
}

/// Results of all envs: (reward, terminated, truncated, elapsed, vehicle rewards,
/// vehicle terminated, progress, wrong way).
#[allow(clippy::type_complexity)]
fn results(
    ep: &Episodes,
) -> (
    Vec<f64>,
    Vec<bool>,
    Vec<bool>,
    Vec<i64>,
    Vec<f64>,
    Vec<bool>,
    Vec<f64>,
    Vec<i8>,
) {
    let (e, n) = (ep.num_envs(), ep.cars.len());
    let (mut r, mut t, mut tr, mut el) = (vec![0.0; e], vec![false; e], vec![false; e], vec![0; e]);
    let (mut vr, mut vt, mut pr, mut ww) = (vec![0.0; n], vec![false; n], vec![0.0; n], vec![0; n]);
    let out = EpisodeOut {
        reward: &mut r,
        terminated: &mut t,
        truncated: &mut tr,
        elapsed: &mut el,
        vehicle_reward: &mut vr,
        vehicle_terminated: &mut vt,
        progress: &mut pr,
        wrong_way: &mut ww,
    };
    ep.check_out(&out).unwrap();
    ep.write(None, out);
    (r, t, tr, el, vr, vt, pr, ww)
}

fn one_step(p: EpisodeParams, travel: f64, vx: f64, event: u8) -> f64 {
    let mut ep = Episodes::new(p, 1, 1).unwrap();
    ep.update(&rows(&[travel], &[vx]), &[event]);
    results(&ep).0[0]
}

#[test]
fn progress_term_is_weighted_ds() {
    let p = EpisodeParams {
        progress: 1.5,
        ..plain()
    };
    assert_eq!(one_step(p, 0.2, 2.0, 0), 0.2 * 1.5);
    assert_eq!(one_step(p, -0.2, -2.0, 0), -0.2 * 1.5);
}

#[test]
fn stall_penalty_applies_below_the_stall_speed_only() {
    let p = EpisodeParams {
        stall_penalty: 2.0,
        ..plain()
    };
    // stall_ds = 0.5 m/s * 0.1 s = 0.05 m per step
    assert_eq!(one_step(p, 0.04, 0.4, 0), 0.04 - 2.0 * 0.1);
    assert_eq!(one_step(p, 0.06, 0.6, 0), 0.06);
    assert_eq!(one_step(plain(), 0.0, 0.0, 0), 0.0); // off when 0
}

#[test]
fn time_penalty_is_per_second() {
    let p = EpisodeParams {
        time_penalty: 3.0,
        ..plain()
    };
    assert_eq!(one_step(p, 0.1, 1.0, 0), 0.1 - 3.0 * 0.1);
}

#[test]
fn collision_penalty_on_wall_or_vehicle_contact_not_on_a_lap() {
    let p = EpisodeParams {
        collision_penalty: 7.0,
        ..plain()
    };
    assert_eq!(one_step(p, 0.1, 1.0, EVENT_WALL), 0.1 - 7.0);
    assert_eq!(one_step(p, 0.1, 1.0, EVENT_VEHICLE), 0.1 - 7.0);
    assert_eq!(one_step(p, 0.1, 1.0, super::super::world::EVENT_LAP), 0.1);
}

#[test]
fn collision_terminates_only_when_it_ends_episodes() {
    for ends in [false, true] {
        let p = EpisodeParams {
            collision_ends_episode: ends,
            ..plain()
        };
        let mut ep = Episodes::new(p, 1, 1).unwrap();
        ep.update(&rows(&[0.1], &[1.0]), &[EVENT_WALL]);
        let (_, t, _, _, _, vt, _, _) = results(&ep);
        assert_eq!((t[0], vt[0]), (ends, ends));
        ep.update(&rows(&[0.2], &[1.0]), &[0]); // contact gone: no longer terminated
        assert!(!results(&ep).1[0]);
    }
}

/// Drive forward to 3 m, then back by `step` per step at `vx`: the wrong-way flag per step.
fn backwards(p: EpisodeParams, vx: f64) -> (Vec<i8>, Vec<f64>, Vec<bool>) {
    let mut ep = Episodes::new(p, 1, 1).unwrap();
    let (mut flags, mut rewards, mut ends) = (vec![], vec![], vec![]);
    let mut travel = 0.0;
    for i in 0..60 {
        travel += if i < 30 { 0.1 } else { -0.1 };
        ep.update(&rows(&[travel], &[if i < 30 { 1.0 } else { vx }]), &[0]);
        let (r, t, _, _, _, _, _, w) = results(&ep);
        flags.push(w[0]);
        rewards.push(r[0]);
        ends.push(t[0]);
    }
    (flags, rewards, ends)
}

#[test]
fn wrong_way_after_the_distance_nose_first_or_reversing() {
    let (flags, _, ends) = backwards(plain(), -1.0);
    // best 3.0 at step 29; behind by more than 0.95 m from step 39 on (1.0 m)
    assert!(flags[..39].iter().all(|&f| f == 0), "{flags:?}");
    assert!(flags[39..].iter().all(|&f| f == -1), "{flags:?}");
    assert!(!ends.iter().any(|&t| t));
    let (flags, _, _) = backwards(plain(), 1.0); // a U-turn: nose first
    assert!(flags[39..].iter().all(|&f| f == 1));
}

#[test]
fn wrong_way_penalty_and_termination() {
    let p = EpisodeParams {
        wrong_way_penalty: 2.0,
        wrong_way_ends_episode: true,
        ..plain()
    };
    let (flags, rewards, ends) = backwards(p, -1.0);
    for i in 30..60 {
        let wrong = flags[i] != 0;
        assert_eq!(ends[i], wrong);
        let want = if wrong { -2.0 } else { 0.0 };
        assert!(
            (rewards[i] - (-0.1 + want)).abs() < 1e-9,
            "step {i}: {}",
            rewards[i]
        );
    }
}

#[test]
fn standing_still_behind_the_best_is_not_wrong_way() {
    let mut ep = Episodes::new(plain(), 1, 1).unwrap();
    ep.update(&rows(&[3.0], &[1.0]), &[0]);
    ep.update(&rows(&[1.0], &[-1.0]), &[0]); // 2 m back in one step: wrong way
    assert_eq!(results(&ep).7[0], -1);
    ep.update(&rows(&[1.0], &[0.0]), &[0]); // then still: ds = 0 is not backwards
    assert_eq!(results(&ep).7[0], 0);
}

#[test]
fn truncation_at_max_steps_unless_terminated() {
    let p = EpisodeParams {
        max_steps: Some(3),
        collision_ends_episode: true,
        ..plain()
    };
    let mut ep = Episodes::new(p, 2, 1).unwrap();
    for i in 1..=3 {
        let ev = if i == 3 { [EVENT_WALL, 0] } else { [0, 0] };
        ep.update(&rows(&[0.1 * i as f64, 0.1 * i as f64], &[1.0, 1.0]), &ev);
        let (_, t, tr, el, ..) = results(&ep);
        assert_eq!(el, vec![i, i]);
        assert_eq!(tr, vec![false, i == 3]); // env 0 terminated at step 3: not truncated
        assert_eq!(t, vec![i == 3, false]);
    }
    let none = Episodes::new(plain(), 1, 1).unwrap();
    assert!(!results(&none).2[0]);
}

#[test]
fn env_reward_sums_vehicles_and_any_vehicle_terminates() {
    let p = EpisodeParams {
        collision_penalty: 5.0,
        collision_ends_episode: true,
        ..plain()
    };
    let mut ep = Episodes::new(p, 2, 2).unwrap();
    ep.update(
        &rows(&[0.1, 0.2, 0.3, 0.4], &[1.0; 4]),
        &[0, EVENT_VEHICLE, 0, 0],
    );
    let (r, t, _, _, vr, vt, pr, _) = results(&ep);
    assert_eq!(vr, vec![0.1, 0.2 - 5.0, 0.3, 0.4]);
    assert_eq!(r, vec![0.1 + (0.2 - 5.0), 0.3 + 0.4]);
    assert_eq!(t, vec![true, false]);
    assert_eq!(vt, vec![false, true, false, false]);
    assert_eq!(pr, vec![0.1, 0.2, 0.3, 0.4]);
}

#[test]
fn reset_restarts_only_the_masked_envs() {
    let p = EpisodeParams {
        max_steps: Some(10),
        ..plain()
    };
    let mut ep = Episodes::new(p, 2, 1).unwrap();
    ep.update(&rows(&[3.0, 3.0], &[1.0, 1.0]), &[0, 0]);
    ep.update(&rows(&[1.0, 1.0], &[-1.0, -1.0]), &[0, 0]);
    ep.reset(&[true, false]);
    let (r, _, _, el, _, _, pr, ww) = results(&ep);
    assert_eq!((r[0], el[0], pr[0], ww[0]), (0.0, 0, 0.0, 0));
    assert_eq!((el[1], pr[1], ww[1]), (2, 1.0, -1));
    assert_eq!(*ep.car(0, 0), CarEpisode::default());
    // After the reset the travel restarts at 0: the next step's ds is measured from 0.
    ep.update(&rows(&[0.25, 1.5], &[1.0, 1.0]), &[0, 0]);
    let (r, _, _, el, ..) = results(&ep);
    assert_eq!((r[0], el[0]), (0.25, 1));
    assert_eq!((r[1], el[1]), (0.5, 3));
}

#[test]
fn masked_write_touches_only_the_masked_rows() {
    let mut ep = Episodes::new(plain(), 2, 1).unwrap();
    ep.update(&rows(&[0.5, 0.5], &[1.0, 1.0]), &[0, 0]);
    let (mut r, mut t, mut tr, mut el) = (vec![9.0; 2], vec![true; 2], vec![true; 2], vec![9; 2]);
    let (mut vr, mut vt, mut pr, mut ww) = (vec![9.0; 2], vec![true; 2], vec![9.0; 2], vec![9; 2]);
    ep.write(
        Some(&[false, true]),
        EpisodeOut {
            reward: &mut r,
            terminated: &mut t,
            truncated: &mut tr,
            elapsed: &mut el,
            vehicle_reward: &mut vr,
            vehicle_terminated: &mut vt,
            progress: &mut pr,
            wrong_way: &mut ww,
        },
    );
    assert_eq!(
        (r, el, pr, ww),
        (vec![9.0, 0.5], vec![9, 1], vec![9.0, 0.5], vec![9, 0])
    );
}

#[test]
fn bad_params_are_refused() {
    for p in [
        EpisodeParams { dt: 0.0, ..plain() },
        EpisodeParams {
            stall_penalty: -1.0,
            ..plain()
        },
        EpisodeParams {
            progress: f64::NAN,
            ..plain()
        },
        EpisodeParams {
            wrong_way_distance: f64::INFINITY,
            ..plain()
        },
        EpisodeParams {
            max_steps: Some(0),
            ..plain()
        },
    ] {
        assert!(Episodes::new(p, 1, 1).is_err(), "{p:?}");
    }
    assert!(EpisodeParams::default().validate().is_ok());
}

/// The simulator runs the episode step inside its step for any env count, and restarts
/// an env's episode with its reset: progress since reset follows the cars' travel.
#[test]
fn simulator_steps_and_resets_episodes() {
    use super::super::shapes::stadium_track;
    use super::super::{SimParams, Simulator, Track};
    use std::sync::Arc;

    let (walls, centre) = stadium_track(6.0, 3.0, 2.0);
    let track =
        Arc::new(Track::new(&walls, &centre, crate::track::params::DEFAULT_WALL_HEIGHT_M).unwrap());
    let mut params = SimParams::default();
    params.lidar.num_beams = 11;
    for envs in [1usize, 3] {
        let mut sim = Simulator::new(vec![track.clone()], envs, 2, params.clone(), 0).unwrap();
        let p = EpisodeParams {
            max_steps: Some(50),
            ..EpisodeParams::default()
        };
        sim.set_episode(p).unwrap();
        let poses: Vec<f64> = (0..envs)
            .flat_map(|_| [0.0, -3.0, 0.0, -1.0, -3.0, 0.0])
            .collect();
        sim.reset(&vec![true; envs], &poses).unwrap();
        let n = envs * 2;
        let mut state = vec![0.0; n * STATE_SIZE];
        let mut events = vec![0u8; n];
        let acts: Vec<f64> = (0..n).flat_map(|_| [0.0, 2.0]).collect();
        for _ in 0..20 {
            sim.step(&acts, 5, None, &mut state, &mut events).unwrap();
        }
        let ep = sim.episodes().unwrap();
        for k in 0..n {
            let c = ep.car(k / 2, k % 2);
            let travel = state[k * STATE_SIZE + TRAVEL];
            assert!(travel > 0.5, "{travel}");
            assert!((c.progress - travel).abs() < 1e-9 && c.prev_travel == travel);
        }
        assert_eq!(ep.elapsed(0), 20);
        let mut mask = vec![false; envs];
        mask[0] = true;
        sim.reset(&mask, &poses).unwrap();
        let ep = sim.episodes().unwrap();
        assert_eq!((ep.elapsed(0), ep.car(0, 1).progress), (0, 0.0));
        if envs > 1 {
            assert_eq!(ep.elapsed(1), 20);
        }
        // Changing the parameters keeps the state.
        sim.set_episode(EpisodeParams::default()).unwrap();
        assert_eq!(
            sim.episodes().unwrap().elapsed(envs - 1),
            if envs > 1 { 20 } else { 0 }
        );
    }
}
