//! The Allan variance and the noise fit on synthetic sensors whose densities are known: white noise `N`,
//! flicker noise of bias instability `B` (a sum of Gauss–Markov processes one octave apart, whose
//! spectrum is `B²/(π f)` within a few per cent over their band) and a rate random walk `K`.

mod support;

use quatprop::noise::{AllanVariance, GyroNoise, NoiseFit, Point, FLICKER_FLOOR};
use quatprop::{Error, Vec3};
use support::Xorshift;

/// A 3-axis sensor at rest with the three noises, sampled every `period`.
struct Sensor {
    white: f64,
    /// Each Gauss–Markov process: (its coefficient a = e^(−Ts/Tc), its innovation's σ), per axis state.
    markov: Vec<(f64, f64, [f64; 3])>,
    walk: f64,
    bias: [f64; 3],
    rng: Xorshift,
}

impl Sensor {
    /// Densities `n` (unit/√s), `b` (unit), `k` (unit/√s); the flicker band's correlation times run from
    /// `period` over `octaves` octaves: its Allan variance is within 1 % of the floor from τ = 128·period
    /// to 2^(octaves − 7)·period, 6 % below it at 16·period (where the white noise is 10 to 100 times
    /// larger in these sensors).
    fn new(period: f64, n: f64, b: f64, k: f64, octaves: u32, seed: u64) -> Self {
        // One-sided spectrum of a sum of Gauss–Markov processes of variance σ², correlation times a factor
        // r apart: ≈ σ² / (f ln r); flicker of bias instability B is B²/(π f): σ² = B² ln 2 / π.
        let sigma = b * (core::f64::consts::LN_2 / core::f64::consts::PI).sqrt();
        let markov = (0..octaves)
            .map(|i| {
                let tc = period * 2f64.powi(i as i32);
                let a = (-period / tc).exp();
                (a, sigma * (1.0 - a * a).sqrt(), [0.0; 3])
            })
            .collect();
        let mut rng = Xorshift::with_seed(seed);
        // Start each process in its stationary distribution.
        let mut s = Self {
            white: n / period.sqrt(),
            markov,
            walk: k * period.sqrt(),
            bias: [0.01, -0.02, 0.005],
            rng: Xorshift::new(),
        };
        for m in &mut s.markov {
            for x in &mut m.2 {
                *x = sigma * rng.gaussian();
            }
        }
        s.rng = rng;
        s
    }

    fn sample(&mut self) -> Vec3<f64> {
        let mut v = [0.0; 3];
        for (axis, out) in v.iter_mut().enumerate() {
            self.bias[axis] += self.walk * self.rng.gaussian();
            let mut flicker = 0.0;
            for m in &mut self.markov {
                m.2[axis] = m.0 * m.2[axis] + m.1 * self.rng.gaussian();
                flicker += m.2[axis];
            }
            *out = self.bias[axis] + flicker + self.white * self.rng.gaussian();
        }
        Vec3::new(v[0], v[1], v[2])
    }
}

fn relative(estimate: f64, truth: f64) -> f64 {
    estimate / truth - 1.0
}

