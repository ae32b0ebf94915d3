//! Library bugs the fuzz targets found, each pinned by a test of its own (docs/fuzzing.md lists them). The
//! fuzz targets' seed corpora and crash inputs are replayed by the `quatprop-fuzz-checks` crate's own tests
//! (`cd fuzz && cargo test -p quatprop-fuzz-checks`), next to the files they read.

/// Found by `conversions` (f32 and f64): the axis of a rotation by an angle whose reciprocal overflows.
#[test]
fn axis_angle_of_a_subnormal_rotation_has_a_unit_axis() {
    use quatprop::{Quat, Vec3};
    // A rotation by 2e-39 rad about x (f32), and by 2e-309 rad (f64).
    let (axis, angle) = Quat::new(1.0_f32, 1e-39, 0.0, 0.0).to_axis_angle();
    assert!(angle > 0.0);
    assert_eq!(axis, Vec3::new(1.0, 0.0, 0.0), "f32 axis");
    let (axis, angle) = Quat::new(1.0_f64, 1e-309, 0.0, 0.0).to_axis_angle();
    assert!(angle > 0.0);
    assert_eq!(axis, Vec3::new(1.0, 0.0, 0.0), "f64 axis");
}

/// Found by `frontend` (TickClock, f32, 32-bit counter): the documented exactness (the `dt`s sum to the
/// elapsed ticks times the period within half an ulp of one `dt`) fails after a gap beyond 2²⁴ ticks.
#[test]
fn tick_clock_f32_keeps_time_across_a_gap_beyond_2_24_ticks() {
    use quatprop::frontend::TickClock;
    let mut clock = TickClock::<f32>::new(1.0e6, 32).unwrap(); // 1 µs ticks
    assert_eq!(clock.dt(0), Ok(None));
    let mut t: u32 = (1 << 24) + 1; // a gap of 16.777217 s: f32 rounds the count to 2^24
    let mut total = f64::from(clock.dt(t).unwrap().unwrap());
    for _ in 0..1000 {
        t += 1000; // then 1 ms samples
        total += f64::from(clock.dt(t).unwrap().unwrap());
    }
    let exact = f64::from(t) * 1e-6;
    // Half an ulp of a 1 ms f32 dt is 5.8e-11 s (1e-9 leaves room for the carried roundings); one whole
    // tick (1e-6 s) is lost.
    assert!(
        (total - exact).abs() <= 1e-9,
        "sum of dts off by {:e} s",
        total - exact
    );
}

/// Found by `push` (f32, Rk2, TwiceRate, FirstOrder): `stabilize::FirstOrder` documented that applied every
/// step it keeps `|N| ≤ 4ε`; it does only while a step changes `|q|²` by less than about `√(4ε/3)`. A
/// Runge–Kutta step on a *varying* rate changes the norm at second order in the step angle (Rk2:
/// `−(h²/4)|(A₀ − A₁)q|²` with `A = ½Ω(ω)`), so one Rk2 step of only 0.07 rad (h·max|ω|) whose rate
/// reverses within the step leaves `|N| ≈ 39ε`. The documentation now states that condition and that a
/// larger change is reduced quadratically over the next steps: checked here.
#[test]
fn first_order_recovers_4_eps_after_a_large_norm_change() {
    use quatprop::input::TwiceRate;
    use quatprop::scheme::Rk2;
    use quatprop::stabilize::FirstOrder;
    use quatprop::{GyroSample, Propagator, Quat, Vec3};
    let q0 = Quat::new(-0.233649_f32, -0.49401748, 0.34334356, 0.6681963);
    let w0 = Vec3::new(-1.0964843_f32, 2.8126354, -1.7711017);
    let wm = Vec3::new(0.9641891_f32, -2.6333563, 2.094224);
    let w1 = Vec3::new(1.4413028_f32, -2.8954802, -1.3374751);
    let mut p = Propagator::new(q0, Rk2, TwiceRate::new(), FirstOrder).unwrap();
    assert!(p.norm_error().abs() <= f32::EPSILON);
    for w in [w0, wm, w1] {
        p.push(GyroSample::new(w), 0.01).unwrap(); // start, middle, end: one step of 0.02 s
    }
    assert_eq!(p.steps(), 1);
    // |w| = 3.5 rad/s over h = 0.02 s: a step angle of 0.07 rad, a norm change of ~2.5e-3.
    let big = p.norm_error().abs() / f32::EPSILON;
    assert!(
        big > 4.0,
        "|N| = {big} eps after the step (the counterexample)"
    );
    // The next step (no rotation) reduces it quadratically: −¾N² is far below ε.
    for _ in 0..2 {
        p.push(GyroSample::new(Vec3::new(0.0, 0.0, 0.0)), 0.01)
            .unwrap();
    }
    assert_eq!(p.steps(), 2);
    let n = p.norm_error().abs() / f32::EPSILON;
    assert!(n <= 4.0, "|N| = {n} eps one step later");
}

