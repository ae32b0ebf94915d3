//! The bias estimator: what it learns and refuses, how fast it follows a change, what the accelerometer
//! and the temperature add. The figures beside Fusion's, VQF's and on real recordings: docs/bias.md.

use quatprop::frontend::{Aux, BiasEstimator};
use quatprop::{Error, GyroSample, Vec3};

/// White noise by a small generator (sum of uniforms), deterministic.
struct Noise(u64);
impl Noise {
    fn next(&mut self) -> f64 {
        let mut acc = 0.0;
        for _ in 0..12 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            acc += (self.0 >> 11) as f64 / (1u64 << 53) as f64;
        }
        acc - 6.0 // unit variance
    }
}

#[test]
fn bias_estimator_learns_still_bias_and_nothing_else() {
    let gate = 0.05; // rad/s
    let bias = Vec3::new(0.012, -0.007, 0.003);
    let sigma = 0.002; // rad/s per sample
    let mut noise = Noise(7);
    let mut est = BiasEstimator::<f64>::new(1.0, 1.0e-3, gate).unwrap();
    let sample = |extra: Vec3<f64>, noise: &mut Noise| {
        GyroSample::new(bias + extra + Vec3::new(noise.next(), noise.next(), noise.next()) * sigma)
    };
    // Still for 20 s: the estimate's error is the noise averaged over the still time, σ/√N.
    for _ in 0..20_000 {
        est.update(sample(Vec3::ZERO, &mut noise)).unwrap();
    }
    let err = (est.bias() - bias).norm();
    let expected = sigma * (3.0_f64 / 20_000.0).sqrt(); // rms of the 3-vector error
    assert!(err < 4.0 * expected, "{err:e} vs {expected:e}");
    // A real rotation faster than the gate (0.06 rad/s about x) for 10 s: never learned.
    let learned = est.bias();
    for _ in 0..10_000 {
        est.update(sample(Vec3::new(0.06, 0.0, 0.0), &mut noise))
            .unwrap();
    }
    assert_eq!(est.bias(), learned);
    // Saturated samples, however still, are never learned from.
    for _ in 0..5_000 {
        let mut s = sample(Vec3::new(0.01, 0.0, 0.0), &mut noise);
        s.saturated = true;
        est.update(s).unwrap();
    }
    assert_eq!(est.bias(), learned);
    // A NaN is refused and changes nothing.
    let before = est;
    assert_eq!(
        est.update(GyroSample::new(Vec3::new(f64::NAN, 0.0, 0.0))),
        Err(Error::NonFiniteRate)
    );
    assert_eq!(est, before);
    // A rotation slower than the gate (0.04 rad/s) is indistinguishable from bias: it is learned.
    for _ in 0..5_000 {
        est.update(sample(Vec3::new(0.04, 0.0, 0.0), &mut noise))
            .unwrap();
    }
    assert!(est.bias().x > learned.x + 0.002, "{:?}", est.bias());
    assert_eq!(
        BiasEstimator::<f32>::from_samples(0, 0.05, 64),
        Err(Error::InvalidEstimator)
    );
    assert_eq!(
        BiasEstimator::<f32>::from_samples(10, f32::NAN, 64),
        Err(Error::InvalidEstimator)
    );
    assert_eq!(
        BiasEstimator::<f32>::from_samples(10, -1.0, 64),
        Err(Error::InvalidEstimator)
    );
}

/// The window is a duration: the same second at 1 kHz and at 400 Hz; a window beyond 2³¹ − 1 samples (which
/// learned the bias with the wrong sign) is refused.
#[test]
fn bias_window_is_given_in_seconds() {
    let at_1k = BiasEstimator::<f32>::new(1.0, 1.0e-3, 0.05).unwrap();
    assert_eq!(at_1k, BiasEstimator::from_samples(1000, 0.05, 64).unwrap());
    let at_400 = BiasEstimator::<f32>::with_memory(1.0, 2.5e-3, 0.05, 8).unwrap();
    assert_eq!(at_400, BiasEstimator::from_samples(400, 0.05, 8).unwrap());
    // Learned after 400 still samples at 400 Hz, not before.
    let mut e = at_400;
    let b = Vec3::new(0.01_f32, -0.02, 0.005);
    for _ in 0..399 {
        e.update(GyroSample::new(b)).unwrap();
    }
    assert!(!e.is_learned());
    e.update(GyroSample::new(b)).unwrap();
    assert!(e.is_learned());
    let bad = Err(Error::InvalidEstimator);
    assert_eq!(BiasEstimator::<f32>::new(0.0, 1.0e-3, 0.05), bad);
    assert_eq!(BiasEstimator::<f32>::new(1.0, f64::NAN, 0.05), bad);
    assert_eq!(BiasEstimator::<f32>::new(1.0e-4, 1.0e-3, 0.05), bad); // under one sample
    assert_eq!(BiasEstimator::<f32>::new(3.0e6, 1.0e-3, 0.05), bad); // 3e9 samples
    assert_eq!(BiasEstimator::<f32>::from_samples(1 << 31, 0.05, 64), bad);
    assert!(BiasEstimator::<f32>::from_samples(i32::MAX as u32, 0.05, 64).is_ok());
}

