//! How the propagator adds a step's increment to the attitude: plainly, or with compensated summation.
//!
//! Every scheme and every post-step correction produces an increment `Δ` with the new attitude `q + Δ`
//! (`q ⊗ (e − 1)` for a rotation `e`, `q (f − 1)` for a normalization factor `f`), computed without the
//! cancellation of `e ≈ 1`. Adding `Δ` is then the only place where the attitude's own rounding happens.
//!
//! - [`Plain`]: `q + Δ`. In f32 the per-step rounding of `q` is biased for a steady rotation (the same
//!   increments every step), so the attitude error grows linearly with the step count.
//! - [`Kahan`]: compensated summation (Kahan 1965; Higham, *Accuracy and Stability of Numerical Algorithms*,
//!   §4.3): the low part lost in `q + Δ` is kept in a second quaternion and fed into the next addition, so the
//!   attitude carries about twice the working precision across steps. Four more additions and four more
//!   subtractions per addition, and 16 bytes of state (f32).
//! - [`FloatFloat`]: the attitude as an unevaluated sum `q + l` of two quaternions (twice the working
//!   precision), advanced by the step's exact product `(q + l) ⊗ (1 + p)`: the scheme's right factor `p`
//!   with its own low part ([`Scheme::right_factor`]), multiplied with error-free products (Dekker's
//!   TwoProduct, no FMA) and added with TwoSum. In f32 its own error stays at the rounding of its output
//!   over 10⁸ steps where `Plain` and `Kahan` drift linearly (docs/report, "Long horizon"), for several
//!   times the instructions of a plain step (docs/own_error.md), and 16 bytes of state (f32).

use crate::exact::{product_by_vector, two_sum_quat};
use crate::input::Segment;
use crate::scheme::Scheme;
use crate::{Quat, Real};

/// Adds increments to the attitude: [`Plain`], [`Kahan`] or [`FloatFloat`] (sealed: the float-float
/// accumulator's exact products reach into the schemes and input models, so the set is the library's).
pub trait Accumulator<T: Real>: Copy + sealed::Sealed {
    /// (Precision plumbing of [`FloatFloat`]; hidden, no stability promise.)
    /// `true` if [`Accumulator::advance`] uses the step's low parts ([`Segment::half_angle_split`]): the
    /// propagator then asks the input model for them ([`crate::input::InputModel::accept_split`]).
    #[doc(hidden)]
    const CARRIES_LOW_PARTS: bool = false;

    /// Returns `q + d`, updating any internal compensation.
    fn add(&mut self, q: Quat<T>, d: Quat<T>) -> Quat<T>;

    /// Advances `q` by one step of `scheme` over `segment` (length `h`, s): by default
    /// `add(q, scheme.increment(q, segment, h))`. ([`FloatFloat`] overrides it, repeating the signature:
    /// it multiplies by the scheme's right factor instead.)
    #[inline(always)]
    fn advance<S: Scheme<T>, G: Segment<T>>(
        &mut self,
        q: Quat<T>,
        scheme: &S,
        segment: &G,
        h: T,
    ) -> Quat<T> {
        self.add(q, scheme.increment(q, segment, h))
    }

    /// Forgets any compensation (after the attitude is replaced).
    fn reset(&mut self);
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::Plain {}
    impl<T> Sealed for super::Kahan<T> {}
    impl<T> Sealed for super::FloatFloat<T> {}
}

/// Plain addition `q + Δ`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Plain;

impl<T: Real> Accumulator<T> for Plain {
    #[inline(always)]
    fn add(&mut self, q: Quat<T>, d: Quat<T>) -> Quat<T> {
        q + d
    }
    #[inline(always)]
    fn reset(&mut self) {}
}

/// Kahan-compensated addition: `y = Δ − c; t = q + y; c = (t − q) − y; q = t`.
///
/// ```
/// use quatprop::accumulate::{Accumulator, Kahan, Plain};
/// use quatprop::Quat;
/// let tiny = Quat::new(1e-8_f32, 0.0, 0.0, 0.0); // below half an ulp of 1.0 in f32
/// let (mut plain, mut kahan) = (Quat::IDENTITY, Quat::IDENTITY);
/// let (mut p, mut k) = (Plain, Kahan::new());
/// for _ in 0..1000 {
///     plain = p.add(plain, tiny);
///     kahan = k.add(kahan, tiny);
/// }
/// assert_eq!(plain.w, 1.0); // every increment lost
/// assert!((kahan.w - 1.00001).abs() < 2e-7); // kept
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Kahan<T> {
    /// The negated low part not yet absorbed into the attitude.
    compensation: Quat<T>,
}

impl<T: Real> Kahan<T> {
    /// Starts with no compensation.
    #[must_use]
    pub fn new() -> Self {
        Self {
            compensation: Quat::ZERO,
        }
    }
}

