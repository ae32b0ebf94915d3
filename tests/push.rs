//! The 0.2 entry point, `Propagator::push`: what it counts, what a refused sample leaves behind, how
//! `History` handles its spacing, and every error `push` and `new` can return.

mod support;

use quatprop::input::coning::{ConingCorrection, ConingKind, TwoSample};
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, InputModel, Linear, TwiceRate};
use quatprop::scheme::{Baumgarte, Euler, ExpMap, Rk4, Scheme, SchemeKind};
use quatprop::stabilize::{Every, FirstOrder, Off, StabilizerKind};
use quatprop::{DeltaAngle, Error, GyroSample, Propagator, Quat, Real, Vec3};
use support::{
    assert_history_is_fourth_order, convergence, for_every_input_model, state, Coning,
    InputModelCheck,
};

/// A smooth test rate (rad/s) at sample `k`.
fn rate(k: usize) -> Vec3<f64> {
    let t = k as f64 * 0.01;
    Vec3::new(0.3 + t.sin(), -0.2 * t, 0.5 * (2.0 * t).cos())
}

fn gyro(v: Vec3<f64>, saturated: bool) -> GyroSample<f64> {
    GyroSample { rate: v, saturated }
}

/// A delta angle over one 0.01 s sample interval.
fn delta(v: Vec3<f64>, saturated: bool) -> DeltaAngle<f64> {
    DeltaAngle {
        angle: v * 0.01,
        saturated,
    }
}

// ---------------------------------------------------------------------------------------------------------
// Saturation counting

/// Every accepted saturated sample counts once, whether it closes a step, only starts the model or waits
/// as pending; no refused sample counts (a NaN, a bad dt, or a step refused for its step angle), and no
/// unsaturated one.
fn saturation_on<I: InputModel<f64> + core::fmt::Debug + PartialEq>(
    input: I,
    sample: fn(Vec3<f64>, bool) -> I::Sample,
    every_push_steps: bool,
) {
    let label = format!("{input:?}");
    let mut p = Propagator::new(Quat::IDENTITY, Rk4, input, FirstOrder).unwrap();
    let nan = Vec3::new(f64::NAN, 0.0, 0.0);
    let mut count = 0;
    let mut started_or_pending = 0;
    for k in 0..12 {
        let steps = p.steps();
        p.push(sample(rate(k), true), 0.01).unwrap();
        count += 1;
        if p.steps() == steps {
            started_or_pending += 1;
        }
        assert_eq!(
            p.saturated_samples(),
            count,
            "{label}: accepted clipped sample {k}"
        );
        // Refused for the sample, for dt, or (on a copy that reaches a closing push) for the step angle.
        let before = p;
        assert_eq!(p.push(sample(nan, true), 0.01), Err(Error::NonFiniteRate));
        assert_eq!(
            p.push(sample(rate(k), true), 0.0),
            Err(Error::NonPositiveStep)
        );
        assert_eq!(
            p.push(sample(rate(k), true), f64::NAN),
            Err(Error::NonFiniteStep)
        );
        assert_eq!(p, before, "{label}");
        let mut q = p;
        // 1.5× Rk4's bound over each 0.01 s sample.
        let huge = sample(Vec3::new(1.5 * 4.0 * 2f64.sqrt() / 0.01, 0.0, 0.0), true);
        let mut kept = 0;
        loop {
            let pending = q;
            match q.push(huge, 0.01) {
                Ok(()) => kept += 1, // kept by the model, not yet a step: counted
                Err(Error::StepAngleBeyondStability { .. }) => {
                    assert_eq!(q, pending, "{label}");
                    break;
                }
                Err(e) => panic!("{label}: {e:?}"),
            }
            assert!(kept < 6, "{label}: never refused");
        }
        assert_eq!(q.saturated_samples(), count + kept, "{label}");
        // An unsaturated sample counts nothing.
        p.push(sample(rate(k), false), 0.01).unwrap();
        assert_eq!(p.saturated_samples(), count, "{label}");
    }
    assert!(p.steps() > 0, "{label}");
    if every_push_steps {
        assert_eq!(started_or_pending, 0, "{label}");
    } else {
        assert!(
            started_or_pending > 0,
            "{label}: no starting or pending sample was checked"
        );
    }
}