/// Found by `push` (f32, Rk2): the step-angle check compares `|ω·h|²` in `T` against the limit rounded to
/// `T`. `f32(2√2)` is below `2√2`, so a step of exactly `2√2` (ω = (2, 2, 0), h = 1: `|ω·h|² = 8` exactly)
/// is refused, and the error says `step_angle: 2.8284270763` "exceeds" `limit: 2.8284271247`.
#[test]
fn a_refused_step_angle_exceeds_the_limit_it_reports() {
    use quatprop::input::Hold;
    use quatprop::scheme::Rk2;
    use quatprop::stabilize::Off;
    use quatprop::{Error, GyroSample, Propagator, Quat, Vec3};
    let mut p = Propagator::new(Quat::<f32>::IDENTITY, Rk2, Hold, Off).unwrap();
    match p.push(GyroSample::new(Vec3::new(2.0_f32, 2.0, 0.0)), 1.0) {
        Ok(()) => {}
        Err(Error::StepAngleBeyondStability { step_angle, limit }) => {
            assert!(
                step_angle > limit,
                "refused: step angle {step_angle} <= limit {limit}"
            )
        }
        Err(e) => panic!("{e:?}"),
    }
}

/// Found by `frontend` (TickClock, f64, a period of 1.4e303 s): `TickClock::new` accepts any period that
/// fits in `T`, but `advance` splits it (Veltkamp, inside Dekker's TwoProduct) with a factor 2^⌈p/2⌉ + 1
/// that overflows for a period beyond `T::MAX / 4097` (f32, 8.3e34 s) or `T::MAX / 134217729` (f64,
/// 1.3e300 s): `dt` is NaN, and so is the carry from then on. Absurd periods, but accepted ones.
#[test]
fn tick_clock_gives_a_finite_dt_for_a_huge_period() {
    use quatprop::frontend::TickClock;
    use quatprop::Error;
    // Fixed by refusing such a clock: a tick beyond T::MAX / 2^27 s cannot be split exactly.
    assert_eq!(TickClock::<f32>::new(1e-35, 32), Err(Error::NonFiniteStep));
    // A long but splittable tick still gives a finite, exact dt.
    let mut clock = TickClock::<f32>::new(1e-30, 32).unwrap(); // one tick every 1e30 s
    assert_eq!(clock.dt(0), Ok(None));
    let dt = clock.dt(1).unwrap().unwrap();
    assert!((dt - 1e30).abs() <= 1e30 * f32::EPSILON, "dt = {dt}");
}

