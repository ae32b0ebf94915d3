//! Integration schemes: how one step turns the rate function of the step ([`Segment`]) into an attitude
//! increment. A scheme knows nothing of stabilization (that is [`crate::stabilize`], after the step) or of
//! how the increment is added ([`crate::accumulate`]).
//!
//! | scheme | order | stability bound `h·max‖ω‖` (rad) | norm factor per step, `x = h·‖ω‖/2` |
//! |---|---|---|---|
//! | [`Euler`] | 1 | none; ≤ 2 admitted | `1 + x²` |
//! | [`Rk2`] | 2 | none; ≤ 2√2 admitted | `1 + x⁴/4` |
//! | [`Rk3`] | 3 | 2√3 ≈ 3.46 | `1 − x⁴/12 + x⁶/36` |
//! | [`Rk4`] | 4 | 4√2 ≈ 5.66 | `1 − x⁶/72 + x⁸/576` (the seed's `1 − β`) |
//! | [`Rk5`] | 5 | ≈ 1.99 | `1 − x⁶/1800 + O(x⁸)` |
//! | [`ExpMap`] | 4 (Magnus-4 rotation vector of the segment) | none | 1 |
//! | [`Magnus4`] | 4 (rates at the Gauss nodes) | none | 1 |
//! | [`Cf4`] | 4 (Gauss nodes, two exponentials, no cross product) | none | 1 |
//!
//! The norm factor is `|q_{n+1}|²/|q_n|²` for a held rate and no stabilization. These figures are
//! [`Scheme::information`], computed from each tableau at compile time. The order a step reaches also
//! depends on the input model: with one sample per step and only the two samples bracketing the step, any
//! scheme is second order (see [`crate::input`]).
//!
//! Each scheme is a zero-sized type, so a firmware that names one links only it; [`SchemeKind`] chooses
//! one at run time. [`Baumgarte`] wraps a Runge–Kutta scheme with the seed's stabilizing right-hand side.

mod baumgarte;
mod exp_map;
mod rk;
mod tableau;
mod tableaux;

pub use baumgarte::Baumgarte;
pub use exp_map::{Cf4, ExpMap, Magnus4};
pub use rk::RungeKutta;
pub use tableaux::{Euler, Rk2, Rk3, Rk4, Rk5};

use crate::dispatch::dispatch;
use crate::input::Segment;
use crate::{Error, Quat, Real};

/// What a scheme is, for analysis: one record per scheme (order, stability bounds, norm-factor polynomial).
///
/// ```
/// use quatprop::scheme::Rk4;
/// let info = Rk4.information();
/// assert_eq!((info.name, info.order), ("Rk4", 4));
/// assert!((info.step_angle_limit - 4.0 * 2f64.sqrt()).abs() < 1e-12);
/// // The seed's eq. (3): |q|² shrinks by β = x⁶/72 − x⁸/576 per step, x = h|ω|/2.
/// let x: f64 = 0.05;
/// assert!((info.norm_change(0.1) + x.powi(6) / 72.0 - x.powi(8) / 576.0).abs() < 1e-20);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Information {
    /// Short name, e.g. `"Rk4"`.
    pub name: &'static str,
    /// Classical order on a smooth problem (Runge–Kutta: of the tableau; exponential maps: of their
    /// rotation vector, reached with a fourth-order input model).
    pub order: u32,
    /// Largest admitted step angle `h·max|ω|` (rad); a longer step is refused with
    /// [`Error::StepAngleBeyondStability`]. For RK3–RK5 the end of the stability interval on the imaginary
    /// axis; for Euler and RK2 (no interval: every step gains norm) where one step would double `|q|²`;
    /// infinite for the exponential maps.
    pub step_angle_limit: f64,
    /// End of the stability interval on the negative real axis (`|R(−y)| ≤ 1` for `y` up to it).
    pub real_axis_limit: f64,
    /// Coefficients (constant first) of `|R(ix)|² − 1` as a polynomial in `x²`, `x = h|ω|/2`: the relative
    /// change of `|q|²` per step with a held rate and no stabilization. All zero for the exponential maps.
    pub norm_change_polynomial: [f64; 7],
}

impl Information {
    /// `|R(ix)|² − 1` at the step angle `h|ω|` (rad), from its polynomial (no cancellation).
    #[must_use]
    pub fn norm_change(&self, step_angle: f64) -> f64 {
        let x = 0.5 * step_angle;
        tableau::poly_eval(&self.norm_change_polynomial, x * x)
    }

    /// `|R(ix)|²`: the per-step factor of `|q|²` at the step angle `h|ω|` (rad).
    #[must_use]
    pub fn norm_factor(&self, step_angle: f64) -> f64 {
        1.0 + self.norm_change(step_angle)
    }
}

/// An integration scheme for `q' = ½ q ⊗ (0, ω)` in precision `T`.
pub trait Scheme<T: Real>: Copy {
    /// Order, bounds and norm behaviour of the scheme.
    fn information(&self) -> Information;

