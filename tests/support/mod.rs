//! Exact reference motions and helpers shared by the integration tests.
#![allow(dead_code)]

use quatprop::input::coning::ConingKind;
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, InputModel, Linear, TwiceRate};
use quatprop::scheme::{Scheme, SchemeKind};
use quatprop::stabilize::{Off, Stabilizer};
use quatprop::{DeltaAngle, Error, GyroSample, Propagator, Quat, Real, Vec3};

/// `√3/6`: half the distance between the two Gauss–Legendre nodes on [0, 1] (typed here independently of the
/// crate, whose constant is private).
pub const GAUSS_HALF_GAP: f64 = 0.288_675_134_594_812_9;
/// The first Gauss–Legendre node `½ − √3/6` of a step.
pub const GAUSS_1: f64 = 0.5 - GAUSS_HALF_GAP;
/// The second Gauss–Legendre node `½ + √3/6` of a step.
pub const GAUSS_2: f64 = 0.5 + GAUSS_HALF_GAP;

/// Coning motion about z with half-angle `alpha` (rad) at frequency `big_omega` (rad/s), from the notes:
/// q(t) = (cos α/2, sin α/2 cos Ωt, sin α/2 sin Ωt, 0),
/// ω(t) = (−Ω sin α sin Ωt, Ω sin α cos Ωt, −2Ω sin²(α/2)) (body frame).
#[derive(Clone, Copy, Debug)]
pub struct Coning {
    pub alpha: f64,
    pub big_omega: f64,
}

impl Coning {
    pub const STANDARD: Coning = Coning {
        alpha: 0.3,
        big_omega: 2.0 * core::f64::consts::PI,
    };

    pub fn attitude(&self, t: f64) -> Quat<f64> {
        let (s, c) = (self.alpha / 2.0).sin_cos();
        let p = self.big_omega * t;
        Quat::new(c, s * p.cos(), s * p.sin(), 0.0)
    }

    pub fn rate(&self, t: f64) -> Vec3<f64> {
        let o = self.big_omega;
        let p = o * t;
        let sa = self.alpha.sin();
        let s2 = (self.alpha / 2.0).sin();
        Vec3::new(-o * sa * p.sin(), o * sa * p.cos(), -2.0 * o * s2 * s2)
    }
}

/// The rate input models, with the sampling schedule each one expects from a gyro.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// One sample per step, at its end, held over the step (`input::Hold`).
    Hold,
    /// One sample per step, linear between the step's two end samples (`input::Linear`).
    Linear,
    /// One sample per step, the cubic through the last four (`input::History`). Primed with the samples
    /// before t = 0 (a gyro that was already running), so every step of the run is a full cubic step.
    History,
    /// Two samples per step, at its middle and its end (`input::TwiceRate`, the 0.1 `step_mid`).
    TwiceRate,
    /// Two samples per step, at its Gauss–Legendre nodes (`input::GaussPoints`, the 0.1 `step_gauss`).
    GaussPoints,
}

impl Input {
    pub const ALL: [Input; 5] = [
        Input::Hold,
        Input::Linear,
        Input::History,
        Input::TwiceRate,
        Input::GaussPoints,
    ];

    /// The pushes `(sample time, dt)` made before the first step of `[0, h]`, from t ≤ 0.
    fn prelude(self, h: f64) -> Vec<(f64, f64)> {
        match self {
            Input::Hold | Input::GaussPoints => vec![],
            Input::Linear => vec![(0.0, h)],
            Input::TwiceRate => vec![(0.0, 0.5 * h)],
            Input::History => vec![(-2.0 * h, h), (-h, h), (0.0, h)],
        }
    }

    /// The pushes `(sample time, dt)` of the step `[t, t + h]`; the last one closes the step.
    fn pushes(self, t: f64, h: f64) -> Vec<(f64, f64)> {
        match self {
            Input::Hold | Input::Linear | Input::History => vec![(t + h, h)],
            Input::TwiceRate => vec![(t + 0.5 * h, 0.5 * h), (t + h, 0.5 * h)],
            Input::GaussPoints => vec![(t + GAUSS_1 * h, 0.5 * h), (t + GAUSS_2 * h, 0.5 * h)],
        }
    }
}

/// A check to run on each input model (see [`for_every_input_model`]).
pub trait InputModelCheck<T: Real> {
    /// Checks `input`, fed with `sample(v, saturated)`: the rate `v`, or for an angle-increment model the
    /// increment `v · 0.01 s` (a 100 Hz gyro).
    fn check<I>(&mut self, input: I, sample: fn(Vec3<T>, bool) -> I::Sample)
    where
        I: InputModel<T> + core::fmt::Debug + PartialEq;
}

