//! The exponential map: `q ← q ⊗ exp_q(φ)` with the step's rotation vector φ from the input model.

use super::Scheme;
use crate::rates::RateModel;
use crate::stabilize::Stabilizer;
use crate::{Quat, Real};

/// Exact exponential map of the step's rotation vector.
///
/// - Held rate: `φ = hω`, exact for constant rotation at any `h|ω|` (no stability bound, norm factor 1).
/// - Linear rate: `φ = h(ω₀ + ω₁)/2 + (h²/12) ω₀ × ω₁` (exact to 4th order for a truly linear rate; on sampled
///   data the trapezoid error in ∫ω makes it 2nd order).
/// - Three samples (start, middle, end): 4th-order Magnus, Simpson's ∫ω plus the commutator term.
///
/// Small angles use a Taylor branch that drops nothing (see [`Quat::from_rotation_vector`]).
/// With [`crate::stabilize::Baumgarte`] the radial term commutes with the rotation and is applied exactly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ExpMap;

impl Scheme for ExpMap {
    #[inline(always)]
    fn name(&self) -> &'static str {
        "ExpMap"
    }
    #[inline(always)]
    fn order(&self) -> u32 {
        4
    }
    #[inline(always)]
    fn step_angle_limit(&self) -> f64 {
        f64::INFINITY
    }
    #[inline(always)]
    fn real_axis_limit(&self) -> f64 {
        f64::INFINITY
    }
    fn norm_change(&self, _step_angle: f64) -> f64 {
        0.0
    }
    #[inline(always)]
    fn advance<T: Real, R: RateModel<T>, Z: Stabilizer<T>>(
        &self,
        q: Quat<T>,
        rates: &R,
        h: T,
        stabilizer: &Z,
    ) -> Quat<T> {
        let rotated = q * Quat::exp_half(rates.half_rotation_vector(h * T::HALF));
        if stabilizer.has_rhs_term() {
            rotated * stabilizer.radial_flow_scale(q, h)
        } else {
            rotated
        }
    }
}
