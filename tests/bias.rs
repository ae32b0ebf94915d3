//! The bias estimator: what it learns and refuses, how fast it follows a drift and a step at rest, what it
//! keeps (slow turns, the end of a motion), what the accelerometer and the temperature add. The figures beside Fusion's, VQF's and on real recordings: docs/bias.md.

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
    let mut est = BiasEstimator::<f64>::new(1.0, 1.0e-3, gate)
        .unwrap()
        .with_drift(0.0)
        .and_then(|e| e.with_rest_drift(0.0))
        .unwrap();
    let sample = |extra: Vec3<f64>, noise: &mut Noise| {
        GyroSample::new(bias + extra + Vec3::new(noise.next(), noise.next(), noise.next()) * sigma)
    };
    // Still for 20 s, a constant bias (drift 0 at rest and unseen): the estimate's error is the noise averaged over the
    // still time, σ/√N.
    for _ in 0..20_000 {
        est.update(sample(Vec3::ZERO, &mut noise)).unwrap();
    }
    let err = (est.bias() - bias).norm();
    let expected = sigma * (3.0_f64 / 20_000.0).sqrt(); // rms of the 3-vector error
    assert!(err < 4.0 * expected, "{err:e} vs {expected:e}");
    // Its variance says so: σ²/N per axis within 30 % (the scatter at rest is learned from 20 windows).
    let v = est.variance();
    assert!(
        (v.x / (sigma * sigma / 20_000.0) - 1.0).abs() < 0.3,
        "{v:?}"
    );
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
    // A rotation slower than the gate (0.04 rad/s) after motion is not a bias: the estimate stays.
    for _ in 0..30_000 {
        est.update(sample(Vec3::new(0.04, 0.0, 0.0), &mut noise))
            .unwrap();
    }
    assert_eq!(est.bias(), learned);
    assert_eq!(
        BiasEstimator::<f32>::from_samples(0, 1e-3, 0.05),
        Err(Error::InvalidEstimator)
    );
    assert_eq!(
        BiasEstimator::<f32>::from_samples(10, 1e-3, f32::NAN),
        Err(Error::InvalidEstimator)
    );
    assert_eq!(
        BiasEstimator::<f32>::from_samples(10, 1e-3, -1.0),
        Err(Error::InvalidEstimator)
    );
}