#[test]
fn saturation_is_counted_on_every_input_path() {
    // The input models listed here rather than through `for_every_input_model`: each line states whether
    // that model closes a step on every push.
    saturation_on(Hold, gyro, true);
    saturation_on(Linear::new(), gyro, false);
    saturation_on(History::new(), gyro, false);
    saturation_on(TwiceRate::new(), gyro, false);
    saturation_on(GaussPoints::new(), gyro, false);
    for c in ConingKind::ALL {
        // Uncorrected and OnePlusPrevious take one increment per update; the others keep some pending.
        saturation_on(DeltaAngles::new(c), delta, c.samples() == 1);
    }
}

// ---------------------------------------------------------------------------------------------------------
// A refused sample, then the next one with the time since the last accepted one

/// Stream A refuses sample `skip` (NaN) and pushes the next with dt = 2 periods; stream B never had that
/// sample and pushes the next with dt = 2 periods. Both continue with the same samples. They must be
/// bit-for-bit the same propagator after every push.
struct RefusedThenDoubleDt {
    skip: usize,
}

impl InputModelCheck<f64> for RefusedThenDoubleDt {
    fn check<I>(&mut self, input: I, sample: fn(Vec3<f64>, bool) -> I::Sample)
    where
        I: InputModel<f64> + core::fmt::Debug + PartialEq,
    {
        let skip = self.skip;
        let c = Coning::STANDARD;
        let mut a = Propagator::new(c.attitude(0.0), ExpMap, input, Off).unwrap();
        let mut b = a;
        let nan = Vec3::new(0.0, f64::NAN, 0.0);
        for k in 0..skip + 12 {
            let dt = if k == skip + 1 { 0.02 } else { 0.01 };
            if k == skip {
                let before = a;
                assert_eq!(a.push(sample(nan, false), 0.01), Err(Error::NonFiniteRate));
                assert_eq!(a, before);
                continue; // B never saw it
            }
            let s = sample(c.rate(0.01 * k as f64), false);
            a.push(s, dt).unwrap();
            b.push(s, dt).unwrap();
            assert!(a == b, "{input:?}: streams differ after sample {k}");
            assert_eq!(state(&a), state(&b));
        }
        assert!(a.steps() > 0);
    }
}

#[test]
fn a_refused_sample_then_the_next_after_two_periods_is_as_if_it_never_existed() {
    for skip in 3..9 {
        for_every_input_model(&mut RefusedThenDoubleDt { skip });
    }
}

/// A refused sample's interval (two periods) is spanned by the cubic at the samples' true times; three
/// periods (two samples lost) is a gap: the history restarts (kept samples drop), and the restarted step is
/// the linear step over the true 3-period interval, the same rotation as `Linear` from the same attitude and
/// samples.
#[test]
fn history_spans_a_refused_interval_and_restarts_on_a_gap_with_a_linear_step_over_it() {
    let c = Coning::STANDARD;
    let skip = 5;
    let mut p = Propagator::new(c.attitude(0.0), ExpMap, History::new(), Off).unwrap();
    for k in 0..skip {
        p.push(GyroSample::new(c.rate(0.01 * k as f64)), 0.01)
            .unwrap();
    }
    assert_eq!(p.input().len(), 3);
    // Two periods: no restart, the history stays full.
    let mut spanned = p;
    spanned
        .push(GyroSample::new(c.rate(0.01 * (skip + 1) as f64)), 0.02)
        .unwrap();
    assert_eq!(spanned.input().len(), 3);
    let before = p;
    let (w_prev, w_next) = (
        c.rate(0.01 * (skip - 1) as f64),
        c.rate(0.01 * (skip + 2) as f64),
    );
    p.push(GyroSample::new(w_next), 0.03).unwrap();
    // The restart kept only the last sample, then took this one.
    assert_eq!(p.input().len(), 2);
    assert_eq!(p.steps(), before.steps() + 1);
    let mut linear = Propagator::new(before.attitude(), ExpMap, Linear::new(), Off).unwrap();
    linear.push(GyroSample::new(w_prev), 0.01).unwrap();
    linear.push(GyroSample::new(w_next), 0.03).unwrap();
    // Same formula in exact arithmetic (½∫ω = (hh/2)(ω₀ + ω₁), commutator ω₀ × ω₁ = ω(½) × (ω₁ − ω₀)),
    // different rounding: each half-angle component carries a few roundings of ≤ ε/2 relative to a 0.03 rad
    // step, the exponential and the product a few ε more, and set_attitude's normalization of the start
    // ≤ 2ε. 16ε (rad) bounds their sum.
    let d = p.attitude().angle_to(linear.attitude());
    assert!(d <= 16.0 * f64::EPSILON, "{d:e}");
    // A further sample at the new spacing (0.01 again) restarts once more: dt is a third of 0.03.
    p.push(GyroSample::new(c.rate(0.01 * (skip + 3) as f64)), 0.01)
        .unwrap();
    assert_eq!(p.input().len(), 2);
    p.push(GyroSample::new(c.rate(0.01 * (skip + 4) as f64)), 0.01)
        .unwrap();
    assert_eq!(
        p.input().len(),
        3,
        "equal spacing builds the history up again"
    );
}

