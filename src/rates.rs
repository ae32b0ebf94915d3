//! Input models: what is known of the body rate ω(t) inside one step.
//!
//! A scheme asks a [`RateModel`] for the rate at fractions `c ∈ [0, 1]` of the step (Runge–Kutta stages),
//! or for the rotation vector of the whole step (exponential-map schemes). All rates are body-frame rad/s.
//! The models store ½ω, the factor the kinematic equation `q' = q ⊗ (0, ½ω)` uses, so no stage rescales.

use crate::{Real, Vec3};

/// What a scheme needs to know about ω(t) over one step `[t, t + h]`.
pub trait RateModel<T: Real> {
    /// ½ω(t + c h) (rad/s). `c` is a Butcher node; models return their samples exactly at their nodes.
    fn half_rate_at(&self, c: f64) -> Vec3<T>;

    /// `Some(½ω)` if the model holds the rate constant over the step (the seed's assumption V1):
    /// a Runge–Kutta step then reduces to one quaternion product.
    fn held_half_rate(&self) -> Option<Vec3<T>>;

    /// Half the rotation vector of the step, `φ/2` (rad), for exponential-map schemes:
    /// the exact `q ← q ⊗ exp_q(φ)` of the step is then `q ⊗ exp((0, φ/2))`.
    fn half_rotation_vector(&self, h: T) -> Vec3<T>;

    /// `max |ω|²` over the samples (rad²/s²), for the step-angle check.
    fn max_rate_squared(&self) -> T;

    /// `true` if every sample is finite.
    fn is_finite(&self) -> bool;
}

/// Rate held constant over the step: one sample, at the start (or the step's representative value).
/// Exact for constant rotation; first order on a varying rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hold<T> {
    half: Vec3<T>,
}

impl<T: Real> Hold<T> {
    /// Rate `w` (rad/s) held over the step.
    #[inline(always)]
    #[must_use]
    pub fn new(w: Vec3<T>) -> Self {
        Self { half: w * T::HALF }
    }
}

impl<T: Real> RateModel<T> for Hold<T> {
    #[inline(always)]
    fn half_rate_at(&self, _c: f64) -> Vec3<T> {
        self.half
    }
    #[inline(always)]
    fn held_half_rate(&self) -> Option<Vec3<T>> {
        Some(self.half)
    }
    #[inline(always)]
    fn half_rotation_vector(&self, h: T) -> Vec3<T> {
        self.half * h
    }
    #[inline(always)]
    fn max_rate_squared(&self) -> T {
        self.half.norm_squared() * T::from_f64(4.0)
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        self.half.is_finite()
    }
}

/// Rate linear between the samples at the start and the end of the step.
/// Second order on a varying rate (the trapezoid rule's error in ∫ω), whatever the scheme's order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Linear<T> {
    h0: Vec3<T>,
    h1: Vec3<T>,
}

impl<T: Real> Linear<T> {
    /// Rates `w0` at the start and `w1` at the end of the step (rad/s).
    #[inline(always)]
    #[must_use]
    pub fn new(w0: Vec3<T>, w1: Vec3<T>) -> Self {
        Self {
            h0: w0 * T::HALF,
            h1: w1 * T::HALF,
        }
    }
}

impl<T: Real> RateModel<T> for Linear<T> {
    #[inline(always)]
    fn half_rate_at(&self, c: f64) -> Vec3<T> {
        if c == 0.0 {
            self.h0
        } else if c == 1.0 {
            self.h1
        } else {
            self.h0 + (self.h1 - self.h0) * T::from_f64(c)
        }
    }
    #[inline(always)]
    fn held_half_rate(&self) -> Option<Vec3<T>> {
        None
    }
    /// `φ = h(ω₀ + ω₁)/2 + (h²/12) ω₀ × ω₁`: the mean rate plus the Magnus commutator term, which makes
    /// the increment fourth-order exact for a rate that really is linear in time.
    #[inline(always)]
    fn half_rotation_vector(&self, h: T) -> Vec3<T> {
        // In half rates: φ/2 = h(h0 + h1)/2 + (h²/6) h0 × h1.
        let mean = (self.h0 + self.h1) * (h * T::HALF);
        let comm = self.h0.cross(self.h1) * (h * h * T::from_f64(1.0 / 6.0));
        mean + comm
    }
    #[inline(always)]
    fn max_rate_squared(&self) -> T {
        self.h0.norm_squared().max(self.h1.norm_squared()) * T::from_f64(4.0)
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        self.h0.is_finite() && self.h1.is_finite()
    }
}

/// Rate quadratic through samples at the start, the middle and the end of the step (a gyro sampled at
/// twice the step rate). Runge–Kutta stages at c = 0, ½, 1 see the samples themselves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quadratic<T> {
    h0: Vec3<T>,
    hm: Vec3<T>,
    h1: Vec3<T>,
}

impl<T: Real> Quadratic<T> {
    /// Rates at the start `w0`, middle `wm` and end `w1` of the step (rad/s).
    #[inline(always)]
    #[must_use]
    pub fn new(w0: Vec3<T>, wm: Vec3<T>, w1: Vec3<T>) -> Self {
        Self {
            h0: w0 * T::HALF,
            hm: wm * T::HALF,
            h1: w1 * T::HALF,
        }
    }
}

impl<T: Real> RateModel<T> for Quadratic<T> {
    #[inline(always)]
    fn half_rate_at(&self, c: f64) -> Vec3<T> {
        if c == 0.0 {
            self.h0
        } else if c == 0.5 {
            self.hm
        } else if c == 1.0 {
            self.h1
        } else {
            // Lagrange basis on the nodes 0, ½, 1.
            let l0 = 2.0 * (c - 0.5) * (c - 1.0);
            let lm = -4.0 * c * (c - 1.0);
            let l1 = 2.0 * c * (c - 0.5);
            self.h0 * T::from_f64(l0) + self.hm * T::from_f64(lm) + self.h1 * T::from_f64(l1)
        }
    }
    #[inline(always)]
    fn held_half_rate(&self) -> Option<Vec3<T>> {
        None
    }
    /// Fourth-order Magnus increment: `φ = (h/6)(ω₀ + 4ω_m + ω₁) + (h²/12) ω₀ × ω₁` (Simpson's rule for ∫ω,
    /// and the commutator term from the end samples, whose error is O(h⁵)).
    #[inline(always)]
    fn half_rotation_vector(&self, h: T) -> Vec3<T> {
        let simpson =
            (self.h0 + self.hm * T::from_f64(4.0) + self.h1) * (h * T::from_f64(1.0 / 6.0));
        let comm = self.h0.cross(self.h1) * (h * h * T::from_f64(1.0 / 6.0));
        simpson + comm
    }
    #[inline(always)]
    fn max_rate_squared(&self) -> T {
        self.h0
            .norm_squared()
            .max(self.hm.norm_squared())
            .max(self.h1.norm_squared())
            * T::from_f64(4.0)
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        self.h0.is_finite() && self.hm.is_finite() && self.h1.is_finite()
    }
}
