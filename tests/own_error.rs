//! The float-float accumulator's own error over 10⁶ steps (issue "an f32 attitude whose only error is its
//! inputs", item 5): an f32 propagator (ExpMap + FirstOrder + `FloatFloat`) against an f64 shadow fed the
//! same f32 samples and the same f32 `dt`s, at 1 kHz, on a constant rate and on coning at a frequency
//! incommensurate with the sample rate. The 10⁸-step runs are the lab's (docs/report, "Long horizon").
//!
//! The bound, derived (u = 2⁻²⁴, the unit roundoff of f32; θ the largest half step angle):
//! - the f32 attitude is the high part `q` of `q + l`: each component within half an ulp (≤ u for
//!   components below 1) of the float-float value, so its direction is off by at most `2·2u·√4/2 = 4u`;
//! - per step, what rounds in f32: the low-order terms `q ⊗ lo + l ⊗ hi + (Dot2's low parts)`, each of size
//!   ≤ 2uθ, summed with at most 5 roundings: ≤ 5u·(3·2uθ) = 30u²θ; and `q·(cos θ − 1)`, ≤ θ²/2 per
//!   component, rounded plainly: ≤ u·θ² (mostly radial, counted whole);
//! - the sample history's correction `(9Δ₃ + 4Δ₂ − Δ₁)/24` (differences of samples) is rounded plainly
//!   (3 roundings of terms up to 14/24·max|Δω|) before its TwoSum with `ω_k`: ≤ 3u·(14/24)·max|Δω|·hh per
//!   step;
//! - the shadow's own error (f64, Kahan-compensated) and the truncation differences of the f32 and f64
//!   series are below 10⁻¹² here.
//!
//! Summed linearly over N steps (no credit for cancellation). `Kahan` (2.6e-5 rad on the constant rate)
//! and `Plain` fail this bound by orders of magnitude.

use quatprop::accumulate::{Accumulator, FloatFloat, Kahan};
use quatprop::frontend::FixedPeriod;
use quatprop::input::{History, Hold, InputModel, Linear};
use quatprop::scheme::ExpMap;
use quatprop::stabilize::FirstOrder;
use quatprop::{GyroSample, Propagator, Quat, Vec3};

const STEPS: u64 = 1_000_000;

#[derive(Clone, Copy, Debug)]
enum Motion {
    Constant,
    Coning,
}

/// The body rate (rad/s) at sample k (t = k·0.001 s).
fn rate(m: Motion, k: u64) -> Vec3<f64> {
    match m {
        Motion::Constant => Vec3::new(0.36, -0.48, 0.80),
        Motion::Coning => {
            let (alpha, o) = (
                0.3_f64,
                2.0 * core::f64::consts::PI / core::f64::consts::SQRT_2,
            );
            let (s, c) = (o * k as f64 * 1e-3).sin_cos();
            let s2 = (0.5 * alpha).sin();
            Vec3::new(
                -o * alpha.sin() * s,
                o * alpha.sin() * c,
                -2.0 * o * s2 * s2,
            )
        }
    }
}

// The f32 propagator against its f64 shadow is also examples/own_error.rs's `run`: spelled out in both, as
// the example stands alone for users to copy and this test measures its own bound's terms as it goes.
/// Own error of an f32 state adding with `acc` after `STEPS` steps, and the bound's per-step history term
/// `max|Δω|` (rad/s).
fn own_error<I32, I64, A>(m: Motion, i32: I32, i64: I64, acc: A) -> (f64, f64)
where
    I32: InputModel<f32, Sample = GyroSample<f32>>,
    I64: InputModel<f64, Sample = GyroSample<f64>>,
    A: Accumulator<f32>,
{
    let mut p32 = Propagator::new(Quat::IDENTITY, ExpMap, i32, FirstOrder)
        .unwrap()
        .with_accumulator(acc);
    let mut p64 = Propagator::new(Quat::IDENTITY, ExpMap, i64, FirstOrder)
        .unwrap()
        .with_accumulator(Kahan::new());
    let mut period = FixedPeriod::<f32>::new(1e-3).unwrap();
    let mut previous = Vec3::<f32>::from_f64(rate(m, 0));
    p32.start(GyroSample::new(previous)).unwrap();
    p64.start(GyroSample::new(previous.to_f64())).unwrap();
    let mut max_change = 0.0_f64;
    for k in 1..=STEPS {
        let w = Vec3::<f32>::from_f64(rate(m, k));
        let dt = period.next_dt();
        p32.push(GyroSample::new(w), dt).unwrap();
        p64.push(GyroSample::new(w.to_f64()), f64::from(dt))
            .unwrap();
        max_change = max_change.max((w.to_f64() - previous.to_f64()).norm());
        previous = w;
    }
    let (a, b) = (p32.attitude().to_f64(), p64.attitude());
    (
        a.normalized().unwrap().angle_to(b.normalized().unwrap()),
        max_change,
    )
}

fn check<I32, I64>(m: Motion, name: &str, i32: I32, i64: I64, history: bool)
where
    I32: InputModel<f32, Sample = GyroSample<f32>>,
    I64: InputModel<f64, Sample = GyroSample<f64>>,
{
    let (err, max_change) = own_error(m, i32, i64, FloatFloat::new());
    let u = f64::from(f32::EPSILON) / 2.0;
    let hh = 0.5e-3;
    let theta = (0..=1000u64)
        .map(|k| rate(m, k * 997).norm() * hh * (1.0 + 1e-3))
        .fold(0.0, f64::max);
    let per_step = 30.0 * u * u * theta
        + u * theta * theta
        + if history {
            3.0 * u * (14.0 / 24.0) * max_change * hh
        } else {
            0.0
        };
    let bound = 4.0 * u + STEPS as f64 * per_step;
    println!("{m:?} {name}: own error {err:.3e} rad, bound {bound:.3e}");
    assert!(err <= bound, "{m:?} {name}: own error {err:e} > {bound:e}");
}

#[test]
fn float_float_f32_own_error_stays_at_its_inputs_over_1e6_steps() {
    for m in [Motion::Constant, Motion::Coning] {
        check(m, "Hold", Hold, Hold, false);
        check(m, "Linear", Linear::new(), Linear::new(), false);
        check(m, "History", History::new(), History::new(), true);
    }
}

/// The same measure separates the accumulators: Kahan's own error on the constant rate after 10⁶ steps is
/// orders above the float-float bound (so the bound above is not one any f32 state meets).
#[test]
fn kahan_f32_own_error_on_a_constant_rate_exceeds_the_float_float_bound() {
    let (err, _) = own_error(Motion::Constant, Hold, Hold, Kahan::new());
    let u = f64::from(f32::EPSILON) / 2.0;
    assert!(err > 100.0 * 4.0 * u, "Kahan own error {err:e}");
}
