//! Issue "beyond the peers", item 1: fourth order from one gyro sample per step, no latency
//! (`input::History`). Coning α = 0.3 rad at 1 Hz (the notes' figures: trapezoid exponential map 3.6e-4 rad
//! after 1 s at 100 steps/s; the sample-history update 2.3e-7, order 4.00).

mod support;

use quatprop::input::{History, Hold};
use quatprop::scheme::{ExpMap, SchemeKind};
use quatprop::stabilize::Off;
use quatprop::{GyroSample, Propagator, Vec3};
use support::{assert_history_is_fourth_order, coning_error, convergence, Coning, Input};

#[test]
fn sample_history_reaches_order_four_with_one_sample_per_step() {
    // The notes' reference point: 1 s, 100 steps per second. Their "trapezoid exponential map" is
    // exp(h(ω₀ + ω₁)/2) (PX4, glam); quatprop's linear ExpMap adds the commutator term and halves that error.
    let c = Coning::STANDARD;
    let mut bare = Propagator::new(c.attitude(0.0), ExpMap, Hold, Off).unwrap();
    for i in 0..100 {
        let (w0, w1) = (c.rate(i as f64 * 0.01), c.rate((i + 1) as f64 * 0.01));
        bare.push(GyroSample::new((w0 + w1) * 0.5), 0.01).unwrap();
    }
    let bare = bare.attitude().angle_to(c.attitude(1.0));
    let linear = coning_error(SchemeKind::ExpMap, Input::Linear, 100, 1.0);
    let hist = coning_error(SchemeKind::ExpMap, Input::History, 100, 1.0);
    println!(
        "1 s at 100 Hz: trapezoid exp map {bare:.2e} rad, with commutator {linear:.2e}, sample history {hist:.2e}"
    );
    assert!((bare / 3.6e-4 - 1.0).abs() < 0.05, "{bare:e}");
    assert!((hist / 2.3e-7 - 1.0).abs() < 0.05, "{hist:e}");
    assert!(hist < linear / 500.0);
    assert_history_is_fourth_order(&[SchemeKind::ExpMap, SchemeKind::Rk4], &[50, 100, 200, 400]);
}

#[test]
fn start_up_orders_and_cold_start() {
    // Cold start: the first sample only starts the history, the second step is linear, the third quadratic.
    let c = Coning::STANDARD;
    let mut p = Propagator::new(c.attitude(0.0), ExpMap, History::new(), Off).unwrap();
    let h = 0.01;
    assert!(p.input().is_empty());
    p.push(GyroSample::new(c.rate(0.0)), h).unwrap();
    assert_eq!(p.steps(), 0);
    assert_eq!(p.input().len(), 1);
    assert_eq!(
        p.attitude(),
        c.attitude(0.0),
        "a starting sample moves nothing"
    );
    for i in 1..=100 {
        p.push(GyroSample::new(c.rate(i as f64 * h)), h).unwrap();
        assert_eq!(p.input().len(), (i + 1).min(3));
    }
    assert_eq!(p.steps(), 100);
    let e = p.attitude().angle_to(c.attitude(1.0));
    // The two low-order start-up steps cost ~h³ each; still far below the trapezoid's 3.6e-4.
    assert!(e < 1e-5, "{e:e}");
    // A refused sample leaves the propagator, its history included, untouched.
    let before = p;
    assert!(p
        .push(GyroSample::new(Vec3::new(f64::NAN, 0.0, 0.0)), h)
        .is_err());
    assert_eq!(p, before);
    // restart_input forgets the history (after a gap): the next sample only starts it again.
    p.restart_input();
    assert!(p.input().is_empty());
    assert_eq!(p.attitude(), before.attitude());
    p.push(GyroSample::new(c.rate(5.0)), h).unwrap();
    assert_eq!((p.steps(), p.input().len()), (100, 1));
}

