//! Delta-angle coning corrections on the exact coning motion: the measured coning drift of each matches its
//! closed-form coefficient (src/coning.rs, derived in lab/derivations/coning_drift.py) to 1% at small α.
//!
//! Increments are the exact ∫ω dt over each sample interval (elementary functions); the propagator (f64,
//! ExpMap, no stabilizer needed: the exponential map keeps |q|) applies each correction; the drift is the
//! axial component of the accumulated error rotation `q_exact* ⊗ q` divided by the elapsed time. Horizons are
//! whole cone periods, so periodic error terms cancel.

mod support;

use quatprop::accumulate::Kahan;
use quatprop::coning::{ConingCorrection, Method};
use quatprop::scheme::ExpMap;
use quatprop::stabilize::Off;
use quatprop::{Error, Propagator, Quat, Vec3};
use support::Coning;

/// Small cone half-angle: the closed forms are the α² terms of the drift. The exact motion also has α⁴ terms
/// that no cross-product correction removes; at α = 0.05 they already outweigh the four-sample α²(ΩT)⁸ term,
/// so the comparison uses α = 10⁻³ (α⁴/α² = 10⁻⁶).
const ALPHA: f64 = 1e-3;
const BIG_OMEGA: f64 = 2.0 * core::f64::consts::PI;

/// Exact increment ∫ω dt over [t0, t1], written without cancellation.
fn increment(c: &Coning, t0: f64, t1: f64) -> Vec3<f64> {
    let (a, b) = (c.big_omega * t1, c.big_omega * t0);
    let (mean, half) = (0.5 * (a + b), 0.5 * (a - b));
    let s = c.alpha.sin();
    let s2 = (c.alpha / 2.0).sin();
    Vec3::new(
        -2.0 * s * mean.sin() * half.sin(),
        2.0 * s * mean.cos() * half.sin(),
        -2.0 * c.big_omega * s2 * s2 * (t1 - t0),
    )
}

/// Drift rate (rad/s, about the cone axis) with `n` samples per update and `per_period` updates per period,
/// over `periods` cone periods.
fn measured_drift(m: Method, n: usize, per_period: usize, periods: usize) -> (f64, f64) {
    let c = Coning {
        alpha: ALPHA,
        big_omega: BIG_OMEGA,
    };
    let period = 2.0 * core::f64::consts::PI / c.big_omega;
    let t_update = period / per_period as f64;
    let h = t_update / n as f64;
    // A Kahan-compensated f64 state keeps the attitude's own round-off far below the drifts measured here.
    let mut p = Propagator::new_compensated(c.attitude(0.0), ExpMap, Off).unwrap();
    let updates = per_period * periods;
    let mut incs = vec![Vec3::ZERO; n];
    // The drift is the slope of the axial error between two whole-period checkpoints, which excludes the
    // one-time start-up error (OnePlusPrevious has no previous increment on its first update).
    let axial_error = |p: &Propagator<f64, ExpMap, Off, Kahan<f64>>, t: f64| {
        (c.attitude(t).conjugate() * p.attitude())
            .to_rotation_vector()
            .z
    };
    let mut first = None;
    for u in 0..updates {
        if u == per_period {
            first = Some((axial_error(&p, u as f64 * t_update), u as f64 * t_update));
        }
        let t0 = u as f64 * t_update;
        for (i, d) in incs.iter_mut().enumerate() {
            *d = increment(&c, t0 + i as f64 * h, t0 + (i + 1) as f64 * h);
        }
        p.step_delta(m, &incs, t_update).unwrap();
    }
    let t = updates as f64 * t_update;
    let (e1, t1) = first.unwrap();
    let drift = (axial_error(&p, t) - e1) / (t - t1);
    (drift, c.big_omega * t_update)
}

