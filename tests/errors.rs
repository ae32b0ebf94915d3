//! Test 5 of the core issue: every bad input gets its typed error and leaves the propagator bit-for-bit
//! unchanged, for every scheme × stabilizer × input model, in f32 and f64.

use quatprop::scheme::{Method, Rk4, Scheme};
use quatprop::stabilize::{Baumgarte, Every, Policy};
use quatprop::{Error, Propagator, Quat, Real, Vec3};

/// Bit pattern of the whole propagator state, via its public accessors (NaN-safe comparison).
fn snapshot<T: Real, S: Scheme, Z: quatprop::stabilize::Stabilizer<T>>(
    p: &Propagator<T, S, Z>,
) -> ([u64; 4], u64, u64) {
    let q = p.attitude().to_f64();
    (
        [q.w.to_bits(), q.x.to_bits(), q.y.to_bits(), q.z.to_bits()],
        p.steps(),
        p.corrections(),
    )
}

fn policies<T: Real>() -> [Policy<T>; 5] {
    [
        Policy::Off,
        Policy::Normalize,
        Policy::FirstOrder,
        Policy::Every(3),
        Policy::Baumgarte {
            k: T::from_f64(0.5),
        },
    ]
}

#[derive(Clone, Copy, Debug)]
enum Call {
    Hold,
    Linear,
    Mid,
}

fn call<T: Real>(
    p: &mut Propagator<T, Method, Policy<T>>,
    c: Call,
    w: Vec3<T>,
    dt: T,
) -> Result<(), Error> {
    let ok = Vec3::new(T::from_f64(0.1), T::ZERO, T::ZERO);
    match c {
        Call::Hold => p.step_hold(w, dt),
        // The bad sample in each position in turn is covered by the loop over `slot` below.
        Call::Linear => p.step_linear(ok, w, dt),
        Call::Mid => p.step_mid(ok, w, ok, dt),
    }
}

