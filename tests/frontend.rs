//! The sensor front end and the burst paths: exact time, wraparound, refusals that leave the state as it
//! was, bursts bit for bit equal to one sample at a time (the bias estimator: tests/bias.rs).

use quatprop::accumulate::Kahan;
use quatprop::frontend::{BiasEstimator, CountScale, FixedPeriod, TickClock};
use quatprop::input::{GaussPoints, History, Hold, InputModel, Linear, TwiceRate};
use quatprop::scheme::{ExpMap, Rk4};
use quatprop::stabilize::FirstOrder;
use quatprop::{Error, GyroSample, Propagator, Quat, Refused, Vec3};

/// A deterministic coning-like rate stream with a few bad samples.
fn stream(n: usize, bad: &[usize]) -> Vec<GyroSample<f32>> {
    (0..n)
        .map(|k| {
            let t = k as f32 * 1e-3;
            let mut s = GyroSample::new(Vec3::new(
                0.9 * (7.1 * t).sin(),
                0.9 * (7.1 * t).cos(),
                -0.3,
            ));
            if bad.contains(&k) {
                s.rate.x = f32::NAN;
            }
            s.saturated = k % 97 == 0;
            s
        })
        .collect()
}

/// `push_burst` over refusals equals pushing one at a time with the same time base, bit for bit.
fn burst_equals_one_at_a_time<
    I: InputModel<f32, Sample = GyroSample<f32>> + PartialEq + core::fmt::Debug,
>(
    input: I,
) {
    let samples = stream(3000, &[17, 18, 1500, 2999]);
    let mut a = Propagator::new(Quat::IDENTITY, ExpMap, input, FirstOrder).unwrap();
    let mut b = a;
    let (mut pa, mut pb) = (
        FixedPeriod::new(1e-3).unwrap(),
        FixedPeriod::new(1e-3).unwrap(),
    );
    // a: bursts of 32, resumed after each refusal.
    let mut refusals = 0;
    for chunk in samples.chunks(32) {
        let mut rest = chunk;
        while let Err(Refused { index, error }) = a.push_burst(rest, &mut pa) {
            assert_eq!(error, Error::NonFiniteRate);
            refusals += 1;
            rest = rest.get(index + 1..).unwrap_or(&[]);
        }
    }
    // b: one at a time.
    for s in &samples {
        let dt = pb.next_dt();
        if b.push(*s, dt).is_err() {
            pb.carry_over(dt);
        }
    }
    assert_eq!(refusals, 4);
    assert_eq!(a, b);
    assert_eq!(a.saturated_samples(), b.saturated_samples());
    assert_eq!(
        a.saturated_samples(),
        (0..3000).filter(|k| k % 97 == 0).count() as u64
    );
}

#[test]
fn bursts_equal_one_sample_at_a_time_on_every_rate_input() {
    burst_equals_one_at_a_time(Hold);
    burst_equals_one_at_a_time(Linear::new());
    burst_equals_one_at_a_time(History::new());
    burst_equals_one_at_a_time(TwiceRate::new());
    burst_equals_one_at_a_time(GaussPoints::new());
}

#[test]
fn no_interval_is_lost_across_refusals() {
    // Constant rate: the attitude depends only on the total time integrated, which must be the full span.
    let w = GyroSample::new(Vec3::new(0.0, 0.0, 1.0_f64));
    let mut samples = vec![w; 1001];
    for k in [3, 4, 5, 500, 999] {
        samples[k].rate.z = f64::NAN;
    }
    let mut p = Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder).unwrap();
    let mut period = FixedPeriod::new(1e-3).unwrap();
    let mut rest = &samples[..];
    while let Err(r) = p.push_burst(rest, &mut period) {
        rest = rest.get(r.index + 1..).unwrap_or(&[]);
    }
    let yaw = 2.0 * p.attitude().z.atan2(p.attitude().w);
    // 1000 intervals after the first sample; f64 rounding over 1000 steps is far below 1e-12.
    assert!((yaw - 1.0).abs() < 1e-12, "{yaw}");
}