const DEG: f64 = core::f64::consts::PI / 180.0;

/// f32 samples at 1 kHz: `bias(t)` plus white noise of σ = 0.1 °/s per axis (a MEMS gyro's at 1 kHz).
fn still(seconds: f64, bias: impl Fn(f64) -> Vec3<f64>, noise: &mut Noise) -> Vec<GyroSample<f32>> {
    let sigma = 0.1 * DEG;
    (0..(seconds * 1000.0) as usize)
        .map(|k| {
            let n = Vec3::new(noise.next(), noise.next(), noise.next()) * sigma;
            GyroSample::new(Vec3::<f32>::from_f64(bias((k + 1) as f64 * 1e-3) + n))
        })
        .collect()
}

/// The time (s) from which `|b̂ − b| < tol` until `until`, counted from `from` (s), or None.
fn settled(
    estimates: &[(f64, Vec3<f64>)],
    truth: impl Fn(f64) -> Vec3<f64>,
    (from, until): (f64, f64),
    tol: f64,
) -> Option<f64> {
    let mut since = None;
    for &(t, b) in estimates {
        if t < from || t >= until {
            continue;
        }
        if (b - truth(t)).norm() < tol {
            since.get_or_insert(t);
        } else {
            since = None;
        }
    }
    since.map(|t| t - from)
}

fn run(est: &mut BiasEstimator<f32>, samples: &[GyroSample<f32>]) -> Vec<(f64, Vec3<f64>)> {
    samples
        .iter()
        .enumerate()
        .map(|(k, s)| {
            est.update(*s).unwrap();
            ((k + 1) as f64 * 1e-3, est.bias().to_f64())
        })
        .collect()
}

/// A bias step of (+0.3, 0, −0.2) °/s at rest, 20.37 s in: the window that straddles it is a candidate,
/// the next replaces it (they disagree by 37 % of the step), the third confirms: followed 2.63 s after the
/// step. With changes switched off the running mean takes tens of windows.
#[test]
fn a_bias_step_at_rest_is_followed_within_three_windows() {
    let b0 = Vec3::new(0.6, -0.4, 0.25) * DEG;
    let step = Vec3::new(0.3, 0.0, -0.2) * DEG;
    let at = 20.37;
    let truth = move |t: f64| if t < at { b0 } else { b0 + step };
    let samples = still(40.0, truth, &mut Noise(3));
    let tol = 0.05 * DEG;

    let mut est = BiasEstimator::<f32>::new(1.0, 1e-3, (3.0 * DEG) as f32).unwrap();
    let trace = run(&mut est, &samples);
    let start = settled(&trace, truth, (0.0, at), tol).unwrap();
    assert!((start - 1.0).abs() < 1e-9, "{start}"); // the first window sets it
    let followed = settled(&trace, truth, (at, 40.0), tol).unwrap();
    assert!(followed > 2.62 && followed < 2.64, "{followed}");
    let residual = (est.bias().to_f64() - truth(40.0)).norm();
    assert!(residual < 0.01 * DEG, "{}", residual / DEG);

    let mut slow = BiasEstimator::<f32>::new(1.0, 1e-3, (3.0 * DEG) as f32)
        .unwrap()
        .with_change(f32::MAX)
        .unwrap();
    let trace = run(&mut slow, &samples);
    let (t, b) = trace[((at + 5.0) * 1000.0) as usize];
    let unlearned = (b - truth(t)).norm();
    assert!(unlearned > 0.25 * DEG, "{}", unlearned / DEG); // of |step| = 0.36 °/s
}

