//! Issue "beyond the peers", item 1: fourth order from one gyro sample per step, no latency.
//! Coning α = 0.3 rad at 1 Hz (the notes' figures: trapezoid exponential map 3.6e-4 rad after 1 s at 100
//! steps/s; the sample-history update 2.3e-7, order 4.00).

mod support;

use quatprop::scheme::{ExpMap, Method};
use quatprop::stabilize::Off;
use quatprop::{Propagator, SampleHistory, Vec3};
use support::{loglog_slope, Coning};

/// Attitude error after `t_end` with one sample per step: history-based or trapezoid (linear).
fn error(m: Method, history: bool, n: usize, t_end: f64) -> f64 {
    let c = Coning::STANDARD;
    let h = t_end / n as f64;
    let mut p = Propagator::new(c.attitude(0.0), m, Off).unwrap();
    if history {
        // Samples before t = 0 exist for a running gyro: start the history three samples early, so every step
        // in [0, t_end] is a full fourth-order step. (Starting cold costs the first two steps' lower order.)
        let mut hist = SampleHistory::new();
        for i in -3i64..=0 {
            hist.push(c.rate(i as f64 * h));
        }
        for i in 1..=n {
            p.step_history(&mut hist, c.rate(i as f64 * h), h).unwrap();
        }
    } else {
        for i in 0..n {
            p.step_linear(c.rate(i as f64 * h), c.rate((i + 1) as f64 * h), h)
                .unwrap();
        }
    }
    p.attitude()
        .normalized()
        .unwrap()
        .angle_to(c.attitude(t_end))
}

#[test]
fn sample_history_reaches_order_four_with_one_sample_per_step() {
    // The notes' reference point: 1 s, 100 steps per second. Their "trapezoid exponential map" is
    // exp(h(ω₀ + ω₁)/2) (PX4, glam); quatprop's linear ExpMap adds the commutator term and halves that error.
    let c = Coning::STANDARD;
    let mut bare = Propagator::new(c.attitude(0.0), ExpMap, Off).unwrap();
    for i in 0..100 {
        let (w0, w1) = (c.rate(i as f64 * 0.01), c.rate((i + 1) as f64 * 0.01));
        bare.step_hold((w0 + w1) * 0.5, 0.01).unwrap();
    }
    let bare = bare.attitude().angle_to(c.attitude(1.0));
    let linear = error(Method::ExpMap, false, 100, 1.0);
    let hist = error(Method::ExpMap, true, 100, 1.0);
    println!(
        "1 s at 100 Hz: trapezoid exp map {bare:.2e} rad, with commutator {linear:.2e}, sample history {hist:.2e}"
    );
    assert!((bare / 3.6e-4 - 1.0).abs() < 0.05, "{bare:e}");
    assert!((hist / 2.3e-7 - 1.0).abs() < 0.05, "{hist:e}");
    assert!(hist < linear / 500.0);
    for m in [Method::ExpMap, Method::Rk4] {
        let ns = [50usize, 100, 200, 400];
        let hs: Vec<f64> = ns.iter().map(|&n| 0.7 / n as f64).collect();
        let es: Vec<f64> = ns.iter().map(|&n| error(m, true, n, 0.7)).collect();
        let slope = loglog_slope(&hs, &es);
        println!("{m:?} with sample history: errors {es:?}, order {slope:.3}");
        assert!((slope - 4.0).abs() < 0.15, "{m:?}: order {slope}");
    }
}

#[test]
fn start_up_orders_and_cold_start() {
    // Cold start: the first sample only starts the history, the second step is linear, the third quadratic.
    let c = Coning::STANDARD;
    let mut p = Propagator::new(c.attitude(0.0), ExpMap, Off).unwrap();
    let mut hist = SampleHistory::new();
    let h = 0.01;
    p.step_history(&mut hist, c.rate(0.0), h).unwrap();
    assert_eq!(p.steps(), 0);
    assert_eq!(hist.len(), 1);
    for i in 1..=100 {
        p.step_history(&mut hist, c.rate(i as f64 * h), h).unwrap();
    }
    assert_eq!(p.steps(), 100);
    assert_eq!(hist.len(), 3);
    let e = p.attitude().angle_to(c.attitude(1.0));
    // The two low-order start-up steps cost ~h³ each; still far below the trapezoid's 3.6e-4.
    assert!(e < 1e-5, "{e:e}");
    // A refused sample leaves the history untouched.
    let before = hist;
    assert!(p
        .step_history(&mut hist, Vec3::new(f64::NAN, 0.0, 0.0), h)
        .is_err());
    assert_eq!(hist, before);
}