/// Attitude error at 0.7 s of coning, n steps, with the history cold-started at t = 0 and the samples
/// listed by `skip` refused (a NaN pushed in their place: the next sample then carries the refused
/// interval, as the README's loop does).
fn cold(n: usize, refuse: &[f64]) -> f64 {
    let c = Coning::STANDARD;
    let h = 0.7 / n as f64;
    let mut p = Propagator::new(c.attitude(0.0), ExpMap, History::new(), Off).unwrap();
    let mut dt = h;
    for i in 0..=n {
        let t = i as f64 * h;
        if refuse.iter().any(|&r| (t - r).abs() < 0.5 * h) {
            let nan = GyroSample::new(Vec3::new(f64::NAN, 0.0, 0.0));
            assert!(p.push(nan, dt).is_err());
            dt += h;
            continue;
        }
        p.push(GyroSample::new(c.rate(t)), dt).unwrap();
        dt = h;
    }
    p.attitude().angle_to(c.attitude(0.7))
}

#[test]
fn a_cold_start_is_fourth_order_over_the_horizon() {
    // The first step is linear (local error O(h³)); the quadratic step after it carries the correction,
    // so the horizon's error falls as h⁴ like the primed history's (0.2 fell as h³: slope 3.0).
    let ns = [50usize, 100, 200, 400];
    let (es, slope) = convergence(0.7, &ns, |n| cold(n, &[]));
    println!("cold-started history: errors {es:?}, order {slope:.3}");
    assert!((slope - 4.0).abs() < 0.1, "order {slope}");
    // Within a factor of the primed history's error (which has no start-up at all).
    for (&n, &e) in ns.iter().zip(&es) {
        let primed = coning_error(SchemeKind::ExpMap, Input::History, n, 0.7);
        assert!(e < 3.0 * primed, "n = {n}: {e:e} against primed {primed:e}");
    }
}

#[test]
fn a_refused_sample_keeps_the_fourth_order() {
    // A refused sample at t = 0.35 s: its interval goes into the next dt (2h), which the cubic spans at
    // the samples' true times (no restart: 2h is below History::GAP_RATIO).
    // From 100 steps on: at 50 the spanned 2h interval's higher-order term still shows (ratio 19.5 to
    // the next, then 17.8, 16.9, 16.5).
    let (es, slope) = convergence(0.7, &[100, 200, 400, 800], |n| cold(n, &[0.35]));
    println!("refused sample: errors {es:?}, order {slope:.3}");
    assert!((slope - 4.0).abs() < 0.1, "order {slope}");
}

#[test]
fn after_a_gap_the_history_is_fourth_order_again() {
    // Two refused samples in a row make a 3h interval: a gap (beyond History::GAP_RATIO), integrated
    // linearly over its true length (third order: nothing is known of ω inside it). What follows is a
    // fresh start: the rotation from the gap's end to the horizon converges at fourth order.
    let c = Coning::STANDARD;
    let (es, slope) = convergence(0.7, &[50, 100, 200, 400], |n| {
        let h = 0.7 / n as f64;
        let gap_end = n / 2;
        let mut p = Propagator::new(c.attitude(0.0), ExpMap, History::new(), Off).unwrap();
        for i in 0..=gap_end - 3 {
            p.push(GyroSample::new(c.rate(i as f64 * h)), h).unwrap();
        }
        let t_end_of_gap = gap_end as f64 * h;
        p.push(GyroSample::new(c.rate(t_end_of_gap)), 3.0 * h)
            .unwrap();
        assert_eq!(
            p.input().len(),
            2,
            "the gap restarts the history at its last sample"
        );
        let at_gap = p.attitude();
        for i in gap_end + 1..=n {
            p.push(GyroSample::new(c.rate(i as f64 * h)), h).unwrap();
        }
        // The rotation made after the gap against the motion's.
        let made = at_gap.conjugate() * p.attitude();
        let truth = c.attitude(t_end_of_gap).conjugate() * c.attitude(0.7);
        made.angle_to(truth)
    });
    println!("after a gap: errors {es:?}, order {slope:.3}");
    assert!((slope - 4.0).abs() < 0.1, "order {slope}");
}