impl<T: Real> Accumulator<T> for Kahan<T> {
    #[inline(always)]
    fn add(&mut self, q: Quat<T>, d: Quat<T>) -> Quat<T> {
        let y = d - self.compensation;
        let t = q + y;
        self.compensation = (t - q) - y;
        t
    }
    #[inline(always)]
    fn reset(&mut self) {
        self.compensation = Quat::ZERO;
    }
}

/// Float-float state: the attitude is `q + l`, `l` the low part kept here; each step is the exact product
/// `(q + l) ⊗ (1 + hi + lo)` of the scheme's right factor ([`Scheme::right_factor`]), added with TwoSum.
///
/// What is exact: `q ⊗ (0, h⃗)` for the vector part `h⃗` of `hi` (12 TwoProducts, Dot2 summation), the
/// addition to `q` (TwoSum), the rounding of the rotation vector's final sum and product (the exponential
/// maps' `lo`). What rounds, far below f32's ulp of the attitude: the low-order terms `q ⊗ lo + l ⊗ hi`,
/// and `q` times the scalar part of `hi`, which only scales the attitude (the stabilizer's business).
/// [`Propagator::attitude`](crate::Propagator::attitude) is `q`, the high part. Rates are body-frame rad/s,
/// steps in s, as everywhere (`q' = ½ q ⊗ (0, ω)`, Hamilton product).
///
/// ```
/// use quatprop::accumulate::FloatFloat;
/// use quatprop::{input::Hold, scheme::ExpMap, stabilize::FirstOrder, GyroSample, Propagator, Quat, Vec3};
/// let mut p = Propagator::new(Quat::IDENTITY, ExpMap, Hold, FirstOrder)?.with_accumulator(FloatFloat::new());
/// let spin = GyroSample::new(Vec3::new(0.0_f32, 0.0, 1.0)); // 1 rad/s about z
/// for _ in 0..100_000 {
///     p.push(spin, 1.0e-3)?;
/// }
/// // 100 s at 1 rad/s: the angle 100 rad (mod 2π) to f32's resolution, as if computed in f64 from the
/// // same f32 dt (the dt's own rounding, 4.75e-8 relative, is the time base's: see frontend::FixedPeriod).
/// let angle = 100_000.0 * f64::from(1.0e-3_f32);
/// let q = p.attitude();
/// assert!((f64::from(q.z) - (angle / 2.0).sin()).abs() < 1e-7);
/// assert!((f64::from(q.w) - (angle / 2.0).cos()).abs() < 1e-7);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FloatFloat<T> {
    /// The attitude's low part `l`.
    low: Quat<T>,
}

impl<T: Real> FloatFloat<T> {
    /// Starts with no low part.
    #[must_use]
    pub fn new() -> Self {
        Self { low: Quat::ZERO }
    }

    /// The attitude's low part `l` (the attitude is `q + l`).
    #[must_use]
    pub fn low(&self) -> Quat<T> {
        self.low
    }

    /// `q + l ← (q + l) ⊗ (1 + p + p_low)`, returning the new `q`. One copy per precision, not per scheme
    /// and input model (the exact product is long; a firmware naming several configurations links it once).
    #[inline(never)]
    fn multiply(&mut self, q: Quat<T>, p: Quat<T>, p_low: Quat<T>) -> Quat<T> {
        // (q + l) ⊗ (p + p_low) = q ⊗ (0, p⃗) (exact: d + d_low) + p_w·q + q ⊗ p_low + l ⊗ p
        // (+ l ⊗ p_low, negligible). p_w = cos|φ/2| − 1 only scales q (radial: no attitude error from its
        // rounding), so it is multiplied plainly, as is everything below ulp level.
        let (d, d_low) = product_by_vector(q, p.vector());
        let small = d_low + q * p.w + q * p_low + self.low * p;
        self.add_split(q, d, small)
    }

    /// `(q + l) + (d + small)` → `(q', l')`, `q'` the rounded sum and `l'` the rest (TwoSum twice).
    #[inline(always)]
    fn add_split(&mut self, q: Quat<T>, d: Quat<T>, small: Quat<T>) -> Quat<T> {
        let (s, e) = two_sum_quat(q, d);
        let (hi, lo) = two_sum_quat(s, self.low + (e + small));
        self.low = lo;
        hi
    }
}

impl<T: Real> Accumulator<T> for FloatFloat<T> {
    const CARRIES_LOW_PARTS: bool = true;
    #[inline(always)]
    fn add(&mut self, q: Quat<T>, d: Quat<T>) -> Quat<T> {
        self.add_split(q, d, Quat::ZERO)
    }
    #[inline(always)]
    fn advance<S: Scheme<T>, G: Segment<T>>(
        &mut self,
        q: Quat<T>,
        scheme: &S,
        segment: &G,
        h: T,
    ) -> Quat<T> {
        let (p, p_low) = scheme.right_factor(segment, h);
        self.multiply(q, p, p_low)
    }
    #[inline(always)]
    fn reset(&mut self) {
        self.low = Quat::ZERO;
    }
}