// ---------------------------------------------------------------------------------------------------------
// History: order 4 at equal spacing, restarts at unequal spacing

#[test]
fn history_step_order_is_four_at_equal_spacing() {
    let schemes = [SchemeKind::ExpMap, SchemeKind::Rk4, SchemeKind::Cf4];
    assert_history_is_fourth_order(&schemes, &[40, 80, 160, 320]);
}

/// With every 8th interval longer: up to two periods (jitter, a dropped or refused sample) the cubic spans
/// it at the samples' true times and the order stays 4. Three periods is a gap: History restarts twice per
/// long interval (entering and leaving it), the gap's step linear over its true interval (local error O(h³),
/// nothing being known of ω inside it), the steps after it a fresh start (fourth order). The gaps are a
/// fixed fraction of the steps, so the global error falls as h² — and it converges at all because each
/// restarted step integrates over its true interval. Were the cubic built on the wrong spacing, its error
/// would be O(h) per step and the run would not converge.
#[test]
fn history_keeps_fourth_order_under_jitter_and_dropped_samples_and_restarts_at_gaps() {
    let c = Coning::STANDARD;
    // (long interval, restarts expected per long interval, order): 1.3 h is jitter and 2 h a dropped
    // sample (both within History::GAP_RATIO): the cubic through the samples at their true times, no
    // restart, order 4. 3 h is a gap: restarts on entering and on leaving it, order 2.
    for (stretch, restarts_per, order) in [(1.3, 0usize, 4.0), (2.0, 0, 4.0), (3.0, 2, 2.0)] {
        let (es, slope) = convergence(0.7, &[64, 128, 256, 512], |n| {
            let h = 0.7 / n as f64;
            // Pre-fill the history with the samples at −3h … 0 and reset the attitude to the exact one, so
            // the start-up's linear and quadratic steps (local errors h³, h⁴) do not mask the order.
            let mut p = Propagator::new(c.attitude(0.0), ExpMap, History::new(), Off).unwrap();
            for k in [-3.0, -2.0, -1.0, 0.0] {
                p.push(GyroSample::new(c.rate(k * h)), h).unwrap();
            }
            p.set_attitude(c.attitude(0.0)).unwrap();
            let mut t = 0.0;
            let mut restarts = 0;
            for i in 0..n {
                let dt = if i % 8 == 7 { stretch * h } else { h };
                t += dt;
                let len = p.input().len();
                p.push(GyroSample::new(c.rate(t)), dt).unwrap();
                // Without a restart the history grows (1 → 2 → 3) or stays full; a restart leaves 2.
                if len >= 2 && p.input().len() == 2 {
                    restarts += 1;
                }
            }
            let expected = restarts_per * (n / 8) - usize::from(restarts_per > 0);
            assert_eq!(restarts, expected, "stretch {stretch}, n = {n}");
            p.attitude().angle_to(c.attitude(t))
        });
        println!("History with every 8th interval {stretch} h: {es:?}, order {slope:.3}");
        assert!(
            (slope - order).abs() < 0.15,
            "stretch {stretch}: order {slope}"
        );
    }
}

// ---------------------------------------------------------------------------------------------------------
// Every error variant of push and new