#[test]
fn fixed_period_sums_exactly_and_the_naive_period_does_not() {
    for period in [1e-3, 1.0 / 1600.0, 1.0 / 3.0e3, 2.5e-4] {
        let mut p = FixedPeriod::<f32>::new(period).unwrap();
        let mut sum = 0.0_f64; // each f32 dt is exact in f64, and 1e6 of them sum exactly in f64 here
        let n = 1_000_000;
        for _ in 0..n {
            sum += f64::from(p.next_dt());
        }
        let exact = n as f64 * period;
        // Within half an ulp of one dt (f32: 2^-24 relative) plus the f64 summation's rounding.
        let bound = 0.5 * f64::from(f32::EPSILON) * period + 1e6 * f64::EPSILON * exact;
        assert!(
            (sum - exact).abs() <= bound,
            "{period}: {:e} > {bound:e}",
            sum - exact
        );
    }
    assert_eq!(FixedPeriod::<f32>::new(0.0), Err(Error::NonPositiveStep));
    assert_eq!(FixedPeriod::<f32>::new(-1e-3), Err(Error::NonPositiveStep));
    assert_eq!(FixedPeriod::<f32>::new(f64::NAN), Err(Error::NonFiniteStep));
    assert_eq!(FixedPeriod::<f32>::new(1e-60), Err(Error::NonPositiveStep)); // underflows f32
}

/// A run of `n` refused samples (each `dt` given back with `carry_over`), then one accepted sample covering
/// them all and `m` more: the `dt`s handed out sum to `(n + 1 + m)` periods within half an ulp of the long
/// `dt` (its remainder, spread over the following samples, may be partly unpaid) plus the rounding of the
/// carried remainder at each of the `n + 1` long steps (≤ ulp of a remainder of ≤ ½ulp(dt_k) ≤ ε·k·period:
/// in all ε²·n²·period), and every `dt` after it is at least ⅞ of the period.
/// Before the fix a run of 1000 lost 80 ulps of the long `dt`, and 2²⁰ lost 10 s of 1048 s.
#[test]
fn fixed_period_keeps_time_over_a_long_run_of_refused_samples() {
    let period = 1e-3;
    for n in [1_u64, 10, 1000, 1 << 20, 1 << 25] {
        let mut p = FixedPeriod::<f32>::new(period).unwrap();
        for _ in 0..n {
            let dt = p.next_dt();
            p.carry_over(dt);
        }
        let long = f64::from(p.next_dt());
        let mut sum = long;
        let m = 10_000;
        for _ in 0..m {
            let dt = f64::from(p.next_dt());
            assert!(dt >= 0.875 * period * (1.0 - 1e-6), "n {n}: dt {dt:e}");
            sum += dt;
        }
        let eps = f64::from(f32::EPSILON) / 2.0;
        let exact = (n + 1 + m) as f64 * period;
        let ulp_long = 2.0 * eps * long.abs();
        let bound = 0.5 * ulp_long + eps * eps * (n as f64).powi(2) * period + 1e-15 * exact;
        let err = (sum - exact).abs();
        assert!(err <= bound, "n {n}: off by {err:e} s > {bound:e}");
        // The long dt covers the run: n + 1 periods to within its own rounding.
        assert!(
            (long - (n + 1) as f64 * period).abs() <= ulp_long + bound,
            "n {n}: {long}"
        );
    }
}

#[test]
fn tick_clock_wraps_refuses_and_counts_gaps() {
    // A 16-bit counter at 32 kHz, 32 ticks per sample (a 1 kHz ODR), wrapping every 2.048 s.
    let mut clock = TickClock::<f32>::new(32_000.0, 16).unwrap();
    let mut t: u32 = 65_000;
    assert_eq!(clock.dt(t), Ok(None));
    let mut total = 0.0_f64;
    for _ in 0..100_000 {
        t = t.wrapping_add(32);
        total += f64::from(clock.dt(t & 0xFFFF).unwrap().unwrap());
    }
    let exact = 100_000.0 * 32.0 / 32_000.0;
    assert!((total - exact).abs() < 1e-9, "{:e}", total - exact);
    assert_eq!(clock.gaps(), 0);
    // Duplicate and backwards: refused, clock unchanged.
    let before = clock;
    assert_eq!(clock.dt(t & 0xFFFF), Err(Error::TimestampNotIncreasing));
    assert_eq!(
        clock.dt(t.wrapping_sub(5) & 0xFFFF),
        Err(Error::TimestampNotIncreasing)
    );
    assert_eq!(clock, before);
    // A dropped sample: 64 ticks, integrated over its true length and counted.
    t = t.wrapping_add(64);
    assert!((clock.dt(t & 0xFFFF).unwrap().unwrap() - 2e-3).abs() < 1e-10);
    assert_eq!(clock.gaps(), 1);
    assert_eq!(TickClock::<f32>::new(32_000.0, 0), Err(Error::InvalidClock));
    assert_eq!(
        TickClock::<f32>::new(32_000.0, 33),
        Err(Error::InvalidClock)
    );
    assert_eq!(TickClock::<f32>::new(0.0, 16), Err(Error::NonPositiveStep));
}