/// Runs `check` on every input model: `Hold`, `Linear`, `History`, `TwiceRate` and `GaussPoints` with
/// rates, then `DeltaAngles` with each coning correction.
pub fn for_every_input_model<T: Real>(check: &mut impl InputModelCheck<T>) {
    fn rate<T>(rate: Vec3<T>, saturated: bool) -> GyroSample<T> {
        GyroSample { rate, saturated }
    }
    fn increment<T: Real>(rate: Vec3<T>, saturated: bool) -> DeltaAngle<T> {
        DeltaAngle {
            angle: rate * T::from_f64(0.01),
            saturated,
        }
    }
    check.check(Hold, rate);
    check.check(Linear::new(), rate);
    check.check(History::new(), rate);
    check.check(TwiceRate::new(), rate);
    check.check(GaussPoints::new(), rate);
    for c in ConingKind::ALL {
        check.check(DeltaAngles::new(c), increment);
    }
}

/// What a run ends with.
#[derive(Clone, Copy, Debug)]
pub struct Outcome<T> {
    /// The final attitude.
    pub q: Quat<T>,
    /// Steps taken (the History prelude's steps included).
    pub steps: u64,
}

/// What [`propagate`] runs: `n` steps of `input` over `[0, t_end]` from `q0`, sampling `rate`.
struct Run<'a> {
    input: Input,
    q0: Quat<f64>,
    rate: &'a dyn Fn(f64) -> Vec3<f64>,
    t_end: f64,
    n: usize,
}

fn drive<T: Real, S: Scheme<T>, I: InputModel<T, Sample = GyroSample<T>>, Z: Stabilizer>(
    mut p: Propagator<T, S, I, Z>,
    run: &Run,
) -> Result<Outcome<T>, Error> {
    let Run {
        input,
        q0,
        rate,
        t_end,
        n,
    } = *run;
    let h = t_end / n as f64;
    let push = |p: &mut Propagator<T, S, I, Z>, (t, dt): (f64, f64)| {
        p.push(
            GyroSample::new(Vec3::<T>::from_f64(rate(t))),
            T::from_f64(dt),
        )
    };
    for s in input.prelude(h) {
        push(&mut p, s)?;
    }
    if input == Input::History {
        // The prelude's two steps moved the attitude over [−2h, 0] with low-order start-up steps; the
        // samples they left in the history are what matters. Start the run from the exact attitude.
        p.set_attitude(Quat::<T>::from_f64(q0))?;
    }
    for i in 0..n {
        for s in input.pushes(i as f64 * h, h) {
            push(&mut p, s)?;
        }
    }
    Ok(Outcome {
        q: p.attitude(),
        steps: p.steps(),
    })
}

/// Propagates from `q0` over `[0, t_end]` in `n` steps of `input`, sampling `rate`, in precision `T`.
pub fn propagate<T: Real, S: Scheme<T>, Z: Stabilizer>(
    scheme: S,
    stabilizer: Z,
    input: Input,
    q0: Quat<f64>,
    rate: &dyn Fn(f64) -> Vec3<f64>,
    t_end: f64,
    n: usize,
) -> Result<Outcome<T>, Error> {
    let q = Quat::<T>::from_f64(q0);
    let run = Run {
        input,
        q0,
        rate,
        t_end,
        n,
    };
    // One propagator type per input model: each arm drives its own.
    macro_rules! drive_with {
        ($model:expr) => {
            drive(Propagator::new(q, scheme, $model, stabilizer)?, &run)
        };
    }
    match input {
        Input::Hold => drive_with!(Hold),
        Input::Linear => drive_with!(Linear::new()),
        Input::History => drive_with!(History::new()),
        Input::TwiceRate => drive_with!(TwiceRate::new()),
        Input::GaussPoints => drive_with!(GaussPoints::new()),
    }
}

/// One `#[test]` per precision for a check generic over [`Real`]: `tests_in_f32_and_f64!(check => a, b)`
/// defines the test `a` running `check::<f32>()` and the test `b` running `check::<f64>()`.
#[allow(unused_macros)] // As for `dead_code` above: not every test file uses it.
macro_rules! tests_in_f32_and_f64 {
    ($check:ident => $f32_test:ident, $f64_test:ident) => {
        #[test]
        fn $f32_test() {
            $check::<f32>();
        }

        #[test]
        fn $f64_test() {
            $check::<f64>();
        }
    };
}
#[allow(unused_imports)]
pub(crate) use tests_in_f32_and_f64;