/// Found by `frontend` (TickClock, f32): the carried remainder of a long interval's `dt` (up to half an
/// ulp of it: 2.4e-6 s for 40 s in f32) went whole into the next `dt`. After a gap of 40.8 s at 1 MHz, the
/// next sample one tick (1 µs) later got a *negative* `dt` (−7.5e-7 s), which the propagator refuses
/// (`NonPositiveStep`) although its timestamp advanced. Fixed: the carry goes into a `dt` only up to an
/// eighth of its interval, the rest is paid over the next samples.
#[test]
fn tick_clock_dt_is_positive_after_a_long_gap() {
    use quatprop::frontend::TickClock;
    let mut clock = TickClock::<f32>::new(1.0e6, 32).unwrap();
    assert_eq!(clock.dt(0), Ok(None));
    let gap = clock.dt(40_788_086).unwrap().unwrap();
    assert!((f64::from(gap) - 40.788086).abs() < 1e-5);
    let gap_error = f64::from(gap) - 40.788_086;
    let mut short = 0.0_f64; // summed apart from the gap: the f64 sums' own rounding stays below 1e-18 s
    let mut t = 40_788_086_u32;
    // 1-tick samples after the gap: each dt positive and within an eighth of 1 µs (to f32 rounding).
    for k in 1..=100_u32 {
        t += 1;
        let dt = clock.dt(t).unwrap().unwrap();
        assert!(
            (f64::from(dt) - 1e-6).abs() <= 1e-6 / 8.0 + 1e-12,
            "dt = {dt:e} s for one tick, {k} ticks after the gap"
        );
        short += f64::from(dt);
        // The carry only shrinks while it is spread: never beyond half an ulp of the gap's dt (1.9e-6 s).
        let err = gap_error + (short - f64::from(k) * 1e-6);
        assert!(
            err.abs() <= 0.5 * 3.814_697_3e-6,
            "{k}: sum off by {err:e} s"
        );
    }
    // 1.75 µs of carry at 1/8 µs per tick: paid after 14 ticks; 100 ticks later the sum is exact to the
    // documented rounding, 4ε²·dt per sample (2.3e-12 s for the gap's dt).
    let err = gap_error + (short - 100e-6);
    let bound = 4.0 * f64::from(f32::EPSILON).powi(2) * f64::from(gap) + 1e-15;
    assert!(
        err.abs() <= bound,
        "sum off by {err:e} s > {bound:e} after the carry was paid"
    );
}

/// Found by `push` (f32, Rk4, TwiceRate, Normalize, Kahan): `stabilize::Normalize` documented `|N| ≤ 4ε`
/// after every step; its derivation assumes the unnormalized `|q|²` near 1. A step that changes the norm by
/// a large factor (a quadratic rate overshooting between its samples, inside Rk4's step bound) leaves
/// `|N| = 7.7ε` with `Plain`, and with `Kahan` (which re-adds the low part lost in adding the large
/// increment *after* the normalization, unscaled) 21ε. The documentation now says so (4ε for a change of
/// `|q|²` within a factor of 2 with Plain, `(6 + 7(√F − 1)⁺)ε` for a factor `F`, tests/normalize.rs; with
/// Kahan 32ε in every case the fuzzers reached): checked here.
#[test]
fn normalize_stays_within_its_documented_bound_after_a_large_step() {
    use quatprop::accumulate::Kahan;
    use quatprop::input::TwiceRate;
    use quatprop::scheme::Rk4;
    use quatprop::stabilize::Normalize;
    use quatprop::{GyroSample, Propagator, Quat, Vec3};
    let q0 = Quat::new(-0.7268356_f32, -0.7902908, 0.5266356, -0.7859738);
    let rates = [
        Vec3::new(-11.64225_f32, -18.45121, 17.390251),
        Vec3::new(22.321976, 15.092447, 7.2358394),
        Vec3::new(-2.7438238, 27.715008, 1.6612602),
        Vec3::new(11.372024, -14.941289, -20.636011),
        Vec3::new(-16.787394, 7.0021753, 21.155684),
    ]; // |ω| = 27.9 rad/s, steps of 0.2 s: h·max|ω| = 5.58 rad, inside Rk4's 5.66
    let mut plain = Propagator::new(q0, Rk4, TwiceRate::new(), Normalize).unwrap();
    let mut kahan = plain.with_accumulator(Kahan::new());
    let mut worst = (0.0_f32, 0.0_f32);
    for w in rates {
        plain.push(GyroSample::new(w), 0.1).unwrap();
        kahan.push(GyroSample::new(w), 0.1).unwrap();
        worst.0 = worst.0.max(plain.norm_error().abs() / f32::EPSILON);
        worst.1 = worst.1.max(kahan.norm_error().abs() / f32::EPSILON);
    }
    assert!(
        worst.0 <= 32.0 && worst.1 <= 32.0,
        "|N| up to {} eps (Plain), {} eps (Kahan)",
        worst.0,
        worst.1
    );
}