fn check_all<T: Real>() {
    let nan = T::from_f64(f64::NAN);
    let inf = T::from_f64(f64::INFINITY);
    let good_w = Vec3::new(T::from_f64(0.3), T::from_f64(-0.2), T::from_f64(0.5));
    let good_dt = T::from_f64(0.01);
    for m in Method::ALL {
        for pol in policies::<T>() {
            for c in [Call::Hold, Call::Linear, Call::Mid] {
                let mut p = Propagator::new(Quat::IDENTITY, m, pol).unwrap();
                // Take a few good steps so the state is not trivial (and Every has a pending count).
                for _ in 0..2 {
                    call(&mut p, c, good_w, good_dt).unwrap();
                }
                let before = snapshot(&p);
                let limit = m.step_angle_limit();
                let mut cases: Vec<(Vec3<T>, T, Error)> = vec![
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
                if limit.is_finite() {
                    // 1.5× the bound: refused with the bound reported.
                    let w = Vec3::new(T::from_f64(1.5 * limit / 0.01), T::ZERO, T::ZERO);
                    cases.push((
                        w,
                        good_dt,
                        Error::StepAngleBeyondStability {
                            step_angle: 0.0,
                            limit,
                        },
                    ));
                }
                for (w, dt, want) in cases {
                    let got = call(&mut p, c, w, dt);
                    let err = got.expect_err("bad input accepted");
                    match (err, want) {
                        (
                            Error::StepAngleBeyondStability {
                                step_angle,
                                limit: l,
                            },
                            Error::StepAngleBeyondStability { limit: wl, .. },
                        ) => {
                            assert_eq!(l, wl);
                            assert!((step_angle / (1.5 * l) - 1.0).abs() < 1e-5, "{step_angle}");
                        }
                        _ => assert_eq!(err, want, "{m:?} {pol:?} {c:?}"),
                    }
                    assert_eq!(
                        snapshot(&p),
                        before,
                        "{m:?} {pol:?} {c:?} {want:?}: state changed"
                    );
                }
                // And the propagator still works afterwards.
                call(&mut p, c, good_w, good_dt).unwrap();
            }
        }
    }
}

#[test]
fn bad_inputs_are_refused_with_state_unchanged_f32() {
    check_all::<f32>();
}

#[test]
fn bad_inputs_are_refused_with_state_unchanged_f64() {
    check_all::<f64>();
}

#[test]
fn non_finite_sample_in_every_position_is_refused() {
    let mut p = Propagator::new(Quat::<f64>::IDENTITY, Rk4, Policy::Normalize).unwrap();
    let ok = Vec3::new(0.1, 0.2, 0.3);
    let bad = Vec3::new(0.1, f64::NAN, 0.3);
    let before = p;
    assert_eq!(p.step_linear(bad, ok, 0.01), Err(Error::NonFiniteRate));
    assert_eq!(p.step_linear(ok, bad, 0.01), Err(Error::NonFiniteRate));
    assert_eq!(p.step_mid(bad, ok, ok, 0.01), Err(Error::NonFiniteRate));
    assert_eq!(p.step_mid(ok, bad, ok, 0.01), Err(Error::NonFiniteRate));
    assert_eq!(p.step_mid(ok, ok, bad, 0.01), Err(Error::NonFiniteRate));
    assert_eq!(p, before);
}

#[test]
fn bad_initial_quaternions_and_stabilizers_are_refused() {
    let s = Method::Rk4;
    assert_eq!(
        Propagator::new(Quat::<f64>::ZERO, s, Policy::Off).unwrap_err(),
        Error::ZeroQuaternion
    );
    assert_eq!(
        Propagator::new(Quat::new(0.0_f32, 0.0, -0.0, 0.0), s, Policy::Off).unwrap_err(),
        Error::ZeroQuaternion
    );
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(
            Propagator::new(Quat::new(1.0, bad, 0.0, 0.0), s, Policy::Off).unwrap_err(),
            Error::NonFiniteQuaternion
        );
    }
    // Subnormal but non-zero: a valid direction, normalized exactly.
    let p = Propagator::new(Quat::new(1e-45_f32, 0.0, 0.0, 0.0), s, Policy::Off).unwrap();
    assert_eq!(p.attitude(), Quat::IDENTITY);
    assert_eq!(
        Propagator::new(Quat::<f64>::IDENTITY, s, Every(0)).unwrap_err(),
        Error::InvalidStabilizer
    );
    for k in [-1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(
            Propagator::new(Quat::<f64>::IDENTITY, s, Baumgarte { k }).unwrap_err(),
            Error::InvalidStabilizer
        );
    }
    // set_attitude refuses the same inputs and keeps the state.
    let mut p = Propagator::new(Quat::<f64>::IDENTITY, s, Policy::Off).unwrap();
    p.step_hold(Vec3::new(0.1, 0.0, 0.0), 0.1).unwrap();
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
    let mut p = Propagator::new(Quat::<f64>::IDENTITY, Rk4, Baumgarte { k: 100.0 }).unwrap();
    let before = p;
    match p.step_hold(Vec3::new(0.1, 0.0, 0.0), 0.01) {
        Err(Error::GainBeyondStability { gain_step, limit }) => {
            assert!((gain_step - 4.0).abs() < 1e-12);
            assert!((limit - 2.785 / 2.0).abs() < 1e-3, "{limit}");
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(p, before);
    assert!(matches!(
        p.step_hold(Vec3::new(0.1, 0.0, 0.0), 0.004),
        Err(Error::GainBeyondStability { .. })
    ));
    assert_eq!(p, before);
    // Inside the bound it steps: 4 · 100 · 0.003 = 1.2.
    p.step_hold(Vec3::new(0.1, 0.0, 0.0), 0.003).unwrap();
}

#[test]
fn overflowing_rates_are_refused_not_propagated() {
    // |ω|² overflows f32: the step angle is infinite, beyond any finite bound.
    let mut p = Propagator::new(Quat::<f32>::IDENTITY, Method::Rk4, Policy::Normalize).unwrap();
    let before = p;
    let huge = Vec3::new(3e38_f32, 3e38, 0.0);
    assert!(matches!(
        p.step_hold(huge, 1.0),
        Err(Error::StepAngleBeyondStability { .. })
    ));
    assert_eq!(p, before);
    // The exponential map has no bound: a huge but finite rotation is a valid (if meaningless) rotation,
    // computed without overflow, and the attitude stays finite and unit.
    let mut p = Propagator::new(Quat::<f32>::IDENTITY, Method::ExpMap, Policy::Normalize).unwrap();
    p.step_hold(huge, 1.0).unwrap();
    assert!(p.attitude().is_finite());
    assert!(p.norm_error().abs() <= 4.0 * f32::EPSILON);
}

#[test]
fn zero_rate_hold_is_the_identity_bit_for_bit() {
    for m in Method::ALL {
        let q0 = Quat::new(0.5_f32, -0.5, 0.5, 0.5);
        let mut p = Propagator::new(q0, m, Policy::Off).unwrap();
        let q = p.attitude();
        for _ in 0..1000 {
            p.step_hold(Vec3::ZERO, 0.001).unwrap();
        }
        assert_eq!(p.attitude(), q, "{m:?}");
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