/// The window is a duration: the same second at 1 kHz and at 400 Hz; a window beyond 2³¹ − 1 samples is
/// refused.
#[test]
fn bias_window_is_given_in_seconds() {
    let at_1k = BiasEstimator::<f32>::new(1.0, 1.0e-3, 0.05).unwrap();
    assert_eq!(
        at_1k,
        BiasEstimator::from_samples(1000, 1.0e-3, 0.05).unwrap()
    );
    let at_400 = BiasEstimator::<f32>::new(1.0, 2.5e-3, 0.05).unwrap();
    assert_eq!(
        at_400,
        BiasEstimator::from_samples(400, 2.5e-3, 0.05).unwrap()
    );
    // Learned after 400 still samples at 400 Hz, not before.
    let mut e = at_400;
    let b = Vec3::new(0.01_f32, -0.02, 0.005);
    for _ in 0..399 {
        e.update(GyroSample::new(b)).unwrap();
    }
    assert!(!e.is_learned());
    assert_eq!(e.variance().x, f32::MAX);
    e.update(GyroSample::new(b)).unwrap();
    assert!(e.is_learned());
    assert!((e.bias() - b).norm() < 1e-8, "{:?}", e.bias());
    let bad = Err(Error::InvalidEstimator);
    assert_eq!(BiasEstimator::<f32>::new(0.0, 1.0e-3, 0.05), bad);
    assert_eq!(BiasEstimator::<f32>::new(1.0, f64::NAN, 0.05), bad);
    assert_eq!(BiasEstimator::<f32>::new(1.0e-4, 1.0e-3, 0.05), bad); // under one sample
    assert_eq!(BiasEstimator::<f32>::new(3.0e6, 1.0e-3, 0.05), bad); // 3e9 samples
    assert_eq!(BiasEstimator::<f32>::from_samples(1 << 31, 1e-3, 0.05), bad);
    assert_eq!(BiasEstimator::<f32>::from_samples(10, 0.0, 0.05), bad);
    assert!(BiasEstimator::<f32>::from_samples(i32::MAX as u32, 1e-3, 0.05).is_ok());
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

/// f32 samples at 1 kHz of `rate(t) + bias(t)` plus white noise of σ = 0.1 °/s per axis.
fn moving(
    seconds: f64,
    rate: impl Fn(f64) -> Vec3<f64>,
    bias: impl Fn(f64) -> Vec3<f64>,
    noise: &mut Noise,
) -> Vec<GyroSample<f32>> {
    still(seconds, move |t| rate(t) + bias(t), noise)
}

/// A raised-cosine ramp from 0 at `start` to 1 after `ramp` seconds.
fn ramp(t: f64, start: f64, ramp: f64) -> f64 {
    let x = ((t - start) / ramp).clamp(0.0, 1.0);
    0.5 * (1.0 - (core::f64::consts::PI * x).cos())
}

fn default_estimator() -> BiasEstimator<f32> {
    BiasEstimator::<f32>::new(1.0, 1e-3, (3.0 * DEG) as f32).unwrap()
}

/// A bias step of (+0.3, 0, −0.2) °/s at rest, 20.37 s in, inside the window from 20 to 21 s: that window
/// is two flat levels with a block between, and the next window confirms the new level: followed at 22 s,
/// 1.63 s after the step. A step at a window's boundary (30 s) is confirmed by the two windows after it.
#[test]
fn a_bias_step_at_rest_is_followed_within_two_windows() {
    let b0 = Vec3::new(0.6, -0.4, 0.25) * DEG;
    let step = Vec3::new(0.3, 0.0, -0.2) * DEG;
    let truth = move |t: f64| {
        if t < 20.37 {
            b0
        } else if t <= 30.0 {
            b0 + step
        } else {
            b0
        }
    };
    let samples = still(40.0, truth, &mut Noise(3));
    let tol = 0.05 * DEG;
    let mut est = default_estimator();
    let trace = run(&mut est, &samples);
    let start = settled(&trace, truth, (0.0, 20.37), tol).unwrap();
    assert!((start - 1.0).abs() < 1e-9, "{start}"); // the first window sets it
    let followed = settled(&trace, truth, (20.37, 30.0), tol).unwrap();
    assert!(followed > 1.62 && followed < 1.64, "{followed}");
    let back = settled(&trace, truth, (30.0, 40.0), tol).unwrap();
    assert!(back > 1.99 && back < 2.01, "{back}");
    let residual = (est.bias().to_f64() - truth(40.0)).norm();
    assert!(residual < 0.01 * DEG, "{}", residual / DEG);
}

/// One window that disagrees (a 0.5 °/s drift held for one second) is held as a candidate and dropped when
/// the next window agrees with the estimate again: nothing of it is learned.
#[test]
fn a_single_odd_window_is_never_learned() {
    let b0 = Vec3::new(0.6, -0.4, 0.25) * DEG;
    let odd = Vec3::new(0.0, 0.5, 0.0) * DEG;
    let truth = move |t: f64| if t > 10.0 && t <= 11.0 { b0 + odd } else { b0 };
    let samples = still(20.0, truth, &mut Noise(5));
    let mut est = default_estimator();
    run(&mut est, &samples[..10_000]);
    let before = est.bias();
    run(&mut est, &samples[10_000..11_000]);
    assert_eq!(est.bias(), before); // held as a candidate, not learned
    run(&mut est, &samples[11_000..12_000]);
    assert!((est.bias().to_f64() - before.to_f64()).norm() < 0.01 * DEG);
    run(&mut est, &samples[12_000..]);
    assert!((est.bias().to_f64() - b0).norm() < 0.01 * DEG);
}

/// A slow turn from rest about one axis (0.5, 1 and 2 °/s, below the 3 °/s gate, reached over 0.5 s and
/// held for 60 s) is not a bias step: the ramp is not two flat levels. Next to nothing of the turn is taken
/// for bias (the drift would admit it only after minutes).
#[test]
fn a_slow_turn_with_a_ramp_is_kept() {
    let b0 = Vec3::new(0.6, -0.4, 0.25) * DEG;
    for dps in [0.5, 1.0, 2.0] {
        let rate = move |t: f64| Vec3::new(0.0, 0.0, dps * DEG * ramp(t, 20.2, 0.5));
        let samples = moving(80.0, rate, |_| b0, &mut Noise(11));
        let mut est = default_estimator();
        let trace = run(&mut est, &samples);
        // The angle taken for bias during the turn (the estimate's move since the turn began), against
        // the turn's angle.
        let at_start = trace[20_000].1.z;
        let lost: f64 = trace
            .iter()
            .filter(|(t, _)| *t > 20.0)
            .map(|(_, b)| (b.z - at_start) * 1e-3)
            .sum();
        let turned = dps * DEG * 59.55;
        assert!(
            lost.abs() < 0.001 * turned,
            "{dps} °/s: {:.2} % taken",
            100.0 * lost / turned
        );
    }
}

/// The failure: a short hand motion whose rate ramps up below the gate as a window closes, goes
/// above the gate, and ramps down below it into the next windows. Without a bias change, no wrong bias is
/// adopted (every window after the motion agrees with the estimate, or starts no step).
#[test]
fn a_short_motion_with_ramps_leaves_no_wrong_bias() {
    let b0 = Vec3::new(0.6, -0.4, 0.25) * DEG;
    for (seed, at) in [(1, 10.85), (2, 10.9), (3, 10.8), (4, 11.95)] {
        // 0 → 10 °/s about a tilted axis over 0.6 s, back to 0 over 0.6 s.
        let axis = Vec3::new(0.3, 0.5, 0.8) * (1.0 / (0.98_f64).sqrt());
        let rate = move |t: f64| axis * (10.0 * DEG * (ramp(t, at, 0.6) - ramp(t, at + 0.6, 0.6)));
        let samples = moving(20.0, rate, |_| b0, &mut Noise(seed));
        let mut est = default_estimator();
        let trace = run(&mut est, &samples);
        let worst = trace
            .iter()
            .filter(|(t, _)| *t > 5.0)
            .map(|(_, b)| (*b - b0).norm())
            .fold(0.0, f64::max);
        assert!(
            worst < 0.01 * DEG,
            "motion at {at} s: wrong by {:.4} °/s",
            worst / DEG
        );
    }
}

/// A bias drifting at rest (0.002 °/s per second, a warming sensor) is tracked: within 0.02 °/s after the
/// first minute.
#[test]
fn a_drifting_bias_is_tracked_at_rest() {
    let b0 = Vec3::new(0.6, -0.4, 0.25) * DEG;
    let slope = Vec3::new(0.002, -0.001, 0.0) * DEG;
    let truth = move |t: f64| b0 + slope * t;
    let samples = still(120.0, truth, &mut Noise(13));
    let mut est = default_estimator();
    let trace = run(&mut est, &samples);
    let worst = trace
        .iter()
        .filter(|(t, _)| *t > 60.0)
        .map(|(t, b)| (*b - truth(*t)).norm())
        .fold(0.0, f64::max);
    assert!(worst < 0.02 * DEG, "{:.4} °/s", worst / DEG);
}

/// With the accelerometer, a turn about a horizontal axis that starts as abruptly as a bias step (within
/// one block) is seen: the acceleration's block means move with gravity, the window is not flat, and the
/// turn is kept. Gyro alone, the same turn is taken for a step at rest.
#[test]
fn the_accelerometer_tells_an_abrupt_horizontal_turn_from_a_step() {
    let b0 = Vec3::new(0.6, -0.4, 0.25) * DEG;
    let w = 0.5 * DEG; // about x, from 20.5 s
    let samples = moving(
        40.0,
        |t| Vec3::new(if t > 20.5 { w } else { 0.0 }, 0.0, 0.0),
        |_| b0,
        &mut Noise(17),
    );
    let mut noise = Noise(19);
    let mut with = default_estimator();
    let mut without = default_estimator();
    for (k, s) in samples.iter().enumerate() {
        let t = (k + 1) as f64 * 1e-3;
        let angle = if t > 20.5 { w * (t - 20.5) } else { 0.0 };
        // Gravity in body axes as the body turns about x, plus 0.02 m/s² noise.
        let g = Vec3::new(0.0, 9.81 * angle.sin(), 9.81 * angle.cos())
            + Vec3::new(noise.next(), noise.next(), noise.next()) * 0.02;
        let aux = Aux {
            accel: Some(Vec3::<f32>::from_f64(g)),
            temperature: None,
        };
        with.update_with(*s, aux).unwrap();
        without.update(*s).unwrap();
    }
    assert!(
        (with.bias().to_f64() - b0).norm() < 0.01 * DEG,
        "{:?}",
        with.bias()
    );
    assert!(
        (without.bias().to_f64().x - b0.x - w).abs() < 0.02 * DEG,
        "{:?}",
        without.bias()
    );
}

/// With the accelerometer gate, a window whose acceleration moves by more than the gate is not still,
/// however still the rates look; without it, the same window is learned.
#[test]
fn the_accelerometer_gate_keeps_a_moving_window_out() {
    let b = Vec3::new(0.0078125_f32, -0.015625, 0.00390625);
    let mut with = BiasEstimator::<f32>::from_samples(100, 1e-3, 0.05)
        .unwrap()
        .with_accel_gate(0.5)
        .unwrap();
    let mut without = BiasEstimator::<f32>::from_samples(100, 1e-3, 0.05).unwrap();
    for k in 0..1000 {
        // A 1 m/s² shake at 5 Hz on x.
        let a = Vec3::new((k as f32 * 0.0314).sin(), 0.0, 9.81);
        let aux = Aux {
            accel: Some(a),
            temperature: None,
        };
        with.update_with(GyroSample::new(b), aux).unwrap();
        without.update(GyroSample::new(b)).unwrap();
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

/// Given the sensor's noise, the scatter at rest is known from the first window: a first window that
/// holds a ramp is not flat and is not learned (learning it from its own scatter, the estimator would).
#[test]
fn the_noise_model_judges_the_first_window() {
    use quatprop::noise::GyroNoise;
    let b0 = Vec3::new(0.6, -0.4, 0.25) * DEG;
    // 0.1 °/s per sample at 1 kHz: N = 0.1 °/s · √1 ms.
    let noise = GyroNoise::<f32>::new((0.1 * DEG * 1e-3_f64.sqrt()) as f32, 0.0).unwrap();
    let rate = |t: f64| Vec3::new(0.0, 2.0 * DEG * ramp(t, 0.2, 0.6), 0.0);
    let samples = moving(1.0, rate, |_| b0, &mut Noise(23));
    let mut given = default_estimator().with_noise(&noise).unwrap();
    run(&mut given, &samples);
    assert!(!given.is_learned());
    let mut learned = default_estimator();
    run(&mut learned, &samples);
    assert!(learned.is_learned());
    // At rest, the first window is flat and learned either way.
    let samples = still(1.0, |_| b0, &mut Noise(29));
    let mut given = default_estimator().with_noise(&noise).unwrap();
    run(&mut given, &samples);
    assert!((given.bias().to_f64() - b0).norm() < 0.02 * DEG);
    let zero = GyroNoise::<f32>::new(0.0, 0.0).unwrap();
    assert_eq!(
        default_estimator().with_noise(&zero),
        Err(Error::InvalidEstimator)
    );
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
fn bad_parameters_are_refused() {
    let bad = Err(Error::InvalidEstimator);
    let e = BiasEstimator::<f32>::from_samples(10, 1e-3, 0.05).unwrap();
    assert_eq!(e.with_drift(-1.0), bad);
    assert_eq!(e.with_drift(f32::NAN), bad);
    assert_eq!(e.with_drift(f32::INFINITY), bad);
    assert!(e.with_drift(0.0).is_ok());
    assert_eq!(e.with_rest_drift(-1.0), bad);
    assert_eq!(e.with_rest_drift(f32::NAN), bad);
    assert!(e.with_rest_drift(0.0).is_ok());
    assert_eq!(e.with_accel_gate(f32::INFINITY), bad);
    assert_eq!(e.with_temperature_model(-1.0), bad);
    assert_eq!(e.with_initial(Vec3::ZERO, 0.0), bad);
    assert_eq!(
        e.with_initial(Vec3::new(f32::NAN, 0.0, 0.0), 1e-3),
        Err(Error::NonFiniteRate)
    );
    let i = e.with_initial(Vec3::new(0.01, 0.0, 0.0), 1e-3).unwrap();
    assert!(i.is_learned());
    assert!((i.variance().x / 1e-6 - 1.0).abs() < 1e-6);
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

/// A first still window quieter than the sensor (its block scatter a sixth of the truth, as one draw in a
/// hundred gives): the scatter at rest learned from it alone would fail every later window's flatness
/// test, and nothing would be learned again. The later windows are tested against the F bound of a scatter
/// learned from so few windows, pass, and teach it better: every window after the first is learned.
#[test]
fn a_quiet_first_window_does_not_lock_the_estimator_out() {
    let b0 = Vec3::new(0.6, -0.4, 0.25) * DEG;
    let mut noise = Noise(31);
    let sigma = 0.1 * DEG;
    let samples: Vec<GyroSample<f32>> = (0..30_000)
        .map(|k| {
            let s = if k < 1000 { sigma * 0.4 } else { sigma };
            let n = Vec3::new(noise.next(), noise.next(), noise.next()) * s;
            GyroSample::new(Vec3::<f32>::from_f64(b0 + n))
        })
        .collect();
    let mut est = default_estimator();
    let mut learned = Vec::new();
    for (k, s) in samples.iter().enumerate() {
        est.update(*s).unwrap();
        if (k + 1) % 1000 == 0 {
            learned.push(est.last_window().map(|w| w.0));
        }
    }
    // The number of windows taken counts up by one at every window's end.
    let counts: Vec<u32> = learned.iter().map(|c| c.unwrap_or(0)).collect();
    assert_eq!(counts, (1..=30).collect::<Vec<u32>>(), "{counts:?}");
}

/// Found by the fuzz target's checks (three cases, each a library bug): a window's acceleration gate is
/// referenced to the window's own first acceleration, never one a sample in motion left before it; a
/// window that is not a multiple of 8 samples sums the accelerations of its 8 blocks only (past them, a
/// ramp looked perfectly flat); a drift whose square overflows is refused, and the growth saturates.
#[test]
fn fuzz_findings_on_the_accelerometer_and_the_drift() {
    let aux = |x: f32| Aux {
        accel: Some(Vec3::new(x, 0.0, 9.81)),
        temperature: None,
    };
    // Window of 4, accel gate 0.5: a moving sample with accel x = 5, a still one without accel, then
    // three still ones with x = 0: a still window, learned.
    let mut e = BiasEstimator::<f32>::from_samples(4, 1e-3, 0.05)
        .unwrap()
        .with_accel_gate(0.5)
        .unwrap();
    e.update_with(GyroSample::new(Vec3::new(1.0, 0.0, 0.0)), aux(5.0))
        .unwrap();
    e.update(GyroSample::new(Vec3::ZERO)).unwrap();
    for _ in 0..3 {
        e.update_with(GyroSample::new(Vec3::ZERO), aux(0.0))
            .unwrap();
    }
    assert!(e.is_learned());
    // Windows of 12 and 15 samples (blocks of 1): 20 windows at rest, then one whose acceleration ramps
    // by 0.5 m/s² per sample: not flat, not learned (as with 16).
    for window in [12_u32, 15, 16] {
        let mut e = BiasEstimator::<f64>::from_samples(window, 1e-3, 0.05).unwrap();
        let mut noise = Noise(41);
        let n = |noise: &mut Noise| Vec3::new(noise.next(), noise.next(), noise.next()) * 1e-4;
        // One sample: the gyro's noise alone (the body does not turn), the accelerometer reading `accel`.
        let update = |e: &mut BiasEstimator<f64>, noise: &mut Noise, accel: Vec3<f64>| {
            let aux = Aux {
                accel: Some(accel),
                ..Aux::NONE
            };
            e.update_with(GyroSample::new(n(noise)), aux).unwrap();
        };
        for _ in 0..20 * window {
            let a = Vec3::new(0.0, 0.0, 9.81) + n(&mut noise) * 100.0;
            update(&mut e, &mut noise, a);
        }
        let learned = e.last_window().unwrap().0;
        for k in 0..window {
            update(&mut e, &mut noise, Vec3::new(0.5 * k as f64, 0.0, 9.81));
        }
        assert_eq!(e.last_window().unwrap().0, learned, "window {window}");
    }
    // A drift whose square overflows is refused; a huge one that is not saturates the variance.
    let e = BiasEstimator::<f32>::from_samples(8, 1e-3, 0.05).unwrap();
    assert_eq!(e.with_drift(1e30), Err(Error::InvalidEstimator));
    assert_eq!(e.with_rest_drift(1e30), Err(Error::InvalidEstimator));
    let mut e = e
        .with_drift(1e19)
        .and_then(|e| e.with_initial(Vec3::ZERO, 1e-3))
        .unwrap();
    for _ in 0..1000 {
        e.update(GyroSample::new(Vec3::new(1.0, 0.0, 0.0))).unwrap();
    }
    assert!(e.variance().is_finite(), "{:?}", e.variance());
}

#[test]
fn the_motion_bias_refuses_an_acceleration_that_overflows_its_filter() {
    use quatprop::frontend::MotionBias;
    let mut m = MotionBias::<f32>::new(0.01).unwrap();
    for _ in 0..10 {
        m.update(Vec3::new(0.1, 0.0, 0.0), Vec3::new(0.0, 0.0, 9.81), 0.01)
            .unwrap();
    }
    // Finite, but the low-pass filter's start-up sum of two of them overflows f32: the first is taken,
    // the second refused.
    let huge = Vec3::new(3.0e38_f32, 3.0e38, 3.0e38);
    assert_eq!(m.update(Vec3::ZERO, huge, 0.01), Ok(()));
    let before = m;
    assert_eq!(
        m.update(Vec3::ZERO, huge, 0.01),
        Err(Error::NonFiniteResult)
    );
    assert_eq!(m, before);
    m.update(Vec3::new(0.1, 0.0, 0.0), Vec3::new(0.0, 0.0, 9.81), 0.01)
        .unwrap();
    assert!(m.bias().is_finite());
}
