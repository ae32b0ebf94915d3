//! Stabilization: what keeps `|q| = 1` (the seed's first integral `N = |q|² − 1 = 0`), applied after each
//! step as an increment (so a compensated [accumulator](crate::accumulate) adds it exactly like a step).
//!
//! | policy | after a step | cost per step | what it guarantees |
//! |---|---|---|---|
//! | [`Off`] | nothing | 0 | `N` follows the scheme's norm factor (RK4: `(1 − β)^n`, the seed's eq. (3)–(4)) |
//! | [`Normalize`] | `q / ‖q‖` | 9 mul, 9 add, 1 sqrt, 1 div | `‖N‖ ≤ 4ε` after a step that changed `‖q‖²` by a factor in [½, 2] (details below) |
//! | [`FirstOrder`] | `q (3 − ‖q‖²)/2` | 9 mul, 8 add | `N ↦ −¾N² − ¼N³` + rounding: `‖N‖ ≤ 4ε` while the steps change `‖q‖²` by less than 2e-4 (f32) |
//! | [`Every`]`(n)` | `q / ‖q‖` every n-th step | as [`Normalize`], every n steps | `‖N‖` ≤ n steps of drift |
//!
//! (`‖·‖` is the quaternion norm; the costs count the correction and the addition of its increment.)
//! The seed's Baumgarte stabilization is not a post-step policy: it changes the right-hand side inside
//! every stage, and lives with the Runge–Kutta engine as [`crate::scheme::Baumgarte`].
//!
//! A stabilizer is a zero-sized type (a firmware that names one links only it) or the run-time
//! [`StabilizerKind`].

use crate::dispatch::dispatch;
use crate::{Error, Quat, Real};

/// A post-step stabilization policy.
pub trait Stabilizer: Copy {
    /// Checks the parameters (`Every(0)` is refused).
    ///
    /// # Errors
    /// [`Error::InvalidStabilizer`].
    #[inline(always)]
    fn validate(&self) -> Result<(), Error> {
        Ok(())
    }

    /// The correction as an increment: `Some(Δ)` with the corrected attitude `q + Δ`, or `None` when none
    /// is due. `pending` counts the steps since the last correction, this one included.
    fn correction<T: Real>(&self, q: Quat<T>, pending: u32) -> Option<Quat<T>>;
}

/// No stabilization: the seed's plain kinematic equation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Off;

impl Stabilizer for Off {
    #[inline(always)]
    fn correction<T: Real>(&self, _q: Quat<T>, _pending: u32) -> Option<Quat<T>> {
        None
    }
}

/// Exact normalization `q ← q / ‖q‖` after every step (the seed's §4).
///
/// After each step `‖N‖ ≤ 4ε` with the plain accumulator when the step changed `‖q‖²` by a factor `F`
/// within [½, 2]: `‖q‖²` carries ≤ 2ε relative rounding, the reciprocal square root ≤ 1.5ε, the four products
/// ≤ ε/2 each, and `N` doubles relative errors of `‖q‖`. For any `F` the bound is `(6 + 7(√F − 1)⁺)ε`
/// (`x⁺ = max(x, 0)`): the correction is an increment `q (1/‖q‖ − 1)`, which for `F ≫ 1` nearly cancels `q`,
/// so its rounding (≈ 3.5ε relative, from the factor and the product) counts `√F` times relative to the
/// result. Only a Runge–Kutta step near its stability bound, or Baumgarte's term with a large gain, changes
/// `‖q‖²` that much: a property test found `F = 11.4` and 4.8ε (Baumgarte over Rk4, a 5.6 rad step), the
/// fuzzers 7.7ε after `F ≈ 3`. tests/normalize.rs checks both bounds for `F` from 2⁻²⁰ to 2²⁰. With
/// [`Kahan`](crate::accumulate::Kahan) the compensation of the unnormalized sum is re-added after the
/// normalization (the fuzzers found 21ε).
///
/// ```
/// use quatprop::{stabilize::{Normalize, Stabilizer}, Quat};
/// let q = Quat::new(2.0_f64, 0.0, 0.0, 0.0);
/// let d = Normalize.correction(q, 1).unwrap();
/// assert_eq!(q + d, Quat::IDENTITY);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Normalize;

/// The increment `q/‖q‖ − q = q (1/‖q‖ − 1)` with `1/‖q‖ − 1 = (1 − ‖q‖²) / (‖q‖ (1 + ‖q‖))`, free of
/// cancellation (one square root, one division). Non-finite for a zero or non-finite `q`; the propagator
/// then refuses the step.
#[inline(always)]
fn normalizing_increment<T: Real>(q: Quat<T>) -> Quat<T> {
    let n2 = q.norm_squared();
    let n = n2.sqrt();
    q * ((T::ONE - n2) / (n * (T::ONE + n)))
}