#[test]
fn timed_burst_equals_one_at_a_time_and_keeps_the_state_on_a_bad_timestamp() {
    let samples = stream(600, &[100]);
    let mut stamps: Vec<u32> = (0..600u32)
        .map(|k| 4_294_900_000u32.wrapping_add(k * 1000))
        .collect();
    stamps[300] = stamps[299]; // a duplicate
    let fifo: Vec<_> = samples
        .iter()
        .copied()
        .zip(stamps.iter().copied())
        .collect();
    let start = Propagator::new(Quat::IDENTITY, Rk4, History::new(), FirstOrder).unwrap();
    let mut a = start.with_accumulator(Kahan::new());
    let mut b = a;
    let mut ca = TickClock::<f32>::new(1e6, 32).unwrap();
    let mut cb = ca;
    let mut rest = &fifo[..];
    let mut refused = vec![];
    while let Err(r) = a.push_burst_timed(rest, &mut ca) {
        refused.push(r.error);
        rest = rest.get(r.index + 1..).unwrap_or(&[]);
    }
    assert_eq!(
        refused,
        [Error::NonFiniteRate, Error::TimestampNotIncreasing]
    );
    for (s, t) in &fifo {
        if let Ok((next, dt)) = cb.advance(*t) {
            match dt {
                None => {
                    b.push_burst_timed(&[(*s, *t)], &mut cb).unwrap();
                    continue;
                }
                Some(dt) => {
                    if b.push(*s, dt).is_ok() {
                        cb = next;
                    }
                }
            }
        }
    }
    // Equal to the path that commits the clock only with an accepted sample: so a refusal left both the
    // propagator and the clock as they were after the last accepted sample.
    assert_eq!(a, b);
    assert_eq!(ca, cb);
    assert_eq!(a.steps(), 600 - 2 - 1);
}

#[test]
fn counts_scale_per_full_scale_and_flag_the_rails() {
    for fs in [250.0, 500.0, 1000.0, 2000.0, 4000.0] {
        let s = CountScale::<f64>::full_scale_dps(fs).unwrap();
        let top = s.sample([32767, 0, 0]);
        assert!(top.saturated);
        assert!((top.rate.x - (fs * 32767.0 / 32768.0).to_radians()).abs() < 1e-12);
        let inside = s.sample([32766, -32767, 1]);
        assert!(!inside.saturated);
        assert!((inside.rate.y + (fs * 32767.0 / 32768.0).to_radians()).abs() < 1e-12);
        assert!(s.sample([0, -32768, 0]).saturated);
    }
    // The MPU-6050's printed sensitivities differ from 32768/FS by under 0.1 %: 131 vs 131.07.
    let printed = CountScale::<f64>::sensitivity(131.0)
        .unwrap()
        .rad_per_count();
    let spanned = CountScale::<f64>::full_scale_dps(250.0)
        .unwrap()
        .rad_per_count();
    assert!(((printed / spanned) - 32768.0 / 250.0 / 131.0).abs() < 1e-12);
}

#[test]
fn count_scales_that_are_not_finite_and_positive_are_refused() {
    for bad in [
        0.0,
        -0.0,
        -2000.0,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ] {
        assert_eq!(
            CountScale::<f32>::full_scale_dps(bad),
            Err(Error::InvalidScale),
            "{bad}"
        );
        assert_eq!(
            CountScale::<f64>::sensitivity(bad),
            Err(Error::InvalidScale),
            "{bad}"
        );
    }
    // Finite figures whose scale per count leaves the working precision's positive finite range.
    assert_eq!(
        CountScale::<f32>::full_scale_dps(1e-300),
        Err(Error::InvalidScale)
    );
    assert_eq!(
        CountScale::<f32>::sensitivity(1e-300),
        Err(Error::InvalidScale)
    );
    assert_eq!(
        CountScale::<f32>::sensitivity(1e50),
        Err(Error::InvalidScale)
    ); // underflows to 0
       // The same figures in f64 are representable: refused only where the scale itself is not.
    assert!(CountScale::<f64>::full_scale_dps(1e-300).is_ok());
}

