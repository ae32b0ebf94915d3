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
    /// `q ⊗ (e − 1)` with `e = exp_q(φ)`, and with Baumgarte `q ⊗ (ρe − 1)` for the exact radial factor ρ.
    #[inline(always)]
    fn increment<T: Real, R: RateModel<T>, Z: Stabilizer<T>>(
        &self,
        q: Quat<T>,
        rates: &R,
        h: T,
        stabilizer: &Z,
    ) -> Quat<T> {
        let em1 = Quat::exp_half_minus_one(rates.half_rotation_vector(h * T::HALF));
        q * with_radial(em1, q, h, stabilizer)
    }
}

/// A rotation increment `e − 1` with Baumgarte's exact radial factor ρ applied when the stabilizer has a
/// right-hand-side term: `ρe − 1 = (ρ−1 + (e_w−1) + (ρ−1)(e_w−1), ρ·e_v)`, free of cancellation.
/// Shared by the exponential-map family (ExpMap, Magnus4, Cf4).
#[inline(always)]
pub(crate) fn with_radial<T: Real, Z: Stabilizer<T>>(
    em1: Quat<T>,
    q: Quat<T>,
    h: T,
    z: &Z,
) -> Quat<T> {
    if z.has_rhs_term() {
        let rm1 = z.radial_flow_scale_minus_one(q, h);
        Quat::from_parts(rm1 + em1.w + rm1 * em1.w, em1.vector() * (T::ONE + rm1))
    } else {
        em1
    }
}
