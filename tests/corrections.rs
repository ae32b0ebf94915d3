//! An estimator's corrections: rotations in the body and the reference frame, and the bias correction
//! that moves the input model's kept samples with the front end's bias; refusals leave everything as it
//! was; the run-time `Configured` propagator matches the static one bit for bit.

use quatprop::accumulate::{FloatFloat, Kahan};
use quatprop::config::{AccumulatorKind, Config, InputKind};
use quatprop::frontend::{BiasEstimator, FixedBias};
use quatprop::input::{History, Linear};
use quatprop::scheme::ExpMap;
use quatprop::stabilize::FirstOrder;
use quatprop::{Error, GyroSample, Propagator, Quat, Vec3};

fn rate(t: f64) -> Vec3<f64> {
    Vec3::new((3.0 * t).sin(), 0.5 * (1.7 * t).cos(), 0.8)
}

#[test]
fn rotations_are_the_quaternion_products() {
    let q0 = Quat::from_rotation_vector(Vec3::new(0.3, -0.2, 1.1));
    for d in [
        Vec3::new(1e-9, -2e-9, 0.0),
        Vec3::new(0.01, 0.02, -0.03),
        Vec3::new(2.0, -1.0, 3.0),
    ] {
        let e = Quat::from_rotation_vector(d);
        let mut p = Propagator::recommended(q0).unwrap();
        p.rotate_body(d).unwrap();
        assert!(p.attitude().angle_to(q0 * e) < 4e-16, "{d:?}");
        let mut p = Propagator::recommended(q0).unwrap();
        p.rotate_reference(d).unwrap();
        assert!(p.attitude().angle_to(e * q0) < 4e-16, "{d:?}");
        // In f32, within rounding.
        let q32 = Quat::<f32>::from_f64(q0);
        let d32 = Vec3::<f32>::from_f64(d);
        let mut p = Propagator::recommended(q32).unwrap();
        let start = p.attitude().to_f64();
        p.rotate_body(d32).unwrap();
        let expected = start * Quat::from_rotation_vector(d32.to_f64());
        let e = p.attitude().to_f64().angle_to(expected);
        // The increment q ⊗ (e − 1) is as large as |e − 1| ≤ |d|: its rounding scales with it.
        assert!(
            e < 4.0 * f64::from(f32::EPSILON) * (1.0 + d.norm()),
            "{d:?}: {e:e}"
        );
    }
}

/// The correction goes through the accumulator: a Kahan or float-float low part stays in the sum.
#[test]
fn corrections_keep_what_the_accumulator_carries() {
    let base = Propagator::new(Quat::<f32>::IDENTITY, ExpMap, History::new(), FirstOrder).unwrap();
    let mut kahan = base.with_accumulator(Kahan::new());
    let mut ff = base.with_accumulator(FloatFloat::new());
    let mut reference = Propagator::recommended(Quat::<f64>::IDENTITY).unwrap();
    let h = 1.0e-3_f32;
    for k in 0..=20_000 {
        let w = Vec3::from_f64(rate(f64::from(k) * 1e-3));
        kahan.push(GyroSample::new(w), h).unwrap();
        ff.push(GyroSample::new(w), h).unwrap();
        reference
            .push(GyroSample::new(w.to_f64()), f64::from(h))
            .unwrap();
        if k % 1000 == 500 {
            let d = Vec3::new(1e-3, -2e-3, 5e-4);
            kahan.rotate_body(d).unwrap();
            ff.rotate_body(d).unwrap();
            reference.rotate_body(d.to_f64()).unwrap();
        }
    }
    let low = ff.accumulator().low();
    let ff_total = ff.attitude().to_f64() + low.to_f64();
    let e_ff = ff_total
        .normalized()
        .unwrap()
        .angle_to(reference.attitude());
    let e_kahan = kahan.attitude().to_f64().angle_to(reference.attitude());
    println!(
        "own error after 20 s with 20 corrections: Kahan {e_kahan:.2e}, float-float {e_ff:.2e}"
    );
    assert_ne!(low, Quat::ZERO);
    assert!(e_ff < 1e-9, "{e_ff}");
    assert!(e_kahan < 1e-6, "{e_kahan}");
}

/// A bias correction mid-run: the next steps equal those of a propagator whose kept samples were
/// corrected with the new bias all along; left uncorrected, the history integrates a jump.
#[test]
fn bias_correction_moves_the_kept_samples() {
    let h = 1.0e-3;
    let b_old = Vec3::new(0.01, -0.02, 0.005);
    let delta = Vec3::new(0.003, 0.002, -0.004);
    let raw = |k: u32| rate(f64::from(k) * h) + b_old + delta; // the true bias is b_old + delta
    let mut bias = FixedBias::new(b_old).unwrap();
    let mut corrected = Propagator::recommended(Quat::IDENTITY).unwrap();
    let mut uncorrected = corrected;
    for k in 0..100 {
        let s = bias.apply(GyroSample::new(raw(k)));
        corrected.push(s, h).unwrap();
        uncorrected.push(s, h).unwrap();
    }
    bias.correct_bias(delta).unwrap();
    assert_eq!(bias.bias(), b_old + delta);
    corrected.correct_bias(delta).unwrap();
    // The same history, built from samples with the new bias removed.
    let mut all_new = Propagator::recommended(Quat::IDENTITY).unwrap();
    for k in 97..100 {
        all_new
            .push(GyroSample::new(raw(k) - b_old - delta), h)
            .unwrap();
    }
    all_new.set_attitude(corrected.attitude()).unwrap();
    let (start_c, start_u) = (corrected.attitude(), uncorrected.attitude());
    for k in 100..103 {
        let s = bias.apply(GyroSample::new(raw(k)));
        corrected.push(s, h).unwrap();
        uncorrected.push(s, h).unwrap();
        all_new.push(s, h).unwrap();
    }
    let step = |a: Quat<f64>, b: Quat<f64>| (a.conjugate() * b).to_rotation_vector();
    let exact = step(start_c, all_new.attitude());
    let with = (step(start_c, corrected.attitude()) - exact).norm();
    let without = (step(start_u, uncorrected.attitude()) - exact).norm();
    println!(
        "three steps after the correction: {with:.2e} rad corrected, {without:.2e} left alone"
    );
    assert!(with < 1e-16, "{with}");
    // The jump of |delta| = 5.4e-3 rad/s through the cubic's weights: a few 1e-7 rad.
    assert!(without > 1e-7, "{without}");
}

