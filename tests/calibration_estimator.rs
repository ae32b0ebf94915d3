//! The calibration estimator: what it learns of a gyro's gain on a synthetic sensor, what it cannot see
//! and says so, what it refuses. The recovery against the number and spread of turns and the noise, and
//! the figures on real recordings: docs/calibration.md.

use quatprop::frontend::{Calibration, CalibrationEstimator};
use quatprop::{Error, GyroSample, Quat, Real, Vec3};

mod support;
use support::Xorshift;

/// Gaussian white noise of standard deviation `sigma` on each axis.
fn noise(g: &mut Xorshift, sigma: f64) -> Vec3<f64> {
    Vec3::new(g.gaussian(), g.gaussian(), g.gaussian()) * sigma
}

/// The true gain correction `I − G` of the test sensor: scale errors of +0.8 %, −0.6 %, +1.0 % and
/// cross-axis terms of ±0.2–0.5° (rad), the sizes of a datasheet's ±1 % and ±0.5°.
const TRUTH: [[f64; 3]; 3] = [
    [1.0 / 1.008, 0.0061, -0.0035],
    [-0.0044, 1.0 / 0.994, 0.0087],
    [0.0026, -0.0070, 1.0 / 1.010],
];

fn mat_vec(m: &[[f64; 3]; 3], v: Vec3<f64>) -> Vec3<f64> {
    Vec3::new(
        m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
        m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
        m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z,
    )
}

/// `m⁻¹` by cofactors.
fn inverse(m: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let c = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
    };
    let det = m[0][0] * c(0, 0) + m[0][1] * c(0, 1) + m[0][2] * c(0, 2);
    core::array::from_fn(|i| core::array::from_fn(|j| c(j, i) / det))
}

/// A body tumbling about an axis that sweeps it (incommensurate frequencies), seen by a gyro whose
/// readings are `TRUTH⁻¹ · ω` plus white noise and an accelerometer reading gravity (m/s², at each
/// sample's end) plus white noise; `update` gets each (reading, acceleration).
fn tumble(
    seconds: f64,
    dt: f64,
    gyro_noise: f64,
    accel_noise: f64,
    mut update: impl FnMut(Vec3<f64>, Vec3<f64>),
) {
    let to_reading = inverse(&TRUTH);
    let mut g = Xorshift::with_seed(11);
    let mut q = Quat::<f64>::IDENTITY;
    let n = (seconds / dt).round() as usize;
    for k in 0..n {
        let t = k as f64 * dt;
        let w = Vec3::new(
            1.3 * t.cos(),
            1.1 * (0.37 * t).sin(),
            0.8 * (0.21 * t + 1.0).cos(),
        );
        q = (q * Quat::from_rotation_vector(w * dt))
            .normalized()
            .unwrap();
        let gravity = q.conjugate().rotate(Vec3::new(0.0, 0.0, 9.81));
        let reading = mat_vec(&to_reading, w) + noise(&mut g, gyro_noise);
        update(reading, gravity + noise(&mut g, accel_noise));
    }
}

/// The estimator of these tests at `dt`: the datasheet's priors (±1 % on each scale, ±0.5° = 0.0087 rad on
/// each cross-axis term) and a motion noise of 0.01° per sample.
fn datasheet_estimator<T: Real>(dt: f64) -> CalibrationEstimator<T> {
    CalibrationEstimator::with_motion_noise(dt, 0.01, 0.0087, 0.01_f64.to_radians()).unwrap()
}

/// Feeds `est` a [`tumble`] of `seconds` with a consumer MEMS gyro's noise (0.005 rad/s per sample) and
/// 0.05 m/s² on the accelerometer, each reading rounded to the estimator's precision.
fn tumble_into<T: Real>(est: &mut CalibrationEstimator<T>, seconds: f64, dt: f64) {
    tumble(seconds, dt, 0.005, 0.05, |r, a| {
        est.update(Vec3::from_f64(r), Vec3::from_f64(a), T::from_f64(dt))
            .unwrap()
    });
}

