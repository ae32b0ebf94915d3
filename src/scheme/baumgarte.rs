//! Baumgarte stabilization: the seed's eq. (7), `q' = ½(Ω − 4kN·E) q`, a right-hand-side option of the
//! Runge–Kutta engine (not a post-step stabilizer: it acts inside every stage).

use super::rk::{stage_increment, RungeKutta};
use super::{Information, Scheme};
use crate::input::Segment;
use crate::{Error, Quat, Real};

/// A Runge–Kutta scheme `S` whose right-hand side carries Baumgarte's term with gain `k` (1/s):
/// `q' = ½[q ⊗ (0, ω) − 4kN q]`, `N = |q|² − 1`, evaluated in every stage.
///
/// In exact arithmetic `N' = −4kN(1 + N)` (the seed's eq. (8)). Under an explicit RK scheme the seed shows
/// (and the tests reproduce) a jump on the first step and convergence to a wrong `N∞ ≠ 0` that depends on
/// k, h and |ω|; only two tuned values of k give `N∞ ≈ 0`. Use [`crate::stabilize::FirstOrder`] or
/// [`crate::stabilize::Normalize`] instead unless you study the seed's method.
///
/// A step needs `4k·h` within [`Baumgarte::gain_step_limit`] (half the scheme's real-axis stability
/// interval); beyond it the propagator refuses the step with [`Error::GainBeyondStability`].
///
/// ```
/// use quatprop::scheme::{Baumgarte, Rk4};
/// let b = Baumgarte::new(Rk4, 0.5_f32)?;
/// assert_eq!(b.gain(), 0.5);
/// assert!((b.gain_step_limit() - 1.3926).abs() < 1e-3); // half of RK4's 2.785
/// assert_eq!(Baumgarte::new(Rk4, -1.0_f32), Err(quatprop::Error::InvalidGain));
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Baumgarte<S, T> {
    scheme: S,
    k: T,
}

impl<S: RungeKutta, T: Real> Baumgarte<S, T> {
    /// `scheme` with Baumgarte's term of gain `k` (1/s, finite, `k ≥ 0`).
    ///
    /// # Errors
    /// [`Error::InvalidGain`] for a negative or non-finite `k`.
    pub fn new(scheme: S, k: T) -> Result<Self, Error> {
        if k.is_finite() && k >= T::ZERO {
            Ok(Self { scheme, k })
        } else {
            Err(Error::InvalidGain)
        }
    }

    /// `scheme` with the gain `k`, already validated (by [`crate::config::Config::validate`]).
    #[inline(always)]
    pub(crate) fn validated(scheme: S, k: T) -> Self {
        Self { scheme, k }
    }

    /// The gain `k` (1/s).
    #[must_use]
    pub fn gain(&self) -> T {
        self.k
    }

    /// Largest `4k·h` a step may have: half of the scheme's real-axis stability limit.
    ///
    /// The linear bound alone is not enough. The term is nonlinear (`−4kN(1 + N)`), the norm settles on the
    /// seed's `N∞ ≠ 0`, and the one-step map loses its fixed point before `4kh` reaches the real-axis limit
    /// for some schemes: in propagation (lab `baumgarte_sweep`, |ω| = 1 rad/s, h|ω| from 0.1 to 2) Rk5
    /// escapes at 0.82–0.96 of the real-axis limit and stops settling at 0.66–0.82 of it; every scheme
    /// settles below half of it. The seed's optimal gains are `4kh` ≈ 0.002–0.05.
    #[must_use]
    pub fn gain_step_limit(&self) -> f64 {
        0.5 * S::INFORMATION.real_axis_limit
    }

    /// The wrapped scheme's record ([`Information`]; its bounds hold for the rotation part of the
    /// right-hand side).
    #[must_use]
    pub fn information(&self) -> Information {
        S::INFORMATION
    }
}

impl<S: RungeKutta, T: Real> Scheme<T> for Baumgarte<S, T> {
    #[inline(always)]
    fn information(&self) -> Information {
        Baumgarte::information(self)
    }

    #[inline]
    fn check<G: Segment<T>>(&self, segment: &G, h: T) -> Result<(), Error> {
        Scheme::<T>::check(&self.scheme, segment, h)?;
        let gain_step = T::from_f64(4.0) * self.k * h;
        let limit = self.gain_step_limit();
        if !(gain_step <= T::from_f64(limit)) {
            return Err(Error::GainBeyondStability {
                gain_step: gain_step.to_f64(),
                limit,
            });
        }
        Ok(())
    }

    /// The stages with `g = q ⊗ (0, ω) + s(q) q`, `s = −4kN` (no held-rate shortcut: the term is nonlinear).
    #[inline(always)]
    fn increment<G: Segment<T>>(&self, q: Quat<T>, segment: &G, h: T) -> Quat<T> {
        let gain = -(T::from_f64(4.0) * self.k);
        stage_increment::<T, S, _>(q, h * T::HALF, |c, y| {
            y.mul_pure(segment.rate_at(c)) + y * (gain * (y.norm_squared() - T::ONE))
        })
    }
}