    /// Refuses a step of `h` (s) the scheme cannot take: by default one whose step angle exceeds
    /// [`Information::step_angle_limit`].
    ///
    /// # Errors
    /// [`Error::StepAngleBeyondStability`] (and for [`Baumgarte`], [`Error::GainBeyondStability`]).
    #[inline(always)]
    fn check<G: Segment<T>>(&self, segment: &G, h: T) -> Result<(), Error> {
        check_step_angle(self.information().step_angle_limit, segment, h)
    }

    /// The increment `Δ` of one step of `h` (s) from `q` over `segment`: the new attitude is `q + Δ`,
    /// formed without the cancellation of `q + Δ − q` so that [`crate::accumulate`] can add it with
    /// compensation. No checks: call [`Scheme::check`] first (the propagator does).
    fn increment<G: Segment<T>>(&self, q: Quat<T>, segment: &G, h: T) -> Quat<T>;

    /// The step as a right factor, an unevaluated sum `hi + lo`: the new attitude is
    /// `q ⊗ (1 + hi + lo)` (body-frame rates act on the right, so every scheme's step is one; for
    /// [`Baumgarte`], whose term depends on `|q|`, this holds for a unit `q`). What
    /// [`crate::accumulate::FloatFloat`] multiplies exactly. By default [`Scheme::increment`] from the
    /// identity, with no low part; the exponential maps keep the rounding of the rotation vector in `lo`.
    #[doc(hidden)]
    #[inline(always)]
    fn right_factor<G: Segment<T>>(&self, segment: &G, h: T) -> (Quat<T>, Quat<T>) {
        (self.increment(Quat::IDENTITY, segment, h), Quat::ZERO)
    }
}

/// The step-angle check shared by every scheme: `max|ω·h| ≤ limit` (skipped for an infinite limit).
#[inline(always)]
pub(crate) fn check_step_angle<T: Real, G: Segment<T>>(
    limit: f64,
    segment: &G,
    h: T,
) -> Result<(), Error> {
    if limit.is_finite() {
        let angle_sq = segment.max_step_angle_squared(h);
        // Rounded up in T (2 ulp of margin): a step at the bound is never refused for the rounding.
        let l = T::from_f64(limit) * (T::ONE + T::EPSILON + T::EPSILON);
        if !(angle_sq <= l * l) {
            return Err(Error::StepAngleBeyondStability {
                step_angle: angle_sq.sqrt().to_f64(),
                limit,
            });
        }
    }
    Ok(())
}

/// Any scheme, chosen at run time (the host lab's way; firmware names one type instead).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SchemeKind {
    /// [`Euler`].
    Euler,
    /// [`Rk2`].
    Rk2,
    /// [`Rk3`].
    Rk3,
    /// [`Rk4`].
    Rk4,
    /// [`Rk5`].
    Rk5,
    /// [`ExpMap`].
    ExpMap,
    /// [`Magnus4`].
    Magnus4,
    /// [`Cf4`].
    Cf4,
}

impl SchemeKind {
    /// Every scheme.
    pub const ALL: [SchemeKind; 8] = [
        SchemeKind::Euler,
        SchemeKind::Rk2,
        SchemeKind::Rk3,
        SchemeKind::Rk4,
        SchemeKind::Rk5,
        SchemeKind::ExpMap,
        SchemeKind::Magnus4,
        SchemeKind::Cf4,
    ];
}

macro_rules! each {
    ($self:ident, $s:ident => $e:expr) => {
        dispatch!(*$self;
            SchemeKind::Euler => Euler,
            SchemeKind::Rk2 => Rk2,
            SchemeKind::Rk3 => Rk3,
            SchemeKind::Rk4 => Rk4,
            SchemeKind::Rk5 => Rk5,
            SchemeKind::ExpMap => ExpMap,
            SchemeKind::Magnus4 => Magnus4,
            SchemeKind::Cf4 => Cf4;
            $s => $e)
    };
}

impl SchemeKind {
    /// What the chosen scheme is: order, stability bounds, norm factor ([`Information`]).
    #[must_use]
    pub fn information(self) -> Information {
        let this = &self;
        each!(this, s => s.information())
    }
}

impl<T: Real> Scheme<T> for SchemeKind {
    #[inline]
    fn information(&self) -> Information {
        SchemeKind::information(*self)
    }
    #[inline]
    fn check<G: Segment<T>>(&self, segment: &G, h: T) -> Result<(), Error> {
        each!(self, s => s.check(segment, h))
    }
    #[inline]
    fn increment<G: Segment<T>>(&self, q: Quat<T>, segment: &G, h: T) -> Quat<T> {
        each!(self, s => s.increment(q, segment, h))
    }
    #[inline]
    fn right_factor<G: Segment<T>>(&self, segment: &G, h: T) -> (Quat<T>, Quat<T>) {
        each!(self, s => s.right_factor(segment, h))
    }
}
