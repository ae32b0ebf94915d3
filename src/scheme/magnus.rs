//! Fourth-order schemes from the rates at the two Gauss points of the step: Magnus-4 and a commutator-free
//! fourth-order method. Both keep |q| exactly (products of unit quaternions) and read the rate through
//! `RateModel::rate_at` at the Gauss nodes, so they work with any input model: exactly the samples for
//! `step_gauss`, the quadratic interpolant for `step_mid` (still fourth order: the interpolation error is
//! antisymmetric about the midpoint and cancels in the Gauss rule), the exact rate for `step_hold`.

use super::exp_map::with_radial;
use super::Scheme;
use crate::rates::{magnus4_half, RateModel, GAUSS_1, GAUSS_2};
use crate::stabilize::Stabilizer;
use crate::{Quat, Real};

/// Magnus-4: `q ← q ⊗ exp_q((h/2)(ω₁ + ω₂) + (√3 h²/12) ω₁ × ω₂)` with ω₁, ω₂ at the Gauss points
/// (Iserles & Nørsett 1999; Blanes, Casas, Oteo, Ros, *Phys. Rep.* 470 (2009), eq. (4.10)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Magnus4;

impl Scheme for Magnus4 {
    fn name(&self) -> &'static str {
        "Magnus4"
    }
    fn order(&self) -> u32 {
        4
    }
    fn step_angle_limit(&self) -> f64 {
        f64::INFINITY
    }
    fn real_axis_limit(&self) -> f64 {
        f64::INFINITY
    }
    fn norm_change(&self, _step_angle: f64) -> f64 {
        0.0
    }
    #[inline(always)]
    fn increment<T: Real, R: RateModel<T>, Z: Stabilizer<T>>(
        &self,
        q: Quat<T>,
        rates: &R,
        h: T,
        stabilizer: &Z,
    ) -> Quat<T> {
        let v = magnus4_half(rates.rate_at(GAUSS_1), rates.rate_at(GAUSS_2), h * T::HALF);
        q * with_radial(Quat::exp_half_minus_one(v), q, h, stabilizer)
    }
}

/// Commutator-free fourth order (CF4): `q ← q ⊗ exp_q(h(β₁ω₁ + β₂ω₂)) ⊗ exp_q(h(β₂ω₁ + β₁ω₂))`,
/// `β₁,₂ = ¼ ± √3/6`, ω₁, ω₂ at the Gauss points: two exponentials, no cross product
/// (Blanes & Moan, *Appl. Numer. Math.* 56 (2006); Blanes et al., *Phys. Rep.* 470 (2009), eq. (5.8)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Cf4;

impl Scheme for Cf4 {
    fn name(&self) -> &'static str {
        "Cf4"
    }
    fn order(&self) -> u32 {
        4
    }
    fn step_angle_limit(&self) -> f64 {
        f64::INFINITY
    }
    fn real_axis_limit(&self) -> f64 {
        f64::INFINITY
    }
    fn norm_change(&self, _step_angle: f64) -> f64 {
        0.0
    }
    #[inline(always)]
    fn increment<T: Real, R: RateModel<T>, Z: Stabilizer<T>>(
        &self,
        q: Quat<T>,
        rates: &R,
        h: T,
        stabilizer: &Z,
    ) -> Quat<T> {
        const S: f64 = 0.288_675_134_594_812_9; // √3/6
        let (a, b) = (rates.rate_at(GAUSS_1), rates.rate_at(GAUSS_2));
        let hh = h * T::HALF;
        let (b1, b2) = (T::from_f64(0.25 + S), T::from_f64(0.25 - S));
        // exp_q(hβ·ω) = exp((0, hh·β·ω)).
        let e1 = Quat::exp_half_minus_one((a * b1 + b * b2) * hh);
        let e2 = Quat::exp_half_minus_one((a * b2 + b * b1) * hh);
        // e₁e₂ − 1 = (e₁ − 1) + (e₂ − 1) + (e₁ − 1)(e₂ − 1): no cancellation.
        let em1 = e1 + e2 + e1 * e2;
        q * with_radial(em1, q, h, stabilizer)
    }
}
