//! Test 5 of the core issue: every bad input gets its typed error and leaves the propagator bit-for-bit
//! unchanged — attitude, counters and the samples the input model keeps — for every scheme × stabilizer ×
//! input model, at every position of the input model's cycle (start, pending, closing), in f32 and f64.
//!
//! "Unchanged" is checked twice: `==` on the whole `Propagator` (every field, input model included) and
//! equality of its `Debug` text, which tells `-0.0` from `0.0` (see `support::state`).

mod support;

use quatprop::input::{History, Hold, InputModel, TwiceRate};
use quatprop::scheme::{Baumgarte, Rk4, Scheme, SchemeKind};
use quatprop::stabilize::{Every, Normalize, Off, Stabilizer, StabilizerKind};
use quatprop::{Error, GyroSample, Propagator, Quat, Real, Vec3};
use support::{for_every_input_model, state, InputModelCheck};

fn stabilizers() -> [StabilizerKind; 4] {
    [
        StabilizerKind::Off,
        StabilizerKind::Normalize,
        StabilizerKind::FirstOrder,
        StabilizerKind::Every(3),
    ]
}

/// Pushes of good samples before the bad one: 0…5 covers every position of every model's cycle (the
/// longest is FiveSample's five increments).
const POSITIONS: usize = 6;

/// Every bad input of one propagator configuration, at every position of the input model's cycle.
/// `sample(v)` makes the model's sample from a rate-like vector (a delta angle takes `v · dt`).
fn check_config<T, S, I, Z>(scheme: S, input: I, z: Z, sample: &dyn Fn(Vec3<T>) -> I::Sample)
where
    T: Real,
    S: Scheme<T> + core::fmt::Debug + PartialEq,
    I: InputModel<T> + core::fmt::Debug + PartialEq,
    Z: Stabilizer + core::fmt::Debug + PartialEq,
{
    let nan = T::from_f64(f64::NAN);
    let inf = T::from_f64(f64::INFINITY);
    let good_w = Vec3::new(T::from_f64(0.3), T::from_f64(-0.2), T::from_f64(0.5));
    let good_dt = T::from_f64(0.01);
    let limit = scheme.information().step_angle_limit;
    for position in 0..POSITIONS {
        let mut p = Propagator::new(Quat::IDENTITY, scheme, input, z).unwrap();
        for _ in 0..position {
            p.push(sample(good_w), good_dt).unwrap();
        }
        let label = format!("{scheme:?} {z:?} {input:?} position {position}");
        let before = p;
        let text = state(&p);
        let cases: [(Vec3<T>, T, Error); 9] = [
            (
                Vec3::new(nan, T::ZERO, T::ZERO),
                good_dt,
                Error::NonFiniteRate,
            ),
            (
                Vec3::new(T::ZERO, inf, T::ZERO),
                good_dt,
                Error::NonFiniteRate,
            ),
            (
                Vec3::new(T::ZERO, T::ZERO, -inf),
                good_dt,
                Error::NonFiniteRate,
            ),
            (good_w, nan, Error::NonFiniteStep),
            (good_w, inf, Error::NonFiniteStep),
            (good_w, -inf, Error::NonFiniteStep),
            (good_w, T::ZERO, Error::NonPositiveStep),
            (good_w, -T::ZERO, Error::NonPositiveStep),
            (good_w, -good_dt, Error::NonPositiveStep),
        ];
        for (w, dt, want) in cases {
            assert_eq!(p.push(sample(w), dt), Err(want), "{label}");
            assert!(p == before, "{label} {want:?}: state changed");
            assert_eq!(state(&p), text, "{label} {want:?}: state changed");
        }
        if limit.is_finite() {
            // 1.5× the bound per sample along x: accepted while the model only keeps it, refused with the
            // bound reported by the push that closes a step containing it, and that push changes nothing.
            let huge = Vec3::new(T::from_f64(1.5 * limit / 0.01), T::ZERO, T::ZERO);
            let mut q = p;
            let mut next = sample(huge);
            let mut refused = false;
            for _ in 0..POSITIONS {
                let pending = q;
                match q.push(next, good_dt) {
                    Ok(()) => assert_eq!(q.steps(), p.steps(), "{label}: stepped over a huge rate"),
                    Err(Error::StepAngleBeyondStability {
                        step_angle,
                        limit: l,
                    }) => {
                        assert_eq!(l, limit, "{label}");
                        assert!(step_angle > limit, "{label}: {step_angle}");
                        assert!(q == pending, "{label}: state changed");
                        assert_eq!(state(&q), state(&pending), "{label}");
                        refused = true;
                        break;
                    }
                    Err(e) => panic!("{label}: {e:?}"),
                }
                next = sample(good_w);
            }
            assert!(refused, "{label}: a huge rate was never refused");
        }
        // And the propagator still works afterwards.
        p.push(sample(good_w), good_dt).unwrap();
    }
}

