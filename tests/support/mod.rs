//! Exact reference motions and helpers shared by the integration tests.
#![allow(dead_code)]

use quatprop::scheme::Scheme;
use quatprop::stabilize::Stabilizer;
use quatprop::{Propagator, Quat, Real, Vec3};

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

/// How a step sees the rate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// One sample at the start of the step, held.
    Hold,
    /// Samples at both ends, linear.
    Linear,
    /// Samples at start, middle and end.
    Mid,
}

impl Input {
    pub const ALL: [Input; 3] = [Input::Hold, Input::Linear, Input::Mid];
}

/// Steps `p` once over `[t, t + h]` sampling `rate`, in precision `T`.
pub fn step<T: Real, S: Scheme, Z: Stabilizer<T>>(
    p: &mut Propagator<T, S, Z>,
    input: Input,
    rate: &dyn Fn(f64) -> Vec3<f64>,
    t: f64,
    h: f64,
) -> Result<(), quatprop::Error> {
    let w = |t: f64| Vec3::<T>::from_f64(rate(t));
    let dt = T::from_f64(h);
    match input {
        Input::Hold => p.step_hold(w(t), dt),
        Input::Linear => p.step_linear(w(t), w(t + h), dt),
        Input::Mid => p.step_mid(w(t), w(t + 0.5 * h), w(t + h), dt),
    }
}

/// Propagates from `reference(0)` over `[0, t_end]` in `n` steps and returns the attitude error (rad) at the end.
pub fn final_error<T: Real, S: Scheme, Z: Stabilizer<T>>(
    scheme: S,
    stabilizer: Z,
    input: Input,
    reference: &dyn Fn(f64) -> Quat<f64>,
    rate: &dyn Fn(f64) -> Vec3<f64>,
    t_end: f64,
    n: usize,
) -> f64 {
    let h = t_end / n as f64;
    let mut p = Propagator::new(Quat::<T>::from_f64(reference(0.0)), scheme, stabilizer).unwrap();
    for i in 0..n {
        step(&mut p, input, rate, i as f64 * h, h).unwrap();
    }
    let q = p.attitude().to_f64();
    // Compare directions: the error angle of the normalized attitude.
    q.normalized().unwrap().angle_to(reference(t_end))
}

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