/// Least-squares slope of log(err) against log(h).
pub fn loglog_slope(hs: &[f64], errs: &[f64]) -> f64 {
    let n = hs.len() as f64;
    let xs: Vec<f64> = hs.iter().map(|h| h.ln()).collect();
    let ys: Vec<f64> = errs.iter().map(|e| e.ln()).collect();
    let mx = xs.iter().sum::<f64>() / n;
    let my = ys.iter().sum::<f64>() / n;
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// How an error converges over `[0, t_end]`: `error(n)` for each step count `n` of `ns`, and the measured
/// order, the [`loglog_slope`] of those errors against the step `t_end / n`.
pub fn convergence(
    t_end: f64,
    ns: &[usize],
    mut error: impl FnMut(usize) -> f64,
) -> (Vec<f64>, f64) {
    let hs: Vec<f64> = ns.iter().map(|&n| t_end / n as f64).collect();
    let es: Vec<f64> = ns.iter().map(|&n| error(n)).collect();
    let slope = loglog_slope(&hs, &es);
    (es, slope)
}

/// The attitude error (rad) after `n` steps of `input` over `[0, t_end]` of [`Coning::STANDARD`], in f64
/// without a stabilizer: the angle from the normalized result to the exact attitude.
pub fn coning_error(scheme: SchemeKind, input: Input, n: usize, t_end: f64) -> f64 {
    let c = Coning::STANDARD;
    let q = propagate::<f64, _, _>(
        scheme,
        Off,
        input,
        c.attitude(0.0),
        &|t| c.rate(t),
        t_end,
        n,
    )
    .unwrap()
    .q;
    q.normalized().unwrap().angle_to(c.attitude(t_end))
}

/// Asserts that the (primed) sample history is fourth order, within ±0.15, with each of `schemes`: the order
/// measured from the [`coning_error`]s over 0.7 s (not a whole number of coning periods) at the step
/// counts `ns`.
pub fn assert_history_is_fourth_order(schemes: &[SchemeKind], ns: &[usize]) {
    for &m in schemes {
        let (es, slope) = convergence(0.7, ns, |n| coning_error(m, Input::History, n, 0.7));
        println!("{m:?} with sample history: errors {es:?}, order {slope:.3}");
        assert!((slope - 4.0).abs() < 0.15, "{m:?}: order {slope}");
    }
}

/// The whole propagator state as text: `Debug` prints every field, private ones included, and prints each
/// float as its shortest round-trip decimal, so two equal strings mean bit-identical finite floats (and
/// `-0.0` differs from `0.0`, unlike `==`).
pub fn state<P: core::fmt::Debug>(p: &P) -> String {
    format!("{p:?}")
}

/// The bound on `|N| = |‖q‖² − 1|` (in units of ε) after one [`quatprop::stabilize::Normalize`] correction
/// with the plain accumulator, of an attitude whose `‖q‖²` is `f` (the factor by which the step changed
/// `‖q‖²`, the step's start being unit): 4 for `f ∈ [½, 2]`, otherwise `6 + 7(√f − 1)⁺` (src/stabilize.rs
/// derives both; tests/normalize.rs measures them).
pub fn normalize_bound_eps(f: f64) -> f64 {
    if (0.5..=2.0).contains(&f) {
        4.0
    } else {
        6.0 + 7.0 * (f.sqrt() - 1.0).max(0.0)
    }
}

/// A deterministic generator (xorshift64*, Vigna 2016) for tests that sample many operands: `uniform()`
/// in [0, 1), `signed()` in [−1, 1).
pub struct Xorshift(u64);

impl Xorshift {
    /// The generator every test starts from unless it needs another stream.
    pub const fn new() -> Self {
        Self(0x9E37_79B9_7F4A_7C15)
    }

    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn signed(&mut self) -> f64 {
        self.uniform() * 2.0 - 1.0
    }

    /// Another stream: the generator started from `seed` (mixed, so neighbouring seeds are unrelated).
    pub fn with_seed(seed: u64) -> Self {
        let mut g = Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
        g.uniform();
        g
    }

    /// A standard normal deviate (Box–Muller).
    pub fn gaussian(&mut self) -> f64 {
        let u = 1.0 - self.uniform(); // (0, 1]
        let v = self.uniform();
        (-2.0 * u.ln()).sqrt() * (2.0 * core::f64::consts::PI * v).cos()
    }
}

/// The estimator tests' tumbling motion (rad/s, body axes) `s` seconds after it starts: slow incommensurate
/// turns about every axis that take each body axis through the vertical (up to about 1.1 rad/s).
pub fn tumbling_rate(s: f64) -> Vec3<f64> {
    Vec3::new(
        0.6 * (0.31 * s).sin(),
        0.5 * (0.23 * s + 1.0).sin(),
        0.8 * (0.17 * s + 2.0).cos(),
    )
}

/// Gaussian noise for the estimator tests: xorshift64* from the raw state it is given (not mixed),
/// uniforms at the centres of the 2⁻⁵³ bins (never 0, for the logarithm) and Box–Muller's first deviate.
/// A stream of its own, kept bit for bit: the estimator tests' thresholds were set on it.
pub struct GaussNoise(pub u64);

impl GaussNoise {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// A standard normal deviate.
    pub fn gauss(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }

    /// Three independent deviates of standard deviation `sigma`.
    pub fn vec(&mut self, sigma: f64) -> Vec3<f64> {
        Vec3::new(
            self.gauss() * sigma,
            self.gauss() * sigma,
            self.gauss() * sigma,
        )
    }
}