fn largest_error<T: Real>(est: &CalibrationEstimator<T>) -> f64 {
    let g = est.gain();
    (0..9)
        .map(|k| (g[k / 3][k % 3].to_f64() - TRUTH[k / 3][k % 3]).abs())
        .fold(0.0, f64::max)
}

#[test]
fn it_learns_every_term_of_the_gain_of_a_tumbling_sensor() {
    // 100 Hz, 5 min, a consumer MEMS gyro's noise (0.005 rad/s per sample at 100 Hz: 0.03 °/√s) and
    // 0.05 m/s² on the accelerometer; the priors are the datasheet's ±1 % and ±0.5°.
    let dt = 0.01;
    let mut est = datasheet_estimator::<f64>(dt);
    let start = largest_error(&est);
    tumble_into(&mut est, 300.0, dt);
    let end = largest_error(&est);
    println!("largest gain error: {start:.2e} at the start, {end:.2e} after 5 min");
    println!("std dev: {:?}", est.gain_std_dev());
    assert!(start > 8.0e-3);
    assert!(end < 4.0e-4, "{end}");
    // Every term has been seen: each σ is below a tenth of its prior.
    let seen = est.gain_observed();
    assert!(seen.iter().flatten().all(|&s| s > 0.9), "{seen:?}");
    // The error lies within the filter's own 3σ on every term.
    let sd = est.gain_std_dev();
    for k in 0..9 {
        let (i, j) = (k / 3, k % 3);
        assert!(
            (est.gain()[i][j] - TRUTH[i][j]).abs() < 3.0 * sd[i][j],
            "term ({i}, {j})"
        );
    }
}

#[test]
fn it_learns_the_gain_in_f32_as_in_f64() {
    let dt = 0.01;
    // The same tumble (the noise's seed is fixed) into each.
    let mut e32 = datasheet_estimator::<f32>(dt);
    let mut e64 = datasheet_estimator::<f64>(dt);
    tumble_into(&mut e32, 300.0, dt);
    tumble_into(&mut e64, 300.0, dt);
    let (g32, g64) = (e32.gain(), e64.gain());
    let apart = (0..9)
        .map(|k| (f64::from(g32[k / 3][k % 3]) - g64[k / 3][k % 3]).abs())
        .fold(0.0, f64::max);
    println!(
        "f32 against f64: {apart:.2e}; f32's error {:.2e}",
        largest_error(&e32)
    );
    assert!(apart < 1.0e-4, "{apart}");
    assert!(largest_error(&e32) < 4.0e-4);
}

#[test]
fn a_turn_about_the_vertical_shows_only_the_terms_it_can() {
    // Turning about the vertical body z only: a reading of ω_z shows as G·(0, 0, ω_z) = ω_z·(G_xz, G_yz,
    // G_zz). The first two tilt the attitude (learned); G_zz turns it about the vertical, which the
    // accelerometer cannot see: it stays exactly at its prior. The x and y columns see only the small
    // readings the misalignment puts on those axes (0.4 % and 0.3 % of the rate), always in proportion to
    // the z reading: the filter cannot tell them from the z column's terms, and learns only what this
    // motion shows, a correction that takes the reading to a turn about z alone.
    let dt = 0.01;
    let mut est = datasheet_estimator::<f64>(dt);
    let mut q = Quat::<f64>::IDENTITY;
    for k in 0..30_000 {
        let w = Vec3::new(0.0, 0.0, 1.0 + 0.5 * (k as f64 * dt * 0.3).sin());
        q = (q * Quat::from_rotation_vector(w * dt))
            .normalized()
            .unwrap();
        let g = q.conjugate().rotate(Vec3::new(0.0, 0.0, 9.81));
        est.update(Vec3::new(0.004 * w.z, -0.003 * w.z, w.z * 1.01), g, dt)
            .unwrap();
    }
    let seen = est.gain_observed();
    let g = est.gain();
    println!("observed: {seen:?}\ngain: {g:?}");
    for (i, j) in [(0, 2), (1, 2)] {
        assert!(seen[i][j] > 0.9, "({i}, {j}) {}", seen[i][j]);
    }
    assert!((g[0][2] + 0.004).abs() < 2.0e-4 && (g[1][2] - 0.003).abs() < 2.0e-4);
    assert_eq!(seen[2][2], 0.0);
    assert!((g[2][2] - 1.0).abs() < 1.0e-12, "{}", g[2][2]);
    for (i, j) in [(0, 0), (0, 1), (1, 0), (1, 1), (2, 0), (2, 1)] {
        assert!(seen[i][j] < 0.1, "({i}, {j}) {}", seen[i][j]);
    }
    let reading = [0.004, -0.003, 1.01];
    for row in &g[..2] {
        let corrected: f64 = row.iter().zip(reading).map(|(m, r)| m * r).sum();
        assert!(corrected.abs() < 2.0e-4, "{corrected}");
    }
}

