//! Baumgarte stabilization: the seed's eq. (7), `q' = ½(Ω − 4kN·E) q`, a term of the right-hand side.

use super::Stabilizer;
use crate::{Error, Quat, Real};

/// Baumgarte stabilization with gain `k` (1/s): the right-hand side becomes `½[q ⊗ (0, ω) − 4kN q]`
/// with `N = |q|² − 1`, evaluated inside every Runge–Kutta stage (not a post-step correction).
///
/// In exact arithmetic `N' = −4kN(1 + N)` (the seed's eq. (8)). Under an explicit RK scheme the seed shows
/// (and the tests reproduce) a jump on the first step and convergence to a wrong `N∞ ≠ 0` that depends on
/// k, H and |ω|; only two tuned values of k give `N∞ ≈ 0`. Under [`crate::scheme::ExpMap`] the radial term
/// commutes with the rotation and is integrated exactly, so `N` decays as eq. (8) says.
///
/// A step needs `4kh` within [`crate::scheme::Scheme::gain_step_limit`] (half the scheme's real-axis
/// stability interval); beyond it the propagator refuses the step.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Baumgarte<T> {
    /// Gain `k` (1/s), `k ≥ 0`.
    pub k: T,
}

impl<T: Real> Stabilizer<T> for Baumgarte<T> {
    fn validate(&self) -> Result<(), Error> {
        if self.k.is_finite() && self.k >= T::ZERO {
            Ok(())
        } else {
            Err(Error::InvalidStabilizer)
        }
    }
    #[inline(always)]
    fn has_rhs_term(&self) -> bool {
        true
    }
    /// `s = −4kN`: the right-hand side is `½[q ⊗ (0, ω) − 4kN q]`, the seed's eq. (7).
    #[inline(always)]
    fn rhs_scalar(&self, q: Quat<T>) -> T {
        let n = q.norm_squared() - T::ONE;
        -(T::from_f64(4.0) * self.k) * n
    }
    #[inline(always)]
    fn norm_stiffness(&self) -> T {
        T::from_f64(4.0) * self.k
    }
    /// Exact solution of `n' = −4k(n − 1)n` for `n = |q|²` (logistic, the seed's eq. (8)):
    /// `n(h)/n₀ = 1 / (n₀ + (1 − n₀) e^{−4kh}) = 1 + r` with `r = (1 − n₀)(1 − e^{−4kh}) / (…)`;
    /// returns `ρ − 1 = √(1 + r) − 1 = r / (√(1 + r) + 1)`.
    #[inline]
    fn radial_flow_scale_minus_one(&self, q: Quat<T>, h: T) -> T {
        let n0 = q.norm_squared();
        let decay = (-(T::from_f64(4.0) * self.k * h)).exp();
        let denom = n0 + (T::ONE - n0) * decay;
        let r = (T::ONE - n0) * (T::ONE - decay) / denom;
        r / ((T::ONE + r).sqrt() + T::ONE)
    }
    #[inline(always)]
    fn correction(&self, _q: Quat<T>, _pending: u32) -> Option<Quat<T>> {
        None
    }
}