/// The name of an error variant.
fn variant(e: &Error) -> &'static str {
    match e {
        Error::NonFiniteRate => "NonFiniteRate",
        Error::NonFiniteStep => "NonFiniteStep",
        Error::NonPositiveStep => "NonPositiveStep",
        Error::StepAngleBeyondStability { .. } => "StepAngleBeyondStability",
        Error::GainBeyondStability { .. } => "GainBeyondStability",
        Error::ZeroQuaternion => "ZeroQuaternion",
        Error::NonFiniteQuaternion => "NonFiniteQuaternion",
        Error::InvalidStabilizer => "InvalidStabilizer",
        Error::InvalidGain => "InvalidGain",
        Error::NonFiniteResult => "NonFiniteResult",
        _ => "unknown (a variant this test does not list)",
    }
}

/// `push` refuses with `want`, leaving the propagator bit for bit as it was.
fn refused<
    T: Real,
    S: Scheme<T> + PartialEq + core::fmt::Debug,
    I: InputModel<T> + PartialEq + core::fmt::Debug,
>(
    p: &mut Propagator<
        T,
        S,
        I,
        impl quatprop::stabilize::Stabilizer + PartialEq + core::fmt::Debug,
    >,
    sample: I::Sample,
    dt: T,
    want: fn(&Error) -> bool,
) -> Error {
    let before = *p;
    let text = state(p);
    let e = p.push(sample, dt).expect_err("accepted");
    assert!(want(&e), "{e:?}");
    assert!(*p == before);
    assert_eq!(state(p), text);
    e
}

#[test]
fn every_error_variant_of_push_and_new_is_returned_for_its_input_with_the_state_unchanged() {
    let mut seen = std::collections::BTreeSet::new();
    let w = GyroSample::new(Vec3::new(0.3, -0.2, 0.5));

    // new: the stabilizer is checked first, then the quaternion.
    let e = Propagator::new(Quat::<f64>::IDENTITY, Rk4, Hold, Every(0)).unwrap_err();
    assert_eq!(e, Error::InvalidStabilizer);
    seen.insert(variant(&e));
    assert_eq!(
        Propagator::new(Quat::<f64>::IDENTITY, Rk4, Hold, StabilizerKind::Every(0)).unwrap_err(),
        Error::InvalidStabilizer
    );
    assert_eq!(
        Propagator::new(Quat::<f64>::ZERO, Rk4, Hold, Every(0)).unwrap_err(),
        Error::InvalidStabilizer
    );
    let e = Propagator::new(Quat::<f64>::ZERO, Rk4, Hold, Off).unwrap_err();
    assert_eq!(e, Error::ZeroQuaternion);
    seen.insert(variant(&e));
    let e = Propagator::new(Quat::new(f64::NAN, 1.0, 0.0, 0.0), Rk4, Hold, Off).unwrap_err();
    assert_eq!(e, Error::NonFiniteQuaternion);
    seen.insert(variant(&e));
    let e = Baumgarte::new(Rk4, -1.0_f64).unwrap_err();
    assert_eq!(e, Error::InvalidGain);
    seen.insert(variant(&e));

    // push, on a propagator that has taken a step and keeps samples (History).
    let mut p = Propagator::new(Quat::<f64>::IDENTITY, Rk4, History::new(), FirstOrder).unwrap();
    for _ in 0..3 {
        p.push(w, 0.01).unwrap();
    }
    for dt in [0.0, -0.0, -0.01, -f64::MIN_POSITIVE] {
        seen.insert(variant(&refused(&mut p, w, dt, |e| {
            *e == Error::NonPositiveStep
        })));
    }
    for dt in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        seen.insert(variant(&refused(&mut p, w, dt, |e| {
            *e == Error::NonFiniteStep
        })));
    }
    for bad in [f64::NAN, f64::INFINITY] {
        let s = GyroSample::new(Vec3::new(0.0, 0.0, bad));
        seen.insert(variant(&refused(&mut p, s, 0.01, |e| {
            *e == Error::NonFiniteRate
        })));
    }
    // Step angle: RK4 admits h·max|ω| ≤ 4√2 ≈ 5.66 rad; a 600 rad/s sample over 0.01 s is 6 rad (the kept
    // samples are far smaller, so the maximum is this one's).
    let e = refused(
        &mut p,
        GyroSample::new(Vec3::new(600.0, 0.0, 0.0)),
        0.01,
        |e| {
            matches!(e, Error::StepAngleBeyondStability { step_angle, limit }
            if (*step_angle - 6.0).abs() < 1e-12 && (*limit - 4.0 * 2f64.sqrt()).abs() < 1e-9)
        },
    );
    seen.insert(variant(&e));
    // Baumgarte's gain: 4·k·h = 4 · 50 · 0.01 = 2 > RK4's 1.39.
    let mut b = Propagator::new(
        Quat::<f64>::IDENTITY,
        Baumgarte::new(Rk4, 50.0).unwrap(),
        Hold,
        Off,
    )
    .unwrap();
    let e = refused(
        &mut b,
        w,
        0.01,
        |e| matches!(e, Error::GainBeyondStability { gain_step, .. } if (*gain_step - 2.0).abs() < 1e-12),
    );
    seen.insert(variant(&e));
    b.push(w, 0.005).unwrap(); // 4 · 50 · 0.005 = 1: inside

    // Overflow: Euler gains norm by 1 + x² per step; at h|ω| = 2 (its admitted limit) |q|² doubles every
    // step, so an f32 attitude overflows after about log2(f32::MAX²) = 256 steps.
    let mut p = Propagator::new(Quat::<f32>::IDENTITY, Euler, Hold, Off).unwrap();
    let spin = GyroSample::new(Vec3::new(0.0_f32, 2.0, 0.0));
    let mut steps = 0;
    let e = loop {
        let before = p;
        match p.push(spin, 1.0) {
            Ok(()) => steps += 1,
            Err(e) => {
                assert_eq!(p, before);
                break e;
            }
        }
        assert!(steps <= 260, "never overflowed");
    };
    assert_eq!(e, Error::NonFiniteResult);
    assert!(
        (250..=257).contains(&steps),
        "overflowed after {steps} steps"
    );
    assert!(p.attitude().is_finite() && p.attitude().norm() > 1e37);
    seen.insert(variant(&e));
    // Refused again, identically: nothing moved.
    assert_eq!(
        refused(&mut p, spin, 1.0, |e| *e == Error::NonFiniteResult),
        Error::NonFiniteResult
    );

    // set_attitude: the same quaternion errors, the state kept.
    let mut p = Propagator::new(
        Quat::<f64>::IDENTITY,
        ExpMap,
        DeltaAngles::new(TwoSample),
        Off,
    )
    .unwrap();
    p.push(DeltaAngle::new(Vec3::new(0.01, 0.0, 0.0)), 0.01)
        .unwrap(); // pending
    let before = p;
    assert_eq!(p.set_attitude(Quat::ZERO), Err(Error::ZeroQuaternion));
    assert_eq!(
        p.set_attitude(Quat::new(0.0, f64::INFINITY, 0.0, 0.0)),
        Err(Error::NonFiniteQuaternion)
    );
    assert_eq!(p, before);

    println!("{seen:?}");
    assert_eq!(seen.len(), 10, "every variant: {seen:?}");
    assert!(!seen.iter().any(|s| s.starts_with("unknown")));
}