#[test]
fn its_correction_is_the_calibration_it_hands_over() {
    let dt = 0.01;
    let mut est = datasheet_estimator::<f32>(dt);
    tumble_into(&mut est, 60.0, dt);
    let cal = est.calibration();
    let again = Calibration::new(cal.offset(), cal.sensitivity(), cal.misalignment()).unwrap();
    for s in [Vec3::new(1.0_f32, -2.0, 0.5), Vec3::new(-3.0, 0.25, 7.0)] {
        let s = GyroSample::new(s);
        assert_eq!(est.correct(s), cal.apply(s));
        assert_eq!(est.correct(s), again.apply(s));
    }
    // At rest the residual bias restarts at zero; the gain stays.
    let gain = est.gain();
    est.at_rest();
    assert_eq!(est.bias(), Vec3::ZERO);
    assert_eq!(est.gain(), gain);
    assert!(est.bias_std_dev().x < 0.031_f32.to_radians());
}

#[test]
fn bad_input_is_refused_and_leaves_it_unchanged() {
    let dt = 0.01;
    let mut est = CalibrationEstimator::<f32>::new(dt, 0.01, 0.0087).unwrap();
    tumble_into(&mut est, 5.0, dt);
    let before = est;
    let (w, a) = (Vec3::new(0.1_f32, 0.2, 0.3), Vec3::new(0.0_f32, 0.0, 9.81));
    assert_eq!(
        est.update(Vec3::new(f32::NAN, 0.0, 0.0), a, 0.01),
        Err(Error::NonFiniteRate)
    );
    assert_eq!(
        est.update(w, Vec3::new(0.0, f32::INFINITY, 0.0), 0.01),
        Err(Error::NonFiniteAux)
    );
    assert_eq!(est.update(w, a, f32::NAN), Err(Error::NonFiniteStep));
    assert_eq!(est.update(w, a, 0.0), Err(Error::NonPositiveStep));
    assert_eq!(est.update(w, a, -0.01), Err(Error::NonPositiveStep));
    // A rate so large that the filter's arithmetic overflows.
    assert_eq!(
        est.update(Vec3::new(3.0e38, 3.0e38, 3.0e38), a, 0.01),
        Err(Error::NonFiniteResult)
    );
    assert_eq!(est, before);
    // Parameters.
    type C = CalibrationEstimator<f32>;
    assert_eq!(C::new(0.0, 0.01, 0.01).err(), Some(Error::NonPositiveStep));
    assert_eq!(
        C::new(f64::NAN, 0.01, 0.01).err(),
        Some(Error::NonFiniteStep)
    );
    assert_eq!(
        C::new(0.01, -0.01, 0.01).err(),
        Some(Error::InvalidEstimator)
    );
    assert_eq!(
        C::new(0.01, 0.01, 0.06).err(),
        Some(Error::InvalidEstimator)
    );
    assert_eq!(
        C::new(0.01, f64::NAN, 0.01).err(),
        Some(Error::InvalidEstimator)
    );
    assert_eq!(
        C::with_motion_noise(0.01, 0.01, 0.01, 0.0).err(),
        Some(Error::InvalidEstimator)
    );
    assert_eq!(
        C::with_motion_noise(0.01, 0.01, 0.01, f64::INFINITY).err(),
        Some(Error::InvalidEstimator)
    );
    // A noise whose variance per sample overflows f32.
    assert_eq!(
        C::with_motion_noise(1.0e-30, 0.01, 0.01, 1.0e10).err(),
        Some(Error::InvalidEstimator)
    );
}
