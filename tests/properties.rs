//! Property tests (issue "Reliability"): the fuzzing invariants over raw f32/f64 bit patterns (NaN, ±∞,
//! subnormals, huge and tiny values) for every entry point, scheme and stabilizer, plus algebraic properties.
//! cargo-fuzz needs a nightly toolchain, which this project's machines cannot install; these properties run
//! the same invariants on stable in every `cargo test`.
//!
//! Invariants after every call: either `Ok` with a finite attitude (and `|N| ≤ 4ε` for `Normalize`), or `Err`
//! with the propagator bit-for-bit unchanged.

use proptest::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// Entry-point calls executed by the invariant property (printed with --nocapture; a long run is
/// `PROPTEST_CASES=2000000 cargo test --release --test properties every_call -- --nocapture`).
static CALLS: AtomicU64 = AtomicU64::new(0);
static ERRORS: AtomicU64 = AtomicU64::new(0);
use quatprop::coning;
use quatprop::scheme::{ExpMap, Method, Scheme};
use quatprop::stabilize::{FirstOrder, Off, Policy};
use quatprop::{Propagator, Quat, SampleHistory, Vec3};

fn any_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        any::<u32>().prop_map(f32::from_bits),
        (-10.0f32..10.0),
        Just(0.0),
        Just(-0.0),
        Just(f32::NAN),
        Just(f32::INFINITY),
        Just(f32::MIN_POSITIVE / 4.0),
        Just(f32::MAX),
        Just(1e-3),
    ]
}