/// [`check_config`] of one scheme and stabilizer, for each input model (unsaturated samples).
struct EveryInputModel<S> {
    scheme: S,
    z: StabilizerKind,
}

impl<T: Real, S: Scheme<T> + core::fmt::Debug + PartialEq> InputModelCheck<T>
    for EveryInputModel<S>
{
    fn check<I>(&mut self, input: I, sample: fn(Vec3<T>, bool) -> I::Sample)
    where
        I: InputModel<T> + core::fmt::Debug + PartialEq,
    {
        check_config(self.scheme, input, self.z, &|v| sample(v, false));
    }
}

fn check_scheme<T: Real, S: Scheme<T> + core::fmt::Debug + PartialEq>(scheme: S) {
    for z in stabilizers() {
        for_every_input_model(&mut EveryInputModel { scheme, z });
    }
}

fn check_all<T: Real>() {
    for m in SchemeKind::ALL {
        check_scheme::<T, _>(m);
    }
    // The seed's Baumgarte right-hand side (4k·dt = 0.02, far inside its gain bound).
    check_scheme::<T, _>(Baumgarte::new(Rk4, T::from_f64(0.5)).unwrap());
}

support::tests_in_f32_and_f64!(
    check_all => bad_inputs_are_refused_with_state_unchanged_f32,
    bad_inputs_are_refused_with_state_unchanged_f64
);

#[test]
fn non_finite_sample_in_every_position_is_refused() {
    // The 0.1 `step_mid(w0, wm, w1)` had three sample positions; TwiceRate takes them one push each.
    let ok = GyroSample::new(Vec3::new(0.1, 0.2, 0.3));
    let bad = GyroSample::new(Vec3::new(0.1, f64::NAN, 0.3));
    let mut p = Propagator::new(Quat::<f64>::IDENTITY, Rk4, TwiceRate::new(), Normalize).unwrap();
    for position in 0..3 {
        let before = p;
        assert_eq!(p.push(bad, 0.01), Err(Error::NonFiniteRate), "{position}");
        assert_eq!(p, before);
        p.push(ok, 0.01).unwrap();
        assert_ne!(p, before, "a good sample is kept");
    }
    assert_eq!(p.steps(), 1);
}

#[test]
fn bad_initial_quaternions_and_stabilizers_are_refused() {
    let s = SchemeKind::Rk4;
    assert_eq!(
        Propagator::new(Quat::<f64>::ZERO, s, Hold, Off).unwrap_err(),
        Error::ZeroQuaternion
    );
    assert_eq!(
        Propagator::new(Quat::new(0.0_f32, 0.0, -0.0, 0.0), s, Hold, Off).unwrap_err(),
        Error::ZeroQuaternion
    );
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(
            Propagator::new(Quat::new(1.0, bad, 0.0, 0.0), s, Hold, Off).unwrap_err(),
            Error::NonFiniteQuaternion
        );
    }
    // Subnormal but non-zero: a valid direction, normalized exactly.
    let p = Propagator::new(Quat::new(1e-45_f32, 0.0, 0.0, 0.0), s, Hold, Off).unwrap();
    assert_eq!(p.attitude(), Quat::IDENTITY);
    assert_eq!(
        Propagator::new(Quat::<f64>::IDENTITY, s, Hold, Every(0)).unwrap_err(),
        Error::InvalidStabilizer
    );
    assert_eq!(
        Propagator::new(Quat::<f64>::IDENTITY, s, Hold, StabilizerKind::Every(0)).unwrap_err(),
        Error::InvalidStabilizer
    );
    for k in [
        -1.0,
        -f64::MIN_POSITIVE,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ] {
        assert_eq!(
            Baumgarte::new(Rk4, k).unwrap_err(),
            Error::InvalidGain,
            "{k}"
        );
    }
    // Zero and any finite positive gain are valid gains (a huge one is refused per step instead).
    for k in [0.0, f64::MIN_POSITIVE, f64::MAX] {
        assert_eq!(Baumgarte::new(Rk4, k).unwrap().gain(), k);
    }
    // set_attitude refuses the same inputs and keeps the state, input model included.
    let mut p = Propagator::new(Quat::<f64>::IDENTITY, s, History::new(), Off).unwrap();
    for _ in 0..3 {
        p.push(GyroSample::new(Vec3::new(0.1, 0.0, 0.0)), 0.1)
            .unwrap();
    }
    assert_eq!(p.input().len(), 3);
    let before = p;
    assert_eq!(p.set_attitude(Quat::ZERO), Err(Error::ZeroQuaternion));
    assert_eq!(
        p.set_attitude(Quat::new(f64::NAN, 0.0, 0.0, 0.0)),
        Err(Error::NonFiniteQuaternion)
    );
    assert_eq!(p, before);
}

