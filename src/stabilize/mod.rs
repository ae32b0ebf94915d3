//! Stabilization: what keeps `|q| = 1` (the seed's first integral `N = |q|² − 1 = 0`).
//!
//! | policy | where it acts | cost | what it guarantees |
//! |---|---|---|---|
//! | [`Off`] | nowhere | 0 | `N` follows the scheme's norm factor `|R(ix)|²` (RK4: `(1 − β)^n`, the seed's eq. (3)-(4)) |
//! | [`Normalize`] | after every step: `q / |q|` | sqrt + div | `|N| ≤ 4ε` after every step |
//! | [`FirstOrder`] | after every step: `q (3 − |q|²)/2` | 4 mul, no sqrt | `N_after ≈ −¾ N_before²` + rounding: `|N| ≤ 4ε` once near 1 |
//! | [`Every`]`(n)` | after every n-th step: `q / |q|` | sqrt every n | `|N|` ≤ n steps of drift |
//! | [`Baumgarte`]` { k }` | inside every stage: `q' = ½(Ω − 4kN E) q` (the seed's eq. (7)) | 1 norm per stage | with RK: a jump on step 1, then a wrong `N∞` unless k is tuned (the seed's §3) |
//!
//! A stabilizer is either a zero-sized type (a firmware that names one links only it) or the runtime
//! [`Policy`] enum (the host lab iterates over all of them).

mod baumgarte;
mod normalize;

pub use baumgarte::Baumgarte;
pub use normalize::{Every, FirstOrder, Normalize};

use crate::{Error, Quat, Real};

/// How a stabilization policy takes part in a step.
pub trait Stabilizer<T: Real>: Copy {
    /// Checks the parameters (`Every(0)` and a negative or non-finite `k` are refused).
    fn validate(&self) -> Result<(), Error> {
        Ok(())
    }

    /// `true` if the policy adds a term to the right-hand side (Baumgarte). Schemes then evaluate the
    /// full nonlinear right-hand side at every stage instead of their held-rate shortcut.
    #[inline(always)]
    fn has_rhs_term(&self) -> bool {
        false
    }

    /// The scalar `s(q)` of the modified right-hand side `q' = ½ [q ⊗ (0, ω) + s(q) q]`, the seed's eq. (7)
    /// form `½(Ω − 4kN·E) q` (Baumgarte: `s = −4kN`; zero if none).
    #[inline(always)]
    fn rhs_scalar(&self, _q: Quat<T>) -> T {
        T::ZERO
    }

    /// The rate (1/s) at which the right-hand side term pulls `N` back to zero: its linearization
    /// `N' = −λ N` (Baumgarte: λ = 4k; zero if none). A step needs `λ h` within the scheme's real-axis bound.
    #[inline(always)]
    fn norm_stiffness(&self) -> T {
        T::ZERO
    }

    /// Exact solution of the radial part `n' = s(q) n` over `h`, as `ρ − 1` for the scale factor `ρ` on `q`
    /// (computed without cancellation), for schemes that integrate the rotation exactly and treat the
    /// commuting radial term separately (the exponential map). Zero if there is no right-hand side term.
    #[inline(always)]
    fn radial_flow_scale_minus_one(&self, _q: Quat<T>, _h: T) -> T {
        T::ZERO
    }

    /// Post-step correction as an increment: `Some(Δ)` with the corrected attitude `q + Δ`, or `None` when
    /// no correction is due. `pending` counts the steps since the last correction, this one included.
    /// Increments (rather than new values) let the propagator add them with compensated summation.
    fn correction(&self, q: Quat<T>, pending: u32) -> Option<Quat<T>>;
}

/// No stabilization: the seed's plain kinematic equation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Off;

impl<T: Real> Stabilizer<T> for Off {
    #[inline(always)]
    fn correction(&self, _q: Quat<T>, _pending: u32) -> Option<Quat<T>> {
        None
    }
}

/// Any stabilization policy, chosen at run time (the host lab's way; firmware names one type instead).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Policy<T> {
    /// See [`Off`].
    Off,
    /// See [`Normalize`].
    Normalize,
    /// See [`FirstOrder`].
    FirstOrder,
    /// See [`Every`]: exact normalization every n-th step.
    Every(u32),
    /// See [`Baumgarte`]: the seed's eq. (7) with gain `k` (1/s).
    Baumgarte {
        /// Stabilization gain `k` (1/s), `k ≥ 0`.
        k: T,
    },
}

impl<T: Real> Policy<T> {
    /// A short label, e.g. `"Every(10)"` is `"Every"`; parameters are reported separately.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Policy::Off => "Off",
            Policy::Normalize => "Normalize",
            Policy::FirstOrder => "FirstOrder",
            Policy::Every(_) => "Every",
            Policy::Baumgarte { .. } => "Baumgarte",
        }
    }
}

macro_rules! dispatch {
    ($self:ident, $p:ident => $e:expr) => {
        match *$self {
            Policy::Off => {
                let $p = Off;
                $e
            }
            Policy::Normalize => {
                let $p = Normalize;
                $e
            }
            Policy::FirstOrder => {
                let $p = FirstOrder;
                $e
            }
            Policy::Every(n) => {
                let $p = Every(n);
                $e
            }
            Policy::Baumgarte { k } => {
                let $p = Baumgarte { k };
                $e
            }
        }
    };
}

impl<T: Real> Stabilizer<T> for Policy<T> {
    fn validate(&self) -> Result<(), Error> {
        dispatch!(self, p => Stabilizer::<T>::validate(&p))
    }
    #[inline]
    fn has_rhs_term(&self) -> bool {
        matches!(self, Policy::Baumgarte { .. })
    }
    #[inline]
    fn rhs_scalar(&self, q: Quat<T>) -> T {
        dispatch!(self, p => p.rhs_scalar(q))
    }
    #[inline]
    fn norm_stiffness(&self) -> T {
        dispatch!(self, p => Stabilizer::<T>::norm_stiffness(&p))
    }
    #[inline]
    fn radial_flow_scale_minus_one(&self, q: Quat<T>, h: T) -> T {
        dispatch!(self, p => p.radial_flow_scale_minus_one(q, h))
    }
    #[inline]
    fn correction(&self, q: Quat<T>, pending: u32) -> Option<Quat<T>> {
        dispatch!(self, p => p.correction(q, pending))
    }
}