/// Found by `frontend` (f64): with a gate as wide as the numbers (f64::MAX), a confirmed change whose two windows
/// (and temperatures) were near f64::MAX overflowed their mean, `(a + b)/2`, and the estimate became
/// infinite; such a window now teaches nothing, and the estimate stays finite. (Since the Kalman filter of
/// 0.3, a gate this wide makes the scatter at rest's floor, and so the windows' variance, saturate at
/// `f64::MAX`: every window agrees with the estimate and moves it by a gain of zero.)
#[test]
fn numbers_that_overflow_the_running_means_teach_nothing() {
    use quatprop::frontend::{Aux, BiasEstimator};
    use quatprop::{GyroSample, Vec3};
    let mut e = BiasEstimator::<f64>::from_samples(1, 1e-3, f64::MAX)
        .unwrap()
        .with_temperature_model(0.8)
        .unwrap();
    let aux = Aux {
        accel: None,
        temperature: Some(1.7e308),
    };
    for rate in [1.0, 1.5e308, 1.5e308, 1.5e308] {
        e.update_with(GyroSample::new(Vec3::new(rate, 0.0, 0.0)), aux)
            .unwrap();
        assert!(
            e.bias().is_finite() && e.bias_at(1.7e308).is_finite(),
            "{e:?}"
        );
    }
    assert_eq!(e.bias(), Vec3::new(1.0, 0.0, 0.0)); // no change was ever adopted
}

/// A sample whose corrected rate overflows (a huge sample minus a huge bias) is motion: it ends the still
/// window in `learn` as in 0.2's `update`. The `correct`/`learn` split ignored such a sample, so the window
/// went on and closed one sample late (fuzz/frontend, `fuzz/regressions/frontend/crash-52fd…`).
#[test]
fn an_overflowing_corrected_rate_ends_the_still_window() {
    use quatprop::frontend::BiasEstimator;
    use quatprop::{GyroSample, Vec3};
    let est = BiasEstimator::<f64>::from_samples(2, 1e-3, f64::MAX)
        .and_then(|e| e.with_initial(Vec3::new(0.0, -1e308, 0.0), 1.0))
        .unwrap();
    let mut a = est;
    // Still (d = 0), then d = 2e308 = ∞ (motion), then still again: a window of 2 must not close.
    a.update(GyroSample::new(Vec3::new(0.0, -1e308, 0.0)))
        .unwrap();
    let out = a
        .update(GyroSample::new(Vec3::new(0.0, 1e308, 0.0)))
        .unwrap();
    assert!(out.rate.y.is_infinite());
    a.update(GyroSample::new(Vec3::new(0.1, -1e308, 0.0)))
        .unwrap();
    assert_eq!(a.bias(), est.bias());
}

/// Found by `estimator` (f64): the process noise of a step with a huge rotation (a rate held over a long
/// interval, `|φ|` ≫ 1) had a negative attitude variance, −2.7e-20: `Qθθ`'s bias part `I/3 + c₄U²` lost
/// everything to cancellation on the axes across the rotation, where it is `2(x − sin x)/x³`. It is now
/// written `2c₂ I + c₄φφᵀ`, both terms non-negative and each accurate.
#[test]
fn attitude_noise_across_a_huge_rotation_is_accurate_and_non_negative() {
    use quatprop::error_state::{GyroNoise, Step};
    use quatprop::Vec3;
    let noise = GyroNoise::new(0.0, 1.0).unwrap(); // the bias walk alone
    for k in 3..=12 {
        let x = 10f64.powi(k);
        let (_, q) = Step::held_rate(Vec3::new(0.0, 0.0, x), 1.0, &noise)
            .unwrap()
            .matrices();
        let exact = 2.0 * (x - x.sin()) / (x * x * x);
        for v in [q[0][0], q[1][1]] {
            assert!(v >= 0.0);
            assert!(
                (v / exact - 1.0).abs() < 1e-14,
                "x = {x:e}: {v} against {exact}"
            );
        }
    }
}

