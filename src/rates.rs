//! Input models: what is known of the body rate ω(t) inside one step.
//!
//! A scheme asks a [`RateModel`] for the rate at fractions `c ∈ [0, 1]` of the step (Runge–Kutta stages),
//! or for the rotation vector of the whole step (exponential-map schemes). All rates are body-frame rad/s.

use crate::vec3::all_finite;
use crate::{Real, Vec3};

/// What a scheme needs to know about ω(t) over one step `[t, t + h]`.
pub trait RateModel<T: Real> {
    /// ω(t + c h) (rad/s). `c` is a Butcher node; models return their samples exactly at their nodes.
    fn rate_at(&self, c: f64) -> Vec3<T>;

    /// `Some(ω)` if the model holds the rate constant over the step (the seed's assumption V1):
    /// a Runge–Kutta step then reduces to one quaternion product.
    fn held_rate(&self) -> Option<Vec3<T>>;

    /// Half the rotation vector of the step, `φ/2` (rad), from the half step `hh = h/2` (s), for
    /// exponential-map schemes: the step is `q ← q ⊗ exp((0, φ/2))`.
    fn half_rotation_vector(&self, hh: T) -> Vec3<T>;

    /// `max |ω h|²` over the samples (rad²): the squared step angle for the stability check, formed as
    /// `|ω·h|²` (scaled before squaring, so a tiny rate times a huge step cannot underflow to zero).
    /// Infinite if it overflows, which the check refuses.
    fn max_step_angle_squared(&self, h: T) -> T;

    /// `true` if every sample is finite.
    fn is_finite(&self) -> bool;
}

/// Rate held constant over the step: one sample, at the start (or the step's representative value).
/// Exact for constant rotation; first order on a varying rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hold<T> {
    w: Vec3<T>,
}

impl<T: Real> Hold<T> {
    /// Rate `w` (rad/s) held over the step.
    #[inline(always)]
    #[must_use]
    pub fn new(w: Vec3<T>) -> Self {
        Self { w }
    }
}

impl<T: Real> RateModel<T> for Hold<T> {
    #[inline(always)]
    fn rate_at(&self, _c: f64) -> Vec3<T> {
        self.w
    }
    #[inline(always)]
    fn held_rate(&self) -> Option<Vec3<T>> {
        Some(self.w)
    }
    #[inline(always)]
    fn half_rotation_vector(&self, hh: T) -> Vec3<T> {
        self.w * hh
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.w * h).norm_squared()
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        self.w.is_finite()
    }
}

/// Rate linear between the samples at the start and the end of the step.
/// Second order on a varying rate (the trapezoid rule's error in ∫ω), whatever the scheme's order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Linear<T> {
    w0: Vec3<T>,
    w1: Vec3<T>,
}

impl<T: Real> Linear<T> {
    /// Rates `w0` at the start and `w1` at the end of the step (rad/s).
    #[inline(always)]
    #[must_use]
    pub fn new(w0: Vec3<T>, w1: Vec3<T>) -> Self {
        Self { w0, w1 }
    }
}

impl<T: Real> RateModel<T> for Linear<T> {
    #[inline(always)]
    fn rate_at(&self, c: f64) -> Vec3<T> {
        if c == 0.0 {
            self.w0
        } else if c == 1.0 {
            self.w1
        } else {
            self.w0 + (self.w1 - self.w0) * T::from_f64(c)
        }
    }
    #[inline(always)]
    fn held_rate(&self) -> Option<Vec3<T>> {
        None
    }
    /// `φ = h(ω₀ + ω₁)/2 + (h²/12) ω₀ × ω₁`: the mean rate plus the Magnus commutator term, which makes
    /// the increment fourth-order exact for a rate that really is linear in time.
    #[inline(always)]
    fn half_rotation_vector(&self, hh: T) -> Vec3<T> {
        // φ/2 = (hh/2)(ω₀ + ω₁) + (hh²/6) ω₀ × ω₁.
        let mean = (self.w0 + self.w1) * (hh * T::HALF);
        let comm = self.w0.cross(self.w1) * (hh * hh * T::from_f64(1.0 / 6.0));
        mean + comm
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.w0 * h)
            .norm_squared()
            .max((self.w1 * h).norm_squared())
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        all_finite(&[self.w0, self.w1])
    }
}

/// Rate quadratic through samples at the start, the middle and the end of the step (a gyro sampled at
/// twice the step rate). Runge–Kutta stages at c = 0, ½, 1 see the samples themselves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quadratic<T> {
    w0: Vec3<T>,
    wm: Vec3<T>,
    w1: Vec3<T>,
}

impl<T: Real> Quadratic<T> {
    /// Rates at the start `w0`, middle `wm` and end `w1` of the step (rad/s).
    #[inline(always)]
    #[must_use]
    pub fn new(w0: Vec3<T>, wm: Vec3<T>, w1: Vec3<T>) -> Self {
        Self { w0, wm, w1 }
    }
}