/// Closed-form leading drift: α²Ω (ΩT)^p · coefficient.
fn closed_form(m: Method) -> (i32, f64) {
    match m {
        Method::Uncorrected => (2, -1.0 / 12.0),
        Method::OnePlusPrevious => (4, -1.0 / 60.0),
        Method::TwoSample => (4, -1.0 / 960.0),
        Method::ThreeSample => (6, -1.0 / 204_120.0),
        Method::FourSample => (8, -1.0 / 82_575_360.0),
        Method::FiveSample => (10, -1.0 / 54_140_625_000.0),
    }
}

/// The measured coefficient: drift / (α²Ω (ΩT)^p).
fn coefficient(m: Method, per_period: usize, periods: usize) -> (f64, f64) {
    let n = m.samples().unwrap_or(1);
    let (drift, omega_t) = measured_drift(m, n, per_period, periods);
    let (p, _) = closed_form(m);
    (
        drift / (ALPHA * ALPHA * BIG_OMEGA * omega_t.powi(p)),
        omega_t / n as f64,
    )
}

/// The α² coning coefficient of the library's own correction functions: feed the α-free increments of the
/// α² model, `Δθᵢ = (cos θᵢ − cos θᵢ₋₁, sin θᵢ − sin θᵢ₋₁, 0)` with θᵢ = iλ, take the axial part of the
/// library's φ (its cross-product correction), add the increments' axial sum −Nλ/2, subtract the exact
/// −sin(Nλ)/2, and divide by the update time and (ΩT)^p. Exact in f64 at λ = 0.1 (no cancellation below
/// 1e-7 relative), where the next series term is at most 0.35% of the leading one.
fn alpha_squared_coefficient(m: Method, lam: f64) -> f64 {
    let n = m.samples().unwrap_or(1);
    let u = |i: usize| Vec3::new((i as f64 * lam).cos(), (i as f64 * lam).sin(), 0.0);
    // The previous increment (for OnePlusPrevious) is the sample before θ₀.
    let previous = Some(u(0) - Vec3::new((-lam).cos(), (-lam).sin(), 0.0));
    let incs: Vec<Vec3<f64>> = (1..=n).map(|i| u(i) - u(i - 1)).collect();
    let phi = m.rotation_vector(previous, &incs);
    let nl = n as f64 * lam;
    let delta = phi.z - 0.5 * nl + 0.5 * nl.sin();
    let (p, _) = closed_form(m);
    // drift = δ / T with T = N h, Ω h = λ: δ Ω / (N λ) / (Ω (ΩT)^p) with α = Ω = 1.
    delta / (nl * nl.powi(p))
}

#[test]
fn each_correction_has_its_closed_form_alpha_squared_drift() {
    for m in Method::ALL {
        let (_, want) = closed_form(m);
        let got = alpha_squared_coefficient(m, 0.1);
        let rel = (got - want) / want;
        println!(
            "{:16} α² coefficient {got:.6e} vs closed form {want:.6e} (rel {rel:+.2e})",
            m.name()
        );
        assert!(rel.abs() < 1e-2, "{m:?}: {got:e} vs {want:e}");
    }
}

#[test]
fn measured_coning_drift_matches_the_closed_form_at_small_alpha() {
    // Full nonlinear propagation on the exact motion, α = 1e-3, λ ≈ 0.1, 20 cone periods. For the four- and
    // five-sample corrections the α² drift is so small that the α⁴ terms of the exact motion (which no
    // cross-product correction removes) dominate it at any α where f64 can still measure it; see the
    // diagnostic below and README "Coning corrections".
    for m in [
        Method::Uncorrected,
        Method::OnePlusPrevious,
        Method::TwoSample,
        Method::ThreeSample,
    ] {
        let (_, want) = closed_form(m);
        let n = m.samples().unwrap_or(1);
        let lam = if n == 3 { 0.3 } else { 0.1 };
        let per_period = (2.0 * core::f64::consts::PI / (lam * n as f64)).round() as usize;
        let (got, l) = coefficient(m, per_period, 20);
        // Compare with the closed form corrected by its next series term at this λ (from the α² model).
        let model = alpha_squared_coefficient(m, l);
        let rel = (got - model) / model;
        println!(
            "{:16} propagated coefficient {got:.6e} at λ = {l:.3} vs α² model {model:.6e} (rel {rel:+.2e}); leading {want:.6e}",
            m.name()
        );
        assert!(rel.abs() < 1e-2, "{m:?}: {got:e} vs {model:e}");
    }
}

