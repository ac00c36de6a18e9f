use proptest::prelude::*;

use super::*;

const SCALES: ObservationScales = ObservationScales {
    position_scale: 20.0,
    horizon: 10.0,
    range_max: 30.0,
    max_speed: 7.0,
    max_steer: 0.5,
};

fn all_fields() -> ObservationNormaliser {
    ObservationNormaliser::new(OdometryField::ALL.to_vec(), SCALES).unwrap()
}

/// A state row with the given odometry values (x, y, yaw, vx, vy, yaw_rate, steer, speed).
fn state(odo: [f64; 8]) -> [f64; STATE_SIZE] {
    let mut s = [0.0; STATE_SIZE];
    s[..8].copy_from_slice(&odo);
    s
}

fn row(n: &ObservationNormaliser, odo: [f64; 8], start: [f64; 3]) -> Vec<f32> {
    let mut out = vec![f32::MAX; n.columns().len()];
    n.odometry_row(&state(odo), &start, &mut out);
    out
}

#[test]
fn fields_are_named_as_the_state_columns_and_parse_back() {
    for f in OdometryField::ALL {
        assert_eq!(OdometryField::parse(f.name()).unwrap(), f);
        assert_eq!(STATE_FIELDS[f.state_column()], f.name());
    }
    let err = OdometryField::parse("progress_s").unwrap_err().to_string();
    assert!(
        err.contains("progress_s") && err.contains("yaw_rate"),
        "{err}"
    );
}

#[test]
fn columns_name_scale_and_bound_each_output() {
    let n = all_fields();
    let names: Vec<&str> = n.columns().iter().map(|c| c.name).collect();
    assert_eq!(
        names,
        ["x", "y", "yaw_sin", "yaw_cos", "vx", "vy", "yaw_rate", "steer", "speed"]
    );
    let scales: Vec<f64> = n.columns().iter().map(|c| c.scale).collect();
    assert_eq!(
        scales,
        [
            20.0,
            20.0,
            1.0,
            1.0,
            7.0,
            7.0,
            2.0 * std::f64::consts::PI,
            0.5,
            7.0
        ]
    );
    assert!(n.columns()[..2].iter().all(|c| c.bound == f64::INFINITY));
    assert!(n.columns()[2..].iter().all(|c| c.bound == 1.0));
}

#[test]
fn position_is_in_the_start_frame_and_heading_relative_to_the_start() {
    let n = all_fields();
    let half_pi = std::f64::consts::FRAC_PI_2;
    // Start facing +y at (1, 2); the car 2 m ahead and 1 m to its left, turned 90° left.
    let out = row(
        &n,
        [0.0, 4.0, 2.0 * half_pi, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1.0, 2.0, half_pi],
    );
    assert!((out[0] - 0.1).abs() < 1e-7, "x {}", out[0]); // 2 m / 20
    assert!((out[1] - 0.05).abs() < 1e-7, "y {}", out[1]); // 1 m / 20
    assert!(
        (out[2] - 1.0).abs() < 1e-7 && out[3].abs() < 1e-7,
        "{out:?}"
    );
}

#[test]
fn velocities_and_steering_are_scaled_and_clipped() {
    let n = all_fields();
    let out = row(
        &n,
        [
            0.0,
            0.0,
            0.0,
            3.5,
            -14.0,
            std::f64::consts::PI,
            f64::NEG_INFINITY,
            f64::NAN,
        ],
        [0.0; 3],
    );
    assert_eq!(&out[4..8], &[0.5, -1.0, 0.5, -1.0]);
    assert!(out[8].is_nan(), "NaN stays NaN: {out:?}");
    // Position is not clipped.
    let far = row(&n, [1e6, -1e40, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0; 3]);
    assert_eq!(far[0], 5e4);
    assert_eq!(far[1], f32::NEG_INFINITY);
}

#[test]
fn scans_are_scaled_by_the_horizon_and_clipped_to_one() {
    let n = all_fields();
    let mut out = [0.0f32; 4];
    n.scan_row(&[5.0, 10.0, 25.0, f32::NAN], &mut out);
    assert_eq!(&out[..3], &[0.5, 1.0, 1.0]);
    assert!(out[3].is_nan());
    let far = ObservationNormaliser::new(
        vec![],
        ObservationScales {
            horizon: f64::INFINITY,
            ..SCALES
        },
    )
    .unwrap();
    assert_eq!(far.scan_scale(), (1.0f64 / 30.0) as f32);
}