impl<T: Real> RateModel<T> for Quadratic<T> {
    #[inline(always)]
    fn rate_at(&self, c: f64) -> Vec3<T> {
        if c == 0.0 {
            self.w0
        } else if c == 0.5 {
            self.wm
        } else if c == 1.0 {
            self.w1
        } else {
            // Lagrange basis on the nodes 0, ½, 1 (constants: c is a tableau node).
            let l0 = 2.0 * (c - 0.5) * (c - 1.0);
            let lm = -4.0 * c * (c - 1.0);
            let l1 = 2.0 * c * (c - 0.5);
            self.w0 * T::from_f64(l0) + self.wm * T::from_f64(lm) + self.w1 * T::from_f64(l1)
        }
    }
    #[inline(always)]
    fn held_rate(&self) -> Option<Vec3<T>> {
        None
    }
    /// Fourth-order Magnus increment: `φ = (h/6)(ω₀ + 4ω_m + ω₁) + (h²/12) ω₀ × ω₁` (Simpson's rule for ∫ω,
    /// and the commutator term from the end samples, whose error is O(h⁵)).
    #[inline(always)]
    fn half_rotation_vector(&self, hh: T) -> Vec3<T> {
        // φ/2 = (hh/6)(ω₀ + 4ω_m + ω₁) + (hh²/6) ω₀ × ω₁.
        let sixth = T::from_f64(1.0 / 6.0);
        let simpson = (self.w0 + self.wm * T::from_f64(4.0) + self.w1) * (hh * sixth);
        let comm = self.w0.cross(self.w1) * (hh * hh * sixth);
        simpson + comm
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.w0 * h)
            .norm_squared()
            .max((self.wm * h).norm_squared())
            .max((self.w1 * h).norm_squared())
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        all_finite(&[self.w0, self.wm, self.w1])
    }
}

/// The step's rotation vector `φ` (rad) given directly, from delta-angle (integrated-rate) sensors after a
/// coning correction (see [`crate::coning`]). Exponential-map schemes apply `exp_q(φ)` exactly; Runge–Kutta
/// schemes see the equivalent constant rate `φ/h`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotationVector<T> {
    phi: Vec3<T>,
    h: T,
}

impl<T: Real> RotationVector<T> {
    /// Rotation vector `phi` (rad, body frame) over a step of `h` (s).
    #[inline(always)]
    #[must_use]
    pub fn new(phi: Vec3<T>, h: T) -> Self {
        Self { phi, h }
    }
}

impl<T: Real> RateModel<T> for RotationVector<T> {
    #[inline(always)]
    fn rate_at(&self, _c: f64) -> Vec3<T> {
        self.phi * (T::ONE / self.h)
    }
    #[inline(always)]
    fn held_rate(&self) -> Option<Vec3<T>> {
        Some(self.phi * (T::ONE / self.h))
    }
    #[inline(always)]
    fn half_rotation_vector(&self, _hh: T) -> Vec3<T> {
        self.phi * T::HALF
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, _h: T) -> T {
        self.phi.norm_squared()
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        self.phi.is_finite()
    }
}

/// Rate from the sample history: a cubic through four equally spaced samples ω_{k−2}, ω_{k−1}, ω_k, ω_{k+1},
/// on the last interval [t_k, t_{k+1}] — fourth order from one gyro sample per step, without latency.
///
/// Runge–Kutta stages read the cubic; the exponential map uses the Adams–Moulton integral
/// `∫ω = h(ω_{k−2} − 5ω_{k−1} + 19ω_k + 9ω_{k+1})/24` plus the Magnus commutator
/// `(h²/12) ω(t_mid) × (ω_{k+1} − ω_k)` (ω(t_mid) from the cubic). With three samples the same construction
/// uses a quadratic through ω_{k−1}, ω_k, ω_{k+1} (third order), with two the linear model (second order):
/// see [`crate::SampleHistory`], which builds the right one as samples arrive. Samples must be equally spaced
/// (uniform `dt`); with jittered sampling the order drops to that of the linear model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct History<T> {
    /// Samples at c = −2, −1, 0, 1 (oldest first); with fewer, the leading entries are unused.
    w: [Vec3<T>; 4],
    /// 2, 3 or 4 samples.
    count: u8,
}

impl<T: Real> History<T> {
    /// A cubic (4 samples), quadratic (3) or linear (2) model from `samples` (oldest first, uniform spacing,
    /// the last interval being the step). `None` for fewer than 2 or more than 4 samples.
    #[must_use]
    pub fn new(samples: &[Vec3<T>]) -> Option<Self> {
        let z = Vec3::ZERO;
        let (w, count) = match *samples {
            [a, b] => ([z, z, a, b], 2),
            [a, b, c] => ([z, a, b, c], 3),
            [a, b, c, d] => ([a, b, c, d], 4),
            _ => return None,
        };
        Some(Self { w, count })
    }