#[test]
fn corrections_order_the_drift_as_expected_at_equal_sample_rate() {
    // Same gyro (1 kHz samples), 10 Hz coning at α = 0.05: each higher-order correction beats the lower one.
    let c = Coning {
        alpha: 0.05,
        big_omega: 2.0 * core::f64::consts::PI * 10.0,
    };
    let h = 1e-3;
    let mut drifts = Vec::new();
    for m in [Method::Uncorrected, Method::TwoSample, Method::ThreeSample] {
        let n = m.samples().unwrap_or(2);
        let mut p = Propagator::new(c.attitude(0.0), ExpMap, Off).unwrap();
        let updates = 9_990 / n; // ~10 s, a whole number of updates
        let mut incs = vec![Vec3::ZERO; n];
        for u in 0..updates {
            let t0 = (u * n) as f64 * h;
            for (i, d) in incs.iter_mut().enumerate() {
                *d = increment(&c, t0 + i as f64 * h, t0 + (i + 1) as f64 * h);
            }
            p.step_delta(m, &incs, n as f64 * h).unwrap();
        }
        let t = (updates * n) as f64 * h;
        drifts.push(p.attitude().angle_to(c.attitude(t)));
    }
    println!(
        "errors after 10 s: uncorrected {:e}, two-sample {:e}, three-sample {:e}",
        drifts[0], drifts[1], drifts[2]
    );
    assert!(drifts[1] < drifts[0] / 100.0 && drifts[2] < drifts[1]);
}

#[test]
fn wrong_increment_count_is_refused_with_state_unchanged() {
    let mut p = Propagator::new(Quat::<f32>::IDENTITY, ExpMap, Off).unwrap();
    let d = Vec3::new(1e-3_f32, 0.0, 0.0);
    p.step_delta(Method::OnePlusPrevious, &[d], 1e-3).unwrap();
    let before = p;
    assert_eq!(
        p.step_delta(Method::ThreeSample, &[d, d], 1e-3),
        Err(Error::SampleCount {
            expected: 3,
            got: 2
        })
    );
    assert_eq!(
        p.step_delta(Method::Uncorrected, &[], 1e-3),
        Err(Error::SampleCount {
            expected: 1,
            got: 0
        })
    );
    assert_eq!(
        p.step_delta(Method::TwoSample, &[d, Vec3::new(f32::NAN, 0.0, 0.0)], 1e-3),
        Err(Error::NonFiniteRate)
    );
    assert_eq!(p, before);
}

/// The propagated drift of the four- and five-sample corrections at α = 1e-3 against λ, next to the α² model:
/// the gap at small λ is the α⁴ drift. `cargo test --release --test coning -- --ignored --nocapture`.
#[test]
#[ignore = "diagnostic table for README: prints c(λ) for the four- and five-sample corrections"]
fn print_coefficient_against_lambda() {
    for m in [Method::FourSample, Method::FiveSample] {
        let n = m.samples().unwrap();
        for lam in [0.2, 0.3, 0.4, 0.5, 0.6] {
            let pp = (2.0 * core::f64::consts::PI / (lam * n as f64)).round() as usize;
            let (c, l) = coefficient(m, pp, 1000);
            let model = alpha_squared_coefficient(m, l);
            println!(
                "{:12} λ {l:.4}: propagated {c:.4e}, α² model {model:.4e}, ratio {:.3}",
                m.name(),
                c / model
            );
        }
    }
}