/// A delta angle beyond the scheme's bound that a two-sample coning correction would keep for the next
/// update is refused when it arrives, and the stream goes on: before, it was kept, and every update after
/// it was refused (the stream never recovered).
#[test]
fn a_kept_delta_angle_beyond_the_bound_is_refused_when_it_arrives() {
    let small = DeltaAngle::new(Vec3::new(1e-3, -2e-3, 0.5e-3));
    let big = DeltaAngle::new(Vec3::new(6.0, 0.0, 0.0)); // beyond Rk4's 4√2 rad
    let mut p = Propagator::new(Quat::IDENTITY, Rk4, DeltaAngles::new(TwoSample), Off).unwrap();
    for _ in 0..4 {
        p.push(small, 1e-3).unwrap();
    }
    let before = p;
    let e = p.push(big, 1e-3).unwrap_err();
    assert!(
        matches!(e, Error::StepAngleBeyondStability { step_angle, .. } if step_angle == 6.0),
        "{e:?}"
    );
    assert_eq!(p, before);
    // The next pairs close as if the big increment never came.
    for _ in 0..6 {
        p.push(small, 1e-3).unwrap();
    }
    assert_eq!(p.steps(), 5);
    let angle = p.attitude().angle_to(Quat::IDENTITY);
    let want = 10.0 * small.angle.norm();
    assert!((angle - want).abs() < 1e-12, "{angle} vs {want}");
}