/// One window that disagrees (a 0.5 °/s drift held for one second) is held as a candidate and dropped when
/// the next window agrees with the estimate again: nothing of it is learned.
#[test]
fn a_single_odd_window_is_never_learned() {
    let b0 = Vec3::new(0.6, -0.4, 0.25) * DEG;
    let odd = Vec3::new(0.0, 0.5, 0.0) * DEG;
    let truth = move |t: f64| if t > 10.0 && t <= 11.0 { b0 + odd } else { b0 };
    let samples = still(20.0, truth, &mut Noise(5));
    let mut est = BiasEstimator::<f32>::new(1.0, 1e-3, (3.0 * DEG) as f32).unwrap();
    run(&mut est, &samples[..10_000]);
    let before = est.bias();
    run(&mut est, &samples[10_000..11_000]);
    assert_eq!(est.bias(), before); // held as a candidate, not learned
    run(&mut est, &samples[11_000..12_000]);
    // The next window agrees with the estimate: the candidate is dropped, the window refines the mean.
    assert!((est.bias().to_f64() - before.to_f64()).norm() < 0.01 * DEG);
    run(&mut est, &samples[12_000..]);
    assert!((est.bias().to_f64() - b0).norm() < 0.01 * DEG);
}

/// With the accelerometer, a window whose acceleration moves by more than the gate is not still, however
/// still the rates look; without it, the same window is learned.
#[test]
fn the_accelerometer_gate_keeps_a_moving_window_out() {
    let b = Vec3::new(0.0078125_f32, -0.015625, 0.00390625); // binary fractions: sums are exact
    let mut with = BiasEstimator::<f32>::from_samples(100, 0.05, 64)
        .unwrap()
        .with_accel_gate(0.5)
        .unwrap();
    let mut without = BiasEstimator::<f32>::from_samples(100, 0.05, 64).unwrap();
    for k in 0..1000 {
        // A 1 m/s² shake at 5 Hz on x (a hand-held sensor that rotates slowly).
        let a = Vec3::new((k as f32 * 0.0314).sin(), 0.0, 9.81);
        let aux = Aux {
            accel: Some(a),
            temperature: None,
        };
        with.update_with(GyroSample::new(b), aux).unwrap();
        without.update_with(GyroSample::new(b), aux).unwrap();
    }
    assert!(!with.is_learned());
    assert_eq!(without.bias(), b);
    // Still acceleration: learned after one window (the first still sample may close the shaking one).
    let aux = Aux {
        accel: Some(Vec3::new(0.0, 0.0, 9.81)),
        temperature: None,
    };
    for _ in 0..101 {
        with.update_with(GyroSample::new(b), aux).unwrap();
    }
    assert_eq!(with.bias(), b);
    // A NaN acceleration or temperature is refused and changes nothing.
    let before = with;
    let bad = Aux {
        accel: Some(Vec3::new(f32::NAN, 0.0, 0.0)),
        temperature: None,
    };
    assert_eq!(
        with.update_with(GyroSample::new(b), bad),
        Err(Error::NonFiniteAux)
    );
    let bad = Aux {
        accel: None,
        temperature: Some(f32::INFINITY),
    };
    assert_eq!(
        with.update_with(GyroSample::new(b), bad),
        Err(Error::NonFiniteAux)
    );
    assert_eq!(with, before);
}

