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

use crate::{Quat, Real};

/// Adds increments to the attitude.
pub trait Accumulator<T: Real>: Copy {
    /// Returns `q + d`, updating any internal compensation.
    fn add(&mut self, q: Quat<T>, d: Quat<T>) -> Quat<T>;

    /// Forgets any compensation (after the attitude is replaced).
    fn reset(&mut self);
}

/// Plain addition `q + Δ`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
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