    /// Lagrange weights at c for the nodes of this model (−2, −1, 0, 1; the unused ones zero).
    #[inline(always)]
    fn weights(&self, c: f64) -> [f64; 4] {
        match self.count {
            4 => [
                -(c + 1.0) * c * (c - 1.0) / 6.0,
                (c + 2.0) * c * (c - 1.0) / 2.0,
                -(c + 2.0) * (c + 1.0) * (c - 1.0) / 2.0,
                (c + 2.0) * (c + 1.0) * c / 6.0,
            ],
            3 => [
                0.0,
                c * (c - 1.0) / 2.0,
                -(c + 1.0) * (c - 1.0),
                (c + 1.0) * c / 2.0,
            ],
            _ => [0.0, 0.0, 1.0 - c, c],
        }
    }

    #[inline(always)]
    fn combine(&self, k: [f64; 4]) -> Vec3<T> {
        let mut s = Vec3::ZERO;
        for (w, &ki) in self.w.iter().zip(&k) {
            if ki != 0.0 {
                s += *w * T::from_f64(ki);
            }
        }
        s
    }
}

impl<T: Real> RateModel<T> for History<T> {
    #[inline(always)]
    fn rate_at(&self, c: f64) -> Vec3<T> {
        if c == 0.0 {
            self.w[2]
        } else if c == 1.0 {
            self.w[3]
        } else {
            self.combine(self.weights(c))
        }
    }
    #[inline(always)]
    fn held_rate(&self) -> Option<Vec3<T>> {
        None
    }
    #[inline(always)]
    fn half_rotation_vector(&self, hh: T) -> Vec3<T> {
        // ∫₀¹ of the Lagrange basis: cubic (1, −5, 19, 9)/24; quadratic (−1, 8, 5)/12; linear (1, 1)/2.
        let integral = match self.count {
            4 => [1.0 / 24.0, -5.0 / 24.0, 19.0 / 24.0, 9.0 / 24.0],
            3 => [0.0, -1.0 / 12.0, 8.0 / 12.0, 5.0 / 12.0],
            _ => [0.0, 0.0, 0.5, 0.5],
        };
        // φ = h∫ω + (h²/12) ω_mid × (ω₁ − ω₀), so with h = 2hh: φ/2 = hh∫ω + (hh²/6) ω_mid × (ω₁ − ω₀).
        let mean = self.combine(integral) * hh;
        let mid = self.combine(self.weights(0.5));
        let comm = mid.cross(self.w[3] - self.w[2]) * (hh * hh * T::from_f64(1.0 / 6.0));
        mean + comm
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        // Unused leading entries are zero, so the maximum over all four is the maximum over the samples.
        let mut m = T::ZERO;
        for w in &self.w {
            m = m.max((*w * h).norm_squared());
        }
        m
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        all_finite(&self.w)
    }
}

/// `½ − √3/6`: the first Gauss–Legendre node of the step.
pub const GAUSS_1: f64 = 0.5 - 0.288_675_134_594_812_9;
/// `½ + √3/6`: the second Gauss–Legendre node of the step.
pub const GAUSS_2: f64 = 0.5 + 0.288_675_134_594_812_9;

/// Rates sampled at the two Gauss–Legendre points `t + (½ ∓ √3/6)h` of the step (a gyro sampled at twice
/// the step rate with the right phase, or a rate reconstructed there). Linear between (and beyond) them for
/// Runge–Kutta stages; 4th-order Magnus for the exponential map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GaussPair<T> {
    w1: Vec3<T>,
    w2: Vec3<T>,
}

impl<T: Real> GaussPair<T> {
    /// Rates at the first and second Gauss point (rad/s).
    #[inline(always)]
    #[must_use]
    pub fn new(w1: Vec3<T>, w2: Vec3<T>) -> Self {
        Self { w1, w2 }
    }
}

impl<T: Real> RateModel<T> for GaussPair<T> {
    #[inline(always)]
    fn rate_at(&self, c: f64) -> Vec3<T> {
        if c == GAUSS_1 {
            self.w1
        } else if c == GAUSS_2 {
            self.w2
        } else {
            let f = (c - GAUSS_1) / (GAUSS_2 - GAUSS_1);
            self.w1 + (self.w2 - self.w1) * T::from_f64(f)
        }
    }
    #[inline(always)]
    fn held_rate(&self) -> Option<Vec3<T>> {
        None
    }
    /// Magnus-4: `φ = (h/2)(ω₁ + ω₂) + (√3 h²/12) ω₁ × ω₂`.
    #[inline(always)]
    fn half_rotation_vector(&self, hh: T) -> Vec3<T> {
        magnus4_half(self.w1, self.w2, hh)
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.w1 * h)
            .norm_squared()
            .max((self.w2 * h).norm_squared())
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        all_finite(&[self.w1, self.w2])
    }
}

/// Half the Magnus-4 rotation vector from the rates at the two Gauss points:
/// `φ/2 = (hh/2)(ω₁ + ω₂) + (√3 hh²/6) ω₁ × ω₂` with `hh = h/2`.
#[inline(always)]
pub(crate) fn magnus4_half<T: Real>(w1: Vec3<T>, w2: Vec3<T>, hh: T) -> Vec3<T> {
    let mean = (w1 + w2) * (hh * T::HALF);
    let comm = w1.cross(w2) * (hh * hh * T::from_f64(0.288_675_134_594_812_9));
    mean + comm
}