impl Stabilizer for Normalize {
    #[inline(always)]
    fn correction<T: Real>(&self, q: Quat<T>, _pending: u32) -> Option<Quat<T>> {
        Some(normalizing_increment(q))
    }
}

/// First-order (Newton) normalization without a square root: `q ← q (3 − ‖q‖²)/2 = q (1 − N/2)`.
///
/// It maps `N` to `−¾N² − ¼N³`, so one application lands at rounding level when the step's own change of
/// `‖q‖²` is below about `√(4ε/3)` (2.0e-4 in f32; the exponential maps change it only by rounding), and
/// `‖N‖` then stays within 4ε (the tests check 10⁶ steps in f32 and f64). A larger change (a Runge–Kutta
/// step of a fast-varying rate: the fuzzers found 39ε after one Rk2 step of 0.07 rad) is reduced
/// quadratically over the next steps. It converges for `‖q‖² ∈ (0, 5)`. Far from unit norm use
/// [`Normalize`] or [`Every`].
///
/// ```
/// use quatprop::{stabilize::{FirstOrder, Stabilizer}, Quat};
/// let q = Quat::new(1.0 + 1e-4_f64, 0.0, 0.0, 0.0); // N ≈ 2e-4
/// let fixed = q + FirstOrder.correction(q, 1).unwrap();
/// assert!(fixed.norm_error().abs() < 1e-7); // ≈ −¾N²
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FirstOrder;

impl Stabilizer for FirstOrder {
    #[inline(always)]
    fn correction<T: Real>(&self, q: Quat<T>, _pending: u32) -> Option<Quat<T>> {
        // q (3 − ‖q‖²)/2 = q + q (1 − ‖q‖²)/2; 1 − ‖q‖² is exact (Sterbenz) for ‖q‖² ∈ [½, 2].
        Some(q * (T::HALF * (T::ONE - q.norm_squared())))
    }
}

/// Exact normalization every n-th step (`n ≥ 1`; `Every(1)` is [`Normalize`]).
///
/// Between corrections `N` drifts as under [`Off`]: at most `n` steps of the scheme's norm factor plus
/// rounding.
///
/// ```
/// use quatprop::{stabilize::{Every, Stabilizer}, Error, Quat};
/// let q = Quat::new(2.0_f32, 0.0, 0.0, 0.0);
/// assert_eq!(Every(3).correction(q, 2), None);
/// assert!(Every(3).correction(q, 3).is_some());
/// assert_eq!(Every(0).validate(), Err(Error::InvalidStabilizer));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Every(pub u32);

impl Stabilizer for Every {
    fn validate(&self) -> Result<(), Error> {
        if self.0 == 0 {
            Err(Error::InvalidStabilizer)
        } else {
            Ok(())
        }
    }
    #[inline]
    fn correction<T: Real>(&self, q: Quat<T>, pending: u32) -> Option<Quat<T>> {
        if pending >= self.0 {
            Some(normalizing_increment(q))
        } else {
            None
        }
    }
}

/// Any stabilization policy, chosen at run time (the host lab's way; firmware names one type instead).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum StabilizerKind {
    /// See [`Off`].
    Off,
    /// See [`Normalize`].
    Normalize,
    /// See [`FirstOrder`].
    FirstOrder,
    /// See [`Every`]: exact normalization every n-th step.
    Every(u32),
}

impl StabilizerKind {
    /// A short label without parameters, e.g. `"Every"`.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            StabilizerKind::Off => "Off",
            StabilizerKind::Normalize => "Normalize",
            StabilizerKind::FirstOrder => "FirstOrder",
            StabilizerKind::Every(_) => "Every",
        }
    }
}

macro_rules! each {
    ($self:ident, $p:ident => $e:expr) => {
        dispatch!(*$self;
            StabilizerKind::Off => Off,
            StabilizerKind::Normalize => Normalize,
            StabilizerKind::FirstOrder => FirstOrder,
            StabilizerKind::Every(n) => Every(n);
            $p => $e)
    };
}

impl Stabilizer for StabilizerKind {
    fn validate(&self) -> Result<(), Error> {
        each!(self, p => p.validate())
    }
    /// `Normalize` is `Every(1)` (`pending` is at least 1 after a step), so the two share one branch and
    /// one copy of the normalization.
    #[inline(always)]
    fn correction<T: Real>(&self, q: Quat<T>, pending: u32) -> Option<Quat<T>> {
        let every = match *self {
            StabilizerKind::Off => return None,
            StabilizerKind::FirstOrder => return FirstOrder.correction(q, pending),
            StabilizerKind::Normalize => 1,
            StabilizerKind::Every(n) => n,
        };
        Every(every).correction(q, pending)
    }
}