/// A gyro at 10 Hz for 6 h with every term visible (each dominates the curve over several octaves): over
/// four seeds each density is recovered within 10 %, and the truth of the bias instability and the random
/// walk lies inside the fit's 3-standard-error interval. (The white noise's interval is not checked: its
/// standard error, 0.4 %, is below this generator's own departure from the model at the shortest τ fitted,
/// where its flicker band begins: the fits land 0.5–4 % low.)
#[test]
fn three_terms_are_recovered_within_ten_per_cent() {
    // N = 0.3 °/√h, B = 20.6 °/h, K = 0.069 °/h/√s (4.1 °/h/√h·60): a consumer MEMS gyro's magnitudes.
    let (n, b, k) = (8.7e-5, 1.0e-4, 2.0e-5);
    let period = 0.1;
    let samples = (6.0 * 3600.0 / period) as usize;
    let mut worst = [0.0_f64; 3];
    for seed in 0..4 {
        let mut sensor = Sensor::new(period, n, b, k, 24, seed);
        let mut avar = AllanVariance::<f64, 20>::new(period).unwrap();
        for _ in 0..samples {
            avar.push(sensor.sample()).unwrap();
        }
        let fit = NoiseFit::pooled_from(&avar, 16.0 * period).unwrap();
        let terms = [fit.white, fit.instability, fit.random_walk];
        println!(
            "seed {seed}: N {:+.1} %, B {:+.1} %, K {:+.1} % (se {:.1} %), misfit {:.2}, {} points",
            100.0 * relative(terms[0].value(), n),
            100.0 * relative(terms[1].value(), b),
            100.0 * relative(terms[2].value(), k),
            100.0 * terms[2].std_error / terms[2].coefficient / 2.0,
            fit.misfit,
            fit.points
        );
        for (i, (term, truth)) in terms.iter().zip([n, b, k]).enumerate() {
            assert!(term.is_identified(), "seed {seed}: term {i} not identified");
            if i > 0 {
                let (lo, hi) = term.interval(3.0);
                assert!(
                    lo <= truth && truth <= hi,
                    "seed {seed}: term {i}: {truth} outside [{lo}, {hi}]"
                );
            }
            worst[i] = worst[i].max(relative(term.value(), truth).abs());
        }
    }
    println!(
        "worst relative errors: N {:.3}, B {:.3}, K {:.3}",
        worst[0], worst[1], worst[2]
    );
    assert!(worst.iter().all(|&e| e < 0.10), "{worst:?}");
}

/// A short rest (30 s at 285 Hz, as BROAD's trials start) identifies the white noise within a few per
/// cent and says that it cannot see the random walk.
#[test]
fn a_short_rest_identifies_the_white_noise_and_bounds_the_rest() {
    let (n, b, k) = (1.5e-4, 2.0e-5, 1.0e-6);
    let period = 1.0 / 285.714;
    let mut sensor = Sensor::new(period, n, b, k, 22, 11);
    let mut avar = AllanVariance::<f32, 16>::new(period).unwrap();
    for _ in 0..(30.0 / period) as usize {
        let s = sensor.sample();
        avar.push(Vec3::new(s.x as f32, s.y as f32, s.z as f32))
            .unwrap();
    }
    let fit = NoiseFit::pooled_from(&avar, 16.0 * period).unwrap();
    println!("{fit:?}");
    assert!(relative(fit.white.value(), n).abs() < 0.05);
    assert!(!fit.random_walk.is_identified());
    // The bound on what it could not see holds the truth.
    assert!(fit.random_walk.interval(3.0).1 >= k);
    // f32 samples around a bias of 0.02 rad/s: the same curve as f64 within its rounding.
    let noise = GyroNoise::<f32>::from_fit(&fit).unwrap();
    assert!((f64::from(noise.arw()) / fit.white.value() - 1.0).abs() < 1e-6);
}

/// The streaming octaves equal a direct computation of the non-overlapping Allan variance from the
/// stored samples.
#[test]
fn the_streaming_octaves_equal_the_direct_formula() {
    let mut rng = Xorshift::with_seed(5);
    let samples: Vec<Vec3<f64>> = (0..5000)
        .map(|_| {
            Vec3::new(
                rng.gaussian(),
                0.3 + rng.gaussian(),
                -2.0 + 0.1 * rng.gaussian(),
            )
        })
        .collect();
    let mut avar = AllanVariance::<f64, 10>::new(0.001).unwrap();
    for &s in &samples {
        avar.push(s).unwrap();
    }
    let clusters: Vec<_> = avar.clusters().collect();
    assert_eq!(clusters.len(), 10);
    for c in clusters {
        let m = c.samples as usize;
        let means: Vec<Vec3<f64>> = samples
            .chunks_exact(m)
            .map(|ch| ch.iter().fold(Vec3::ZERO, |a, &s| a + s) * (1.0 / m as f64))
            .collect();
        let d = means.len() - 1;
        assert_eq!(c.differences as usize, d);
        let direct: f64 = means
            .windows(2)
            .map(|w| (w[1].y - w[0].y).powi(2))
            .sum::<f64>()
            / (2.0 * d as f64);
        assert!(
            (c.variance.y / direct - 1.0).abs() < 1e-12,
            "τ = {}: {} against {direct}",
            c.tau,
            c.variance.y
        );
        assert!((c.tau - 0.001 * m as f64).abs() < 1e-15);
    }
}