/// A bias linear in temperature (0.005 °/s per °C per axis, the ICM-42688-P datasheet's zero-rate
/// variation), learned over rests at rising temperatures: the fitted slope is within 2 % of the truth, and
/// the bias subtracted at a temperature 10 °C above the last rest is right within 0.005 °/s.
#[test]
fn the_temperature_model_learns_the_slope_at_rest_and_applies_it_beyond() {
    let slope = Vec3::new(0.005, -0.005, 0.005) * DEG;
    let b0 = Vec3::new(0.6, -0.4, 0.25) * DEG;
    let temperature = |t: f64| 25.0 + 20.0 * (1.0 - (-t / 180.0).exp());
    let truth = move |t: f64| b0 + slope * (temperature(t) - 25.0);
    let samples = still(300.0, truth, &mut Noise(9));
    let mut est = BiasEstimator::<f32>::new(1.0, 1e-3, (3.0 * DEG) as f32)
        .unwrap()
        .with_temperature_model(1.0)
        .unwrap();
    for (k, s) in samples.iter().enumerate() {
        let aux = Aux {
            accel: None,
            temperature: Some(temperature((k + 1) as f64 * 1e-3) as f32),
        };
        est.update_with(*s, aux).unwrap();
    }
    let fitted = est.temperature_slope().unwrap().to_f64();
    for (f, s) in [
        (fitted.x, slope.x),
        (fitted.y, slope.y),
        (fitted.z, slope.z),
    ] {
        assert!((f / s - 1.0).abs() < 0.02, "{} vs {}", f / DEG, s / DEG);
    }
    let hotter = temperature(300.0) + 10.0;
    let err = (est.bias_at(hotter as f32).to_f64() - (b0 + slope * (hotter - 25.0))).norm();
    assert!(err < 0.005 * DEG, "{}", err / DEG);
    // Without the model the estimate is the rest bias at the rests' mean temperature.
    assert!(BiasEstimator::<f32>::new(1.0, 1e-3, 0.05)
        .unwrap()
        .temperature_slope()
        .is_none());
}

#[test]
fn memory_beyond_i32_and_bad_gates_are_refused() {
    let bad = Err(Error::InvalidEstimator);
    assert_eq!(BiasEstimator::<f32>::from_samples(10, 0.05, 1 << 31), bad);
    assert!(BiasEstimator::<f32>::from_samples(10, 0.05, i32::MAX as u32).is_ok());
    let e = BiasEstimator::<f32>::from_samples(10, 0.05, 64).unwrap();
    assert_eq!(e.with_change(0.0), bad);
    assert_eq!(e.with_change(f32::NAN), bad);
    assert_eq!(e.with_accel_gate(f32::INFINITY), bad);
    assert_eq!(e.with_temperature_model(-1.0), bad);
}

/// The residual bias in motion from the accelerometer (VQF's motion bias estimation): a body turning on all
/// axes under gravity, a residual bias of (0.3, −0.2, 0.1) °/s on rates sampled at 100 Hz. The
/// accelerometer is gravity in body axes along the true attitude, no noise.
#[test]
fn the_motion_bias_is_learned_from_gravity_while_the_body_turns() {
    use quatprop::frontend::MotionBias;
    use quatprop::{input::Hold, scheme::ExpMap, stabilize::Normalize, Propagator, Quat};
    let dt = 0.01;
    let b = Vec3::new(0.3, -0.2, 0.1) * DEG;
    let rate = |t: f64| Vec3::new(0.3 * (0.7 * t).sin(), 0.4 * (0.5 * t).cos(), 0.2);
    let mut truth = Propagator::new(Quat::IDENTITY, ExpMap, Hold::new(), Normalize).unwrap();
    let mut m = MotionBias::<f64>::new(dt).unwrap();
    let mut after = Vec::new();
    for k in 0..30_000 {
        let w = rate((k + 1) as f64 * dt);
        truth.push(GyroSample::new(w), dt).unwrap();
        let g = truth
            .attitude()
            .conjugate()
            .rotate(Vec3::new(0.0, 0.0, 9.81));
        m.update(w + b, g, dt).unwrap();
        if k % 6000 == 5999 {
            after.push((m.bias() - b).norm() / DEG);
        }
    }
    // Every minute closer; after 5 min within 0.01 °/s on every axis together.
    assert!(after.windows(2).all(|p| p[1] <= p[0] * 1.5), "{after:?}");
    assert!(after[4] < 0.01, "{after:?}");
    // A NaN acceleration is refused and changes nothing; a zero one is no reading.
    let before = m;
    assert_eq!(
        m.update(b, Vec3::new(f64::NAN, 0.0, 9.81), dt),
        Err(Error::NonFiniteAux)
    );
    assert_eq!(
        m.update(b, Vec3::new(0.0, 0.0, 9.81), 0.0),
        Err(Error::NonPositiveStep)
    );
    assert_eq!(m, before);
    // At rest the rest estimator's figure holds: the residual restarts at zero.
    m.at_rest();
    assert_eq!(m.bias(), Vec3::ZERO);
    assert_eq!(MotionBias::<f32>::new(0.0), Err(Error::NonPositiveStep));
}