/// Found by `estimator` (f64): a correction by a finite rotation whose |δθ|² overflows (1e160 rad) was
/// refused as beyond f32's 16384 rad, a limit f64 does not have (its step sine is libm's). f64 now takes
/// any finite angle there, through libm's hypot and sine, as `Quat::from_rotation_vector` does.
#[test]
fn an_f64_correction_takes_any_finite_angle() {
    use quatprop::{Propagator, Quat, Vec3};
    let d = Vec3::new(1e160, 0.0, 0.0);
    let mut p = Propagator::recommended(Quat::<f64>::IDENTITY).unwrap();
    p.rotate_body(d).unwrap();
    assert!(p.attitude().angle_to(Quat::from_rotation_vector(d)) < 1e-15);
    let mut r = Propagator::recommended(Quat::<f64>::IDENTITY).unwrap();
    r.rotate_reference(d).unwrap();
    assert_eq!(r.attitude(), p.attitude());
}

/// Found by `estimator` (f32) in a CI run: a step with `|φ|²` just above 8192² and `dt` = 1e30 s was refused
/// as `StepAngleBeyondStability { step_angle: 8192.0, limit: 8192.0 }`: the check compared `|φ|²` with
/// 8192², while the sine is given `√|φ|²`, which rounds to exactly 8192 and is within its range. The step
/// failed for its overflowing noise (`dt³`), which is `NonFiniteResult`; the check now compares the angle
/// it reports, so a reported angle always exceeds its limit. (Its first form, `!(angle <= limit)`, was
/// caught by the same target at once: a subnormal `|φ|²` has no f32 step-path root, NaN, and was reported
/// as an angle beyond the limit; `fuzz/regressions/estimator/crash-cee6…`.)
#[test]
fn a_step_at_the_sine_limit_is_refused_for_what_failed() {
    use quatprop::error_state::{GyroNoise, Step};
    use quatprop::{Error, Vec3};
    // |φ|² = 2²⁶ + 9, rounded to 2²⁶ + 8 in f32 (above 8192²); its square root rounds to 8192.
    let phi = Vec3::new(8192.0_f32, 3.0, 0.0);
    assert!(phi.norm_squared() > 8192.0 * 8192.0);
    let noise = GyroNoise::new(1e-3_f32, 1e-5).unwrap();
    assert_eq!(
        Step::held_rate(phi, 1e30, &noise),
        Err(Error::NonFiniteResult)
    );
    // A rotation whose |φ|² is subnormal, over the same interval: the noise overflowed, not the angle.
    assert_eq!(
        Step::held_rate(Vec3::new(1e-20_f32, 0.0, 0.0), 1e30, &noise),
        Err(Error::NonFiniteResult)
    );
    // The same angle over a sane interval is within the sine's range and gives a finite step.
    assert!(Step::held_rate(phi, 1e-3, &noise).is_ok());
    // One ulp of the angle beyond the limit is refused, with an angle above the limit.
    match Step::held_rate(Vec3::new(8192.001_f32, 0.0, 0.0), 1e-3, &noise) {
        Err(Error::StepAngleBeyondStability { step_angle, limit }) => {
            assert!(
                step_angle > limit && limit == 8192.0,
                "{step_angle} {limit}"
            )
        }
        other => panic!("{other:?}"),
    }
}

