//! The fixed-point propagator (`fixed::Q30Propagator`): its error measured the way f32's is, against an f64
//! propagator of the same configuration (ExpMap + History + FirstOrder) fed the same samples, and its
//! refusals.

use quatprop::fixed::Q30Propagator;
use quatprop::{Error, GyroSample, Propagator, Quat, Vec3};

/// ±2000 °/s on 16 bits: 16.4 counts per °/s.
const RAD_PER_COUNT: f64 = core::f64::consts::PI / 180.0 / 16.4;
const PERIOD: f64 = 1.0e-3;

/// Counts of a smooth motion with incommensurate frequencies (up to ~2.5 rad/s per axis).
fn counts(k: usize) -> [i16; 3] {
    let t = k as f64 * PERIOD;
    let w = [
        1.3 * (2.0 * t).sin() + 0.7 * (5.0_f64.sqrt() * t).cos(),
        -0.9 * (3.0_f64.sqrt() * 1.7 * t).sin() + 0.4,
        1.1 * (core::f64::consts::E * t).cos() - 0.6 * (0.37 * t).sin(),
    ];
    w.map(|x| (x / RAD_PER_COUNT).round() as i16)
}

fn rate(c: [i16; 3]) -> Vec3<f64> {
    Vec3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2])) * RAD_PER_COUNT
}

/// (fixed point's, f32's) largest error against the f64 propagator over `n` samples, checked every 1000.
fn own_errors(n: usize) -> (f64, f64) {
    let q0 = Quat::new(0.9, 0.1, -0.3, 0.2);
    let mut fixed = Q30Propagator::new(q0, RAD_PER_COUNT, PERIOD).unwrap();
    let mut f64p = Propagator::recommended(q0).unwrap();
    let mut f32p = Propagator::recommended(Quat::new(0.9_f32, 0.1, -0.3, 0.2)).unwrap();
    let (scale32, period32) = (RAD_PER_COUNT as f32, PERIOD as f32);
    let (mut e_fixed, mut e_f32) = (0.0_f64, 0.0_f64);
    for k in 0..n {
        let c = counts(k);
        fixed.push(c).unwrap();
        f64p.push(GyroSample::new(rate(c)), PERIOD).unwrap();
        let w32 = Vec3::new(f32::from(c[0]), f32::from(c[1]), f32::from(c[2])) * scale32;
        f32p.push(GyroSample::new(w32), period32).unwrap();
        if k % 1000 == 999 {
            let reference = f64p.attitude();
            e_fixed = e_fixed.max(fixed.attitude_f64().angle_to(reference));
            e_f32 = e_f32.max(f32p.attitude().to_f64().angle_to(reference));
        }
    }
    assert_eq!(fixed.steps(), f64p.steps());
    (e_fixed, e_f32)
}

#[test]
fn fixed_point_tracks_the_f64_step_far_closer_than_f32() {
    // 200 s at 1 kHz. The Q30 step rounds the attitude to 2⁻³⁰ once per step, with the half angle's and
    // the attitude's roundings carried to the next step: at most a random walk of √n · 2⁻³⁰ = 4.2e-7 rad
    // (what still repeats, the Q31 rounding of sinc − 1, is far below it on this motion). f32 rounds to
    // ε = 1.2e-7, 128 times coarser, and some of its roundings repeat from step to step
    // (docs/own_error.md).
    let n = 200_000;
    let (fixed, f32) = own_errors(n);
    println!("own error over 200 s at 1 kHz: Q30 {fixed:.2e} rad, f32 {f32:.2e} rad");
    assert!(fixed < (n as f64).sqrt() / (1u64 << 30) as f64, "{fixed:e}");
    assert!(fixed < f32 / 100.0, "Q30 {fixed:e}, f32 {f32:e}");
}

#[test]
fn the_history_start_and_steps_match_the_f64_history() {
    // From a cold start: the linear, the start-corrected quadratic and the cubic steps, each within a few
    // units of Q30 of the f64 propagator (the same formulas in exact arithmetic).
    let mut fixed = Q30Propagator::new(Quat::IDENTITY, RAD_PER_COUNT, PERIOD).unwrap();
    let mut f64p = Propagator::recommended(Quat::IDENTITY).unwrap();
    for k in 0..6 {
        let c = counts(37 * k);
        fixed.push(c).unwrap();
        f64p.push(GyroSample::new(rate(c)), PERIOD).unwrap();
        let d = fixed.attitude_f64().angle_to(f64p.attitude());
        assert!(d < 8.0 / (1u64 << 30) as f64, "sample {k}: {d:e}");
    }
    assert_eq!(fixed.steps(), 5);
}