#[test]
fn baumgarte_gain_beyond_the_real_axis_bound_is_refused() {
    // RK4's real-axis interval ends at 2.785, the accepted gain step at half of it: 4·k·dt = 4 · 100 · 0.01
    // = 4 is beyond it, and so is 4 · 100 · 0.004 = 1.6 (inside the interval, but Rk5 escapes at 0.82 of
    // its own interval: the lab's Baumgarte sweep).
    let scheme = Baumgarte::new(Rk4, 100.0).unwrap();
    let mut p = Propagator::new(Quat::<f64>::IDENTITY, scheme, Hold, Off).unwrap();
    let w = GyroSample::new(Vec3::new(0.1, 0.0, 0.0));
    let before = p;
    match p.push(w, 0.01) {
        Err(Error::GainBeyondStability { gain_step, limit }) => {
            assert!((gain_step - 4.0).abs() < 1e-12);
            assert!((limit - 2.785 / 2.0).abs() < 1e-3, "{limit}");
            assert_eq!(limit, scheme.gain_step_limit());
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(p, before);
    assert!(matches!(
        p.push(w, 0.004),
        Err(Error::GainBeyondStability { .. })
    ));
    assert_eq!(p, before);
    // Inside the bound it steps: 4 · 100 · 0.003 = 1.2.
    p.push(w, 0.003).unwrap();
    assert_eq!(p.steps(), 1);
}

#[test]
fn overflowing_rates_are_refused_not_propagated() {
    // |ω|² overflows f32: the step angle is infinite, beyond any finite bound.
    let mut p = Propagator::new(Quat::<f32>::IDENTITY, SchemeKind::Rk4, Hold, Normalize).unwrap();
    let before = p;
    let huge = GyroSample::new(Vec3::new(3e38_f32, 3e38, 0.0));
    assert!(matches!(
        p.push(huge, 1.0),
        Err(Error::StepAngleBeyondStability { .. })
    ));
    assert_eq!(p, before);
    // The exponential map has no stability bound. In f32 its step path computes rotations whose half angle
    // is at most 8192 rad (src/trig.rs; a step of 16384 rad) and refuses larger ones as a non-finite
    // result, state unchanged; in f64 any rotation whose |ω·h/2|² does not overflow.
    let mut p =
        Propagator::new(Quat::<f32>::IDENTITY, SchemeKind::ExpMap, Hold, Normalize).unwrap();
    let before = p;
    assert_eq!(p.push(huge, 1.0), Err(Error::NonFiniteResult));
    assert_eq!(p, before);
    let beyond = GyroSample::new(Vec3::new(0.0, 0.0, 16_384.5_f32));
    assert_eq!(p.push(beyond, 1.0), Err(Error::NonFiniteResult));
    assert_eq!(p, before);
    // Just inside: a yaw of 16383 rad, computed (Normalize: |N| ≤ 4ε) to the angle modulo 2π.
    let inside = GyroSample::new(Vec3::new(0.0, 0.0, 16_383.0_f32));
    p.push(inside, 1.0).unwrap();
    assert!(p.norm_error().abs() <= 4.0 * f32::EPSILON);
    let yaw = 2.0 * f64::from(p.attitude().z).atan2(f64::from(p.attitude().w));
    let off = libm::remainder(yaw - 16_383.0, 2.0 * core::f64::consts::PI);
    assert!(
        off.abs() < 1e-6,
        "yaw {yaw} is {off} rad off 16383 rad modulo 2π"
    );
    let mut p =
        Propagator::new(Quat::<f64>::IDENTITY, SchemeKind::ExpMap, Hold, Normalize).unwrap();
    p.push(GyroSample::new(Vec3::new(3e38_f64, 3e38, 0.0)), 1.0)
        .unwrap();
    assert!(p.attitude().is_finite());
    assert!(p.norm_error().abs() <= 4.0 * f64::EPSILON);
}

#[test]
fn zero_rate_hold_is_the_identity_bit_for_bit() {
    for m in SchemeKind::ALL {
        let q0 = Quat::new(0.5_f32, -0.5, 0.5, 0.5);
        let mut p = Propagator::new(q0, m, Hold, Off).unwrap();
        let q = p.attitude();
        for _ in 0..1000 {
            p.push(GyroSample::new(Vec3::ZERO), 0.001).unwrap();
        }
        assert_eq!(p.attitude(), q, "{m:?}");
        assert_eq!(p.steps(), 1000);
    }
}

#[test]
fn errors_display_with_units() {
    let e = Error::StepAngleBeyondStability {
        step_angle: 6.0,
        limit: 5.656854,
    };
    let s = format!("{e}");
    assert!(s.contains("6 rad") && s.contains("5.656854 rad"), "{s}");
    let boxed: Box<dyn std::error::Error> = Box::new(Error::NonFiniteRate);
    assert_eq!(boxed.to_string(), "rate sample is NaN or infinite");
}