#[test]
fn bad_scales_and_repeated_fields_are_config_errors() {
    for bad in [
        ObservationScales {
            position_scale: 0.0,
            ..SCALES
        },
        ObservationScales {
            horizon: f64::NAN,
            ..SCALES
        },
        ObservationScales {
            max_speed: f64::INFINITY,
            ..SCALES
        },
        ObservationScales {
            max_steer: -1.0,
            ..SCALES
        },
        ObservationScales {
            range_max: 0.0,
            ..SCALES
        },
    ] {
        let err = ObservationNormaliser::new(vec![], bad).unwrap_err();
        assert!(matches!(err, ArenaError::Config(_)), "{err}");
    }
    let err = ObservationNormaliser::new(vec![OdometryField::Vx, OdometryField::Vx], SCALES);
    assert!(matches!(err, Err(ArenaError::Config(_))));
}

#[test]
fn batch_lengths_are_checked() {
    let n = all_fields();
    let frames = Frames {
        envs: 2,
        vehicles: 1,
        frames: 1,
        env_mask: None,
    };
    let state = [0.0; 2 * STATE_SIZE];
    let mut out = [0.0f32; 2 * 9];
    assert!(n
        .write_odometry(&state, &[0.0; 6], &mut out, frames)
        .is_ok());
    assert!(n
        .write_odometry(&state, &[0.0; 3], &mut out, frames)
        .is_err());
    assert!(n
        .write_odometry(&state[1..], &[0.0; 6], &mut out, frames)
        .is_err());
    assert!(n
        .write_odometry(&state, &[0.0; 6], &mut out[1..], frames)
        .is_err());
    let short_mask = Frames {
        env_mask: Some(&[true]),
        ..frames
    };
    assert!(n
        .write_odometry(&state, &[0.0; 6], &mut out, short_mask)
        .is_err());
    assert!(n
        .write_scans(
            &[1.0; 6],
            3,
            &mut [0.0; 6],
            Frames {
                frames: 0,
                ..frames
            }
        )
        .is_err());
}

fn odometry_value() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => -50.0..50.0f64,
        1 => -1e12..1e12f64,
        1 => prop::sample::select(vec![f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0, -0.0]),
    ]
}

proptest! {
    #[test]
    fn bounded_columns_stay_within_one_and_the_pose_rotates_back(
        odo in prop::array::uniform8(-50.0..50.0f64),
        start in (-50.0..50.0f64, -50.0..50.0f64, -3.2..3.2f64),
    ) {
        let n = all_fields();
        let start = [start.0, start.1, start.2];
        let out = row(&n, odo, start);
        prop_assert!(out[2..].iter().all(|v| (-1.0..=1.0).contains(v)), "{:?}", out);
        let (x, y) = (out[0] as f64 * 20.0, out[1] as f64 * 20.0);
        let (c, s) = (start[2].cos(), start[2].sin());
        prop_assert!((start[0] + x * c - y * s - odo[0]).abs() < 1e-4);
        prop_assert!((start[1] + x * s + y * c - odo[1]).abs() < 1e-4);
        let (sn, cs) = (out[2] as f64, out[3] as f64);
        prop_assert!((sn * sn + cs * cs - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_batch_writes_the_newest_frame_of_the_masked_envs_only(
        envs in 1usize..4,
        vehicles in 1usize..3,
        frames in 1usize..4,
        mask in prop::collection::vec(any::<bool>(), 4),
        masked in any::<bool>(),
        values in prop::collection::vec(odometry_value(), 4 * 3 * STATE_SIZE),
    ) {
        let n = ObservationNormaliser::new(
            vec![OdometryField::Steer, OdometryField::Yaw, OdometryField::X], SCALES).unwrap();
        let (rows, k) = (envs * vehicles, n.columns().len());
        let state = &values[..rows * STATE_SIZE];
        let starts: Vec<f64> = values[..rows * 3].iter().map(|v| v.clamp(-3.0, 3.0)).collect();
        let mask = &mask[..envs];
        let layout = Frames { envs, vehicles, frames, env_mask: masked.then_some(mask) };
        let mut out = vec![-7.0f32; rows * frames * k];
        n.write_odometry(state, &starts, &mut out, layout).unwrap();
        for r in 0..rows {
            let written = !masked || mask[r / vehicles];
            let frame = |f: usize| &out[(r * frames + f) * k..(r * frames + f + 1) * k];
            for f in 0..frames - 1 {
                prop_assert!(frame(f).iter().all(|&v| v == -7.0));
            }
            let mut want = vec![-7.0f32; k];
            if written {
                let st = &starts[3 * r..3 * r + 3];
                n.odometry_row(&state[r * STATE_SIZE..], &[st[0], st[1], st[2]], &mut want);
            }
            let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            prop_assert_eq!(bits(frame(frames - 1)), bits(&want));
        }
    }
}