#[test]
fn tick_clock_spreads_a_long_gaps_remainder_and_keeps_every_dt_positive() {
    // f32 at 1 MHz: a gap of 2^31 − 1 ticks (35.8 min, the longest a 32-bit counter allows) leaves a
    // carried remainder of up to half an ulp of its dt (ulp(2147 s) = 2.4e-4 s in f32: 122 ticks); then
    // short samples of 3 ticks. Each dt is within an eighth of its own interval, the sum of the dts never
    // strays from the exact time by more than the gap's own error, and once the carry is paid the sum is
    // exact to the documented rounding: 4ε²·dt per sample (1.2e-10 s for the gap's dt, ε = 2^-23).
    // The gap and the short dts are summed apart, so that the f64 sums' own rounding stays below 1e-15 s.
    let mut clock = TickClock::<f32>::new(1.0e6, 32).unwrap();
    assert_eq!(clock.dt(7), Ok(None));
    let gap_ticks: u32 = (1 << 31) - 1;
    let mut t: u32 = 7 + gap_ticks;
    let gap = f64::from(clock.dt(t).unwrap().unwrap());
    let gap_error = gap - f64::from(gap_ticks) * 1e-6;
    // The gap's own dt: exact to half an ulp of f32 at 2147 s (1.2e-4 s). Near 2^31 ticks f32 rounds the
    // count up to 2^31; its rounding error (−1 tick) is added back exactly.
    assert!(gap_error.abs() <= 0.5 * 2.441_406_25e-4, "{gap_error:e}");
    let rounding = 4.0 * f64::from(f32::EPSILON).powi(2) * gap;
    let mut short = 0.0_f64;
    for k in 1..=1000_u32 {
        t += 3;
        let dt = f64::from(clock.dt(t).unwrap().unwrap());
        assert!(
            // ⅛ of the interval, plus half an ulp of the carry it is split from (≤ 1.2e-4 s: 3.6e-12 s).
            (dt - 3e-6).abs() <= 3e-6 / 8.0 + 1e-11,
            "sample {k}: dt = {dt:e} for 3 ticks"
        );
        short += dt;
        let err = gap_error + (short - f64::from(3 * k) * 1e-6);
        assert!(
            err.abs() <= gap_error.abs() + 2.0 * rounding,
            "sample {k}: {err:e}, the gap's dt was off by {gap_error:e}"
        );
    }
    // 3/8 µs paid per sample: a carry up to 122 µs is paid after 326 samples.
    let err = gap_error + (short - 3000.0 * 1e-6);
    assert!(
        err.abs() <= rounding + 1e-15 * 1000.0,
        "after the carry was paid: {err:e} > {rounding:e}"
    );
    // The long interval was the first one (nothing to compare it with) and the short ones are shorter:
    // no gap counted.
    assert_eq!(clock.gaps(), 0);
}

#[test]
fn tick_clock_in_steady_operation_gives_the_rounded_period_plus_its_own_remainder() {
    // The spreading never acts in steady operation (the remainder is half an ulp of a dt like the next):
    // 1 kHz samples of a 1 MHz clock give dts that differ from f32(1e-3) by at most one ulp of it.
    let mut clock = TickClock::<f32>::new(1.0e6, 32).unwrap();
    assert_eq!(clock.dt(0), Ok(None));
    let ulp = 2f64.powi(-33); // the spacing of f32 at 1e-3 (in [2^-10, 2^-9)): 1.16e-10 s
    for k in 1..=10_000u32 {
        let dt = clock.dt(k * 1000).unwrap().unwrap();
        assert!(
            (f64::from(dt) - f64::from(1e-3_f32)).abs() <= ulp,
            "{k}: {dt:e}"
        );
    }
}

#[test]
fn front_end_constructors_refuse_bad_values_with_typed_errors() {
    use quatprop::frontend::FixedBias;
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert_eq!(
            FixedBias::new(Vec3::new(0.0, bad, 0.0)),
            Err(Error::NonFiniteRate)
        );
        let est = BiasEstimator::<f32>::new(0.01, 1.0e-3, 0.05).unwrap();
        assert_eq!(
            est.with_initial(Vec3::new(bad, 0.0, 0.0), 1e-3),
            Err(Error::NonFiniteRate)
        );
        assert_eq!(
            BiasEstimator::<f32>::from_samples(10, 1e-3, bad),
            Err(Error::InvalidEstimator)
        );
        assert_eq!(est.with_drift(bad), Err(Error::InvalidEstimator));
    }
    assert_eq!(
        BiasEstimator::<f32>::from_samples(10, 0.0, 0.05),
        Err(Error::InvalidEstimator)
    );
    assert_eq!(
        BiasEstimator::<f32>::from_samples(10, 1e-3, 0.0),
        Err(Error::InvalidEstimator)
    );
    // A tick too long to split exactly (beyond f32::MAX / 2^27 s) and one that underflows f32.
    assert_eq!(TickClock::<f32>::new(1e-35, 32), Err(Error::NonFiniteStep));
    assert_eq!(TickClock::<f32>::new(1e60, 32), Err(Error::NonPositiveStep));
    assert_eq!(
        TickClock::<f32>::new(f64::INFINITY, 32),
        Err(Error::NonFiniteStep)
    );
}