/// Found by `calibration` (f64: a period of 2.5e-305 s, a noise of 3.0e-3 rad/√s; in f32 a period of
/// 0.01 s and a noise of 1e13 rad/√s do the same): `CalibrationEstimator::with_motion_noise` checked that
/// the horizontal measurement variance `(noise / 0.01 °/s)² / period` fits in `T`, but not the vertical
/// one, 10⁴ times larger: it was infinite, so was every innovation variance's determinant, and the filter
/// never updated. Such figures are now refused as `InvalidEstimator`.
#[test]
fn a_calibration_estimator_it_accepts_has_a_finite_vertical_variance() {
    use quatprop::frontend::CalibrationEstimator;
    use quatprop::Error;
    let f64_case = CalibrationEstimator::<f64>::with_motion_noise(
        2.456433067008941e-305,
        0.0,
        0.0,
        3.0229989403903626e-3,
    );
    let f32_case = CalibrationEstimator::<f32>::with_motion_noise(0.01, 0.01, 0.0087, 1.0e13);
    let texts = [
        f64_case.map(|e| format!("{e:?}")),
        f32_case.map(|e| format!("{e:?}")),
    ];
    for text in texts {
        match text {
            Err(e) => assert_eq!(e, Error::InvalidEstimator),
            Ok(t) => assert!(!(t.contains("inf") || t.contains("NaN")), "{t}"),
        }
    }
}

/// Found by `calibration` (f64, a period of f64::MAX): `CalibrationEstimator::new` and `MotionBias::new`
/// accepted any finite positive period but computed the bias variance's growth per sample as
/// `10·10·period/100`, which overflows beyond 1.8e306 s: an infinite growth kept in the state, and in
/// `MotionBias`, after its first reading, an infinite covariance that stopped it learning. Such periods
/// are now refused as `InvalidEstimator`; whatever is accepted holds finite numbers.
#[test]
fn a_huge_period_gives_a_finite_bias_growth() {
    use quatprop::frontend::{CalibrationEstimator, MotionBias};
    use quatprop::{Quat, Vec3};
    let period = 1.0e307;
    let finite = |text: String| assert!(!(text.contains("inf") || text.contains("NaN")), "{text}");
    if let Ok(e) = CalibrationEstimator::<f64>::new(period, 0.01, 0.0087) {
        finite(format!("{e:?}"));
    }
    if let Ok(mut m) = MotionBias::<f64>::new(period) {
        // A body turning at 1 rad/s about x with a bias of 0.5 °/s: its readings every 10 ms.
        let mut q = Quat::<f64>::IDENTITY;
        for _ in 0..10 {
            let w = Vec3::new(1.0, 0.0, 0.0);
            q = (q * Quat::from_rotation_vector(w * 0.01))
                .normalized()
                .unwrap();
            let g = q.conjugate().rotate(Vec3::new(0.0, 0.0, 9.81));
            m.update(w + Vec3::new(0.5_f64.to_radians(), 0.0, 0.0), g, 0.01)
                .unwrap();
        }
        finite(format!("{m:?}"));
    }
}

/// Found by `frontend` (f64): a drift whose growth per period overflows (`drift² · period` beyond
/// `f64::MAX`, with `drift²` itself finite, as `with_drift` requires) made the variance's growth over
/// *zero* periods `∞ · 0 = NaN`, saturated to `T::MAX`: right after `with_initial(bias, σ)` the estimator
/// reported a variance of `f64::MAX` instead of `σ²`. No time now grows nothing.
#[test]
fn no_time_grows_no_variance_whatever_the_drift() {
    use quatprop::frontend::BiasEstimator;
    use quatprop::Vec3;
    let est = BiasEstimator::<f64>::new(20.0, 10.0, 0.05)
        .unwrap()
        .with_drift(1.0e154)
        .unwrap()
        .with_initial(Vec3::new(1e-3, -2e-3, 5e-4), 1e-3)
        .unwrap();
    assert_eq!(est.variance(), Vec3::new(1e-6, 1e-6, 1e-6));
}