#[test]
fn refusals_leave_everything_unchanged() {
    let mut p = Propagator::new(Quat::IDENTITY, ExpMap, Linear::new(), FirstOrder).unwrap();
    p.push(GyroSample::new(Vec3::new(1.0, 2.0, 3.0_f32)), 1e-3)
        .unwrap();
    let before = p;
    let nan = Vec3::new(0.0, f32::NAN, 0.0);
    assert_eq!(p.rotate_body(nan), Err(Error::NonFiniteRate));
    assert_eq!(
        p.rotate_reference(Vec3::new(f32::INFINITY, 0.0, 0.0)),
        Err(Error::NonFiniteRate)
    );
    assert_eq!(p.correct_bias(nan), Err(Error::NonFiniteRate));
    // f32 takes the step path's sine: half angles up to 8192 rad.
    assert_eq!(
        p.rotate_body(Vec3::new(0.0, 20000.0, 0.0)),
        Err(Error::StepAngleBeyondStability {
            step_angle: 20000.0,
            limit: 16384.0
        })
    );
    let mut q64 = Propagator::recommended(Quat::<f64>::IDENTITY).unwrap();
    q64.rotate_reference(Vec3::new(0.0, 20000.0, 0.0)).unwrap();
    let expected = Quat::from_rotation_vector(Vec3::new(0.0, 20000.0, 0.0));
    assert!(q64.attitude().angle_to(expected) < 1e-11);
    // A kept sample that would overflow.
    let mut big = Propagator::new(Quat::IDENTITY, ExpMap, Linear::new(), FirstOrder).unwrap();
    big.start(GyroSample::new(Vec3::new(-3e38, 0.0, 0.0_f32)))
        .unwrap();
    let kept = big;
    assert_eq!(
        big.correct_bias(Vec3::new(1e38, 0.0, 0.0)),
        Err(Error::NonFiniteRate)
    );
    assert_eq!(big, kept);
    assert_eq!(p, before);
    let mut fixed = FixedBias::new(Vec3::new(3e38_f32, 0.0, 0.0)).unwrap();
    let kept = fixed;
    assert_eq!(
        fixed.correct_bias(Vec3::new(3e38, 0.0, 0.0)),
        Err(Error::NonFiniteRate)
    );
    assert_eq!(fixed, kept);
    assert_eq!(fixed.correct_bias(nan), Err(Error::NonFiniteRate));
    assert_eq!(fixed, kept);

    let mut est = BiasEstimator::<f32>::from_samples(4, 1e-3, 0.1).unwrap();
    for _ in 0..8 {
        est.update(GyroSample::new(Vec3::new(0.01, 0.0, 0.0)))
            .unwrap();
    }
    let learned = est;
    assert_eq!(est.correct_bias(nan), Err(Error::NonFiniteRate));
    assert_eq!(est, learned);
    est.correct_bias(Vec3::new(0.002, 0.0, 0.0)).unwrap();
    assert_eq!(est.bias(), learned.bias() + Vec3::new(0.002, 0.0, 0.0));
}

#[test]
fn configured_matches_the_static_propagator_bit_for_bit() {
    let cfg = Config {
        input: InputKind::History,
        accumulator: AccumulatorKind::Kahan,
        ..Config::default()
    };
    let mut c = cfg.build::<f32>(Quat::IDENTITY).unwrap();
    let mut p = Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder)
        .unwrap()
        .with_accumulator(Kahan::new());
    for k in 0..50 {
        let s = GyroSample::new(Vec3::from_f64(rate(f64::from(k) * 1e-3)));
        c.push(s, 1e-3).unwrap();
        p.push(s, 1e-3).unwrap();
        if k % 7 == 3 {
            let d = Vec3::new(1e-3, 2e-3, -1e-3);
            c.rotate_body(d).unwrap();
            p.rotate_body(d).unwrap();
            c.rotate_reference(d).unwrap();
            p.rotate_reference(d).unwrap();
            c.correct_bias(d).unwrap();
            p.correct_bias(d).unwrap();
        }
    }
    assert_eq!(c.attitude(), p.attitude());
    assert_eq!(
        c.rotate_body(Vec3::new(f32::NAN, 0.0, 0.0)),
        Err(Error::NonFiniteRate)
    );
}