#[test]
fn a_constant_rate_turns_exactly_as_the_rate_says() {
    // 1000 intervals at 1640 counts (100 °/s): 100° to a few units of Q30, not 1000 (the half angle's and
    // the increments' roundings are carried, so a steady rate's do not add up).
    let mut p = Q30Propagator::new(Quat::IDENTITY, RAD_PER_COUNT, PERIOD).unwrap();
    for _ in 0..1001 {
        p.push([0, 0, 1640]).unwrap();
    }
    let q = p.attitude_f64();
    let yaw = 2.0 * q.z.atan2(q.w);
    let want = 1000.0 * 1640.0 * RAD_PER_COUNT * PERIOD;
    assert!(
        (yaw - want).abs() < 8.0 / (1u64 << 30) as f64,
        "{:e}",
        yaw - want
    );
}

#[test]
fn bad_construction_is_refused_with_its_reason() {
    let q = Quat::<f64>::IDENTITY;
    let e = |r: Result<Q30Propagator, Error>| r.err();
    assert_eq!(
        e(Q30Propagator::new(q, RAD_PER_COUNT, 0.0)),
        Some(Error::NonPositiveStep)
    );
    assert_eq!(
        e(Q30Propagator::new(q, RAD_PER_COUNT, f64::NAN)),
        Some(Error::NonFiniteStep)
    );
    assert_eq!(
        e(Q30Propagator::new(q, -RAD_PER_COUNT, PERIOD)),
        Some(Error::InvalidScale)
    );
    assert_eq!(
        e(Q30Propagator::new(q, f64::INFINITY, PERIOD)),
        Some(Error::InvalidScale)
    );
    // One count over one period beyond 2⁻⁶ rad: 1 rad/s per count at 50 Hz.
    assert_eq!(
        e(Q30Propagator::new(q, 1.0, 0.02)),
        Some(Error::InvalidScale)
    );
    assert_eq!(
        e(Q30Propagator::new(
            Quat::new(0.0, 0.0, 0.0, 0.0),
            RAD_PER_COUNT,
            PERIOD
        )),
        Some(Error::ZeroQuaternion)
    );
    assert_eq!(
        e(Q30Propagator::new(
            Quat::new(f64::NAN, 0.0, 0.0, 0.0),
            RAD_PER_COUNT,
            PERIOD
        )),
        Some(Error::NonFiniteQuaternion)
    );
}

#[test]
fn a_step_beyond_half_a_radian_is_refused_and_changes_nothing() {
    // 10 Hz at ±2000 °/s: a full-scale step turns 3.5 rad. 2⁻⁶ rad per count-period allows the scale.
    let mut p = Q30Propagator::new(Quat::IDENTITY, RAD_PER_COUNT, 0.1).unwrap();
    p.push([0, 0, 0]).unwrap();
    p.push([100, 0, 0]).unwrap(); // 0.0106 rad: taken
    let before = p;
    match p.push([i16::MAX, 0, 0]) {
        Err(Error::StepAngleBeyondStability { step_angle, limit }) => {
            assert_eq!(limit, 0.5);
            assert!(step_angle > 0.5 && step_angle < 4.0, "{step_angle}");
        }
        r => panic!("{r:?}"),
    }
    assert_eq!(p, before);
    // A burst stops at it, the earlier samples taken.
    let r = p.push_burst(&[[120, 0, 0], [i16::MIN, 0, 0], [0, 0, 0]]);
    assert_eq!(r.map_err(|r| r.index), Err(1));
    assert_eq!(p.steps(), before.steps() + 1);
}

#[test]
fn rails_are_counted_and_a_restart_forgets_the_history() {
    let mut p = Q30Propagator::new(Quat::IDENTITY, RAD_PER_COUNT, PERIOD).unwrap();
    p.push([i16::MAX, 0, 0]).unwrap();
    p.push([i16::MAX, 5, 0]).unwrap();
    p.push([0, i16::MIN, 0]).unwrap();
    p.push([0, 0, 3]).unwrap();
    assert_eq!((p.saturated_samples(), p.steps()), (3, 3));
    p.restart_input();
    let q = p.attitude_q30();
    p.push([500, 0, 0]).unwrap(); // only starts the history again
    assert_eq!((p.attitude_q30(), p.steps()), (q, 3));
}