/// The fit of an exact curve gives its coefficients back.
#[test]
fn an_exact_curve_is_fitted_exactly() {
    let (n2, b2, k2) = (4e-8, 9e-10, 1e-12);
    let points = (0..16).map(|k| {
        let tau = 0.01 * 2f64.powi(k);
        Point {
            tau,
            variance: n2 / tau + FLICKER_FLOOR * b2 + k2 * tau / 3.0,
            differences: 1e6 / 2f64.powi(k),
        }
    });
    let fit = NoiseFit::of(points).unwrap();
    for (got, want) in [
        (fit.white.coefficient, n2),
        (fit.instability.coefficient, b2),
        (fit.random_walk.coefficient, k2),
    ] {
        assert!((got / want - 1.0).abs() < 1e-9, "{got} against {want}");
    }
    assert!(fit.misfit < 1e-12);
}

#[test]
fn bad_input_is_refused_and_changes_nothing() {
    assert_eq!(
        AllanVariance::<f32>::new(0.0).unwrap_err(),
        Error::NonPositiveStep
    );
    assert_eq!(
        AllanVariance::<f32>::new(f64::NAN).unwrap_err(),
        Error::NonFiniteStep
    );
    let mut avar = AllanVariance::<f32, 4>::new(0.01).unwrap();
    avar.push(Vec3::new(1.0, 2.0, 3.0)).unwrap();
    let before = avar;
    assert_eq!(
        avar.push(Vec3::new(f32::NAN, 0.0, 0.0)),
        Err(Error::NonFiniteRate)
    );
    assert_eq!(avar, before);
    // A sample so far from the first that the square of a difference overflows.
    assert_eq!(
        avar.push(Vec3::new(f32::MAX, 0.0, 0.0)),
        Err(Error::NonFiniteRate)
    );
    assert_eq!(avar, before);
    avar.push(Vec3::new(1.5, 2.0, 3.0)).unwrap();
    assert_ne!(avar, before);
    // Too few octaves to fit.
    let mut small = AllanVariance::<f64, 4>::new(0.01).unwrap();
    small.push(Vec3::ZERO).unwrap();
    small.push(Vec3::ZERO).unwrap();
    assert!(NoiseFit::pooled(&small).is_none());
}

/// The standard errors are the fit's own scatter: over 64 recordings of white noise (2¹⁵ samples each),
/// the white term's errors in its own standard errors, `z = (c − N²) / se`, have a standard deviation
/// near 1 (0.8 to 1.25; it is 0.92: the octaves share their samples, and standard errors that took them as
/// independent came out too small, the spread of `z` 1.44 before the fit counted that).
#[test]
fn the_standard_errors_are_the_scatter() {
    let (n, period) = (1e-3, 0.01);
    let z: Vec<f64> = (0..64)
        .map(|seed| {
            let mut sensor = Sensor::new(period, n, 0.0, 0.0, 1, 100 + seed);
            let mut avar = AllanVariance::<f64, 16>::new(period).unwrap();
            for _ in 0..1 << 15 {
                avar.push(sensor.sample()).unwrap();
            }
            let fit = NoiseFit::pooled_from(&avar, 16.0 * period).unwrap();
            (fit.white.coefficient - n * n) / fit.white.std_error
        })
        .collect();
    let mean = z.iter().sum::<f64>() / z.len() as f64;
    let sd = (z.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (z.len() - 1) as f64).sqrt();
    println!("z: mean {mean:+.2}, standard deviation {sd:.2}");
    assert!((0.8..1.25).contains(&sd), "{sd}");
    assert!(mean.abs() < 0.5, "{mean}");
}