fn any_vec() -> impl Strategy<Value = Vec3<f32>> {
    (any_f32(), any_f32(), any_f32()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn any_method() -> impl Strategy<Value = Method> {
    (0..Method::ALL.len()).prop_map(|i| Method::ALL[i])
}

fn any_policy() -> impl Strategy<Value = Policy<f32>> {
    prop_oneof![
        Just(Policy::Off),
        Just(Policy::Normalize),
        Just(Policy::FirstOrder),
        (0u32..20).prop_map(Policy::Every),
        any_f32().prop_map(|k| Policy::Baumgarte { k }),
    ]
}

fn bits(p: &Propagator<f32, Method, Policy<f32>>) -> ([u32; 4], u64, u64, u64) {
    let q = p.attitude();
    (
        [q.w.to_bits(), q.x.to_bits(), q.y.to_bits(), q.z.to_bits()],
        p.steps(),
        p.corrections(),
        p.saturated_samples(),
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    #[test]
    fn every_call_is_ok_and_finite_or_an_error_that_changes_nothing(
        m in any_method(),
        pol in any_policy(),
        q0 in (any_f32(), any_f32(), any_f32(), any_f32()),
        calls in proptest::collection::vec((0u8..7, any_vec(), any_vec(), any_vec(), any_f32()), 1..12),
    ) {
        let q0 = Quat::new(q0.0, q0.1, q0.2, q0.3);
        let Ok(mut p) = Propagator::new(q0, m, pol) else {
            // Construction refused: fine, as long as it was a bad q0 or a bad stabilizer.
            return Ok(());
        };
        let mut history = SampleHistory::new();
        for (kind, a, b, c, dt) in calls {
            let before = bits(&p);
            let hist_before = history;
            CALLS.fetch_add(1, Ordering::Relaxed);
            let r = match kind {
                0 => p.step_hold(a, dt),
                1 => p.step_linear(a, b, dt),
                2 => p.step_mid(a, b, c, dt),
                3 => p.step_gauss(a, b, dt),
                4 => p.step_history(&mut history, a, dt),
                5 => p.step_delta(coning::Method::TwoSample, &[a, b], dt),
                _ => p.step_delta(coning::Method::OnePlusPrevious, &[c], dt),
            };
            match r {
                Ok(()) => {
                    prop_assert!(p.attitude().is_finite(), "{m:?} {pol:?}: non-finite attitude");
                    if pol == Policy::Normalize {
                        prop_assert!(p.norm_error().abs() <= 4.0 * f32::EPSILON, "{:e}", p.norm_error());
                    }
                }
                Err(_) => {
                    ERRORS.fetch_add(1, Ordering::Relaxed);
                    prop_assert_eq!(bits(&p), before, "state changed on error");
                    prop_assert_eq!(history, hist_before, "history changed on error");
                }
            }
        }
    }

    #[test]
    fn negated_start_gives_the_negated_attitude_bit_for_bit(
        m in any_method(),
        q in (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0),
        w in (-3.0f64..3.0, -3.0f64..3.0, -3.0f64..3.0),
    ) {
        let q0 = Quat::new(q.0, q.1, q.2, q.3);
        prop_assume!(q0.norm() > 0.1);
        let w = Vec3::new(w.0, w.1, w.2);
        let mut a = Propagator::new(q0, m, FirstOrder).unwrap();
        let mut b = Propagator::new(-q0, m, FirstOrder).unwrap();
        for _ in 0..20 {
            a.step_linear(w, w * 0.9, 1e-2).unwrap();
            b.step_linear(w, w * 0.9, 1e-2).unwrap();
        }
        // Every operation is linear in q or uses |q|², so q and −q stay exact negatives: the same rotation.
        prop_assert_eq!(b.attitude(), -a.attitude());
    }

    #[test]
    fn exp_map_composes_in_the_body_frame_and_two_half_steps_equal_one(
        q in (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0),
        w in (-5.0f64..5.0, -5.0f64..5.0, -5.0f64..5.0),
        h in 1e-4f64..0.5,
    ) {
        let q0 = Quat::new(q.0, q.1, q.2, q.3);
        prop_assume!(q0.norm() > 0.1);
        let q0 = q0.normalized().unwrap();
        let w = Vec3::new(w.0, w.1, w.2);
        let mut one = Propagator::new(q0, ExpMap, Off).unwrap();
        one.step_hold(w, h).unwrap();
        let mut two = Propagator::new(q0, ExpMap, Off).unwrap();
        two.step_hold(w, h / 2.0).unwrap();
        two.step_hold(w, h / 2.0).unwrap();
        // Body frame: q(h) = q0 ⊗ exp_q(ω h).
        let body = q0 * Quat::from_rotation_vector(w * h);
        prop_assert!(one.attitude().angle_to(body) < 1e-14);
        prop_assert!(two.attitude().angle_to(one.attitude()) < 1e-14);
    }

    #[test]
    fn rk_two_half_steps_agree_with_one_step_within_the_local_error(
        m in (0usize..5).prop_map(|i| Method::ALL[i]),
        w in (-2.0f64..2.0, -2.0f64..2.0, -2.0f64..2.0),
        h in 1e-3f64..0.2,
    ) {
        let w = Vec3::new(w.0, w.1, w.2);
        let x = 0.5 * h * w.norm();
        let mut one = Propagator::new(Quat::IDENTITY, m, Off).unwrap();
        one.step_hold(w, h).unwrap();
        let mut two = Propagator::new(Quat::IDENTITY, m, Off).unwrap();
        two.step_hold(w, h / 2.0).unwrap();
        two.step_hold(w, h / 2.0).unwrap();
        // Local error of an order-p RK step is ≤ x^(p+1)/(p+1)! · e^x (Taylor remainder of R vs e^z).
        let p = m.order() as i32;
        let fact: f64 = (1..=p + 1).map(|k| k as f64).product();
        let bound = 2.0 * x.powi(p + 1) / fact * x.exp() + 1e-15;
        prop_assert!((one.attitude() - two.attitude()).norm() <= bound, "{m:?}");
    }

    #[test]
    fn zero_rate_hold_is_the_identity_bit_for_bit(
        m in any_method(),
        q in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
        dt in 1e-6f32..10.0,
    ) {
        let q0 = Quat::new(q.0, q.1, q.2, q.3);
        prop_assume!(q0.norm() > 0.1);
        let mut p = Propagator::new(q0, m, Off).unwrap();
        let start = p.attitude();
        p.step_hold(Vec3::ZERO, dt).unwrap();
        prop_assert_eq!(p.attitude(), start);
    }

    #[test]
    fn conversions_round_trip_near_singularities(
        yaw in -3.1f64..3.1, roll in -3.1f64..3.1, tilt in 0.0f64..1e-6, sign in prop::bool::ANY,
    ) {
        let pitch = if sign { 1.0 } else { -1.0 } * (core::f64::consts::FRAC_PI_2 - tilt);
        let q = Quat::from_euler_zyx(quatprop::EulerZyx { yaw, pitch, roll });
        let back = Quat::from_euler_zyx(q.to_euler_zyx());
        prop_assert!(q.angle_to(back) < 1e-14);
        prop_assert!((q.to_euler_zyx().pitch - pitch).abs() < 1e-15);
        let z = Quat::from_euler_zxz(quatprop::EulerZxz { psi: yaw, theta: tilt, phi: roll });
        prop_assert!(z.angle_to(Quat::from_euler_zxz(z.to_euler_zxz())) < 1e-14);
    }
}

#[test]
fn zz_report_call_count() {
    // Runs after the properties in the default alphabetical order when tests run single-threaded; otherwise
    // it may print a partial count. Informational only.
    println!(
        "invariant property: {} entry-point calls, {} of them refused",
        CALLS.load(Ordering::Relaxed),
        ERRORS.load(Ordering::Relaxed)
    );
}

#[test]
fn schemes_listed_for_the_properties_are_every_scheme() {
    assert_eq!(Method::ALL.len(), 8);
    assert!(Method::ALL.iter().all(|m| m.order() >= 1));
}
