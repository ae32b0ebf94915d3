//! The rate functions the input models hand to the schemes. Crate-private: a custom input model brings
//! its own [`Segment`].

use super::Segment;
use crate::gauss;
use crate::{Real, Vec3};

/// ω constant over the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeldRate<T>(pub(crate) Vec3<T>);

impl<T: Real> Segment<T> for HeldRate<T> {
    #[inline(always)]
    fn rate_at(&self, _c: f64) -> Vec3<T> {
        self.0
    }
    #[inline(always)]
    fn held_rate(&self) -> Option<Vec3<T>> {
        Some(self.0)
    }
    #[inline(always)]
    fn half_angle(&self, hh: T) -> Vec3<T> {
        self.0 * hh
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.0 * h).norm_squared()
    }
}

/// ω linear from `w0` at the start to `w1` at the end of the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearRate<T> {
    pub(crate) w0: Vec3<T>,
    pub(crate) w1: Vec3<T>,
}

impl<T: Real> Segment<T> for LinearRate<T> {
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
    /// Trapezoid: `½∫ω = (hh/2)(ω₀ + ω₁)`.
    #[inline(always)]
    fn half_angle(&self, hh: T) -> Vec3<T> {
        (self.w0 + self.w1) * (hh * T::HALF)
    }
    /// `ω(½) × (ω₁ − ω₀) = ω₀ × ω₁` exactly for a linear rate.
    #[inline(always)]
    fn rate_commutator(&self) -> Option<Vec3<T>> {
        Some(self.w0.cross(self.w1))
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.w0 * h)
            .norm_squared()
            .max((self.w1 * h).norm_squared())
    }
}

/// ω quadratic through samples at the start, the middle and the end of the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadraticRate<T> {
    pub(crate) w0: Vec3<T>,
    pub(crate) wm: Vec3<T>,
    pub(crate) w1: Vec3<T>,
}

impl<T: Real> Segment<T> for QuadraticRate<T> {
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
    /// Simpson: `½∫ω = (hh/6)(ω₀ + 4ω_m + ω₁)`.
    #[inline(always)]
    fn half_angle(&self, hh: T) -> Vec3<T> {
        (self.w0 + self.wm * T::from_f64(4.0) + self.w1) * (hh * T::from_f64(1.0 / 6.0))
    }
    /// `ω₀ × ω₁`: differs from `ω(½) × ω'(½)` by O(h³).
    #[inline(always)]
    fn rate_commutator(&self) -> Option<Vec3<T>> {
        Some(self.w0.cross(self.w1))
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.w0 * h)
            .norm_squared()
            .max((self.wm * h).norm_squared())
            .max((self.w1 * h).norm_squared())
    }
}

/// ω from the sample history: the polynomial through the last 2, 3 or 4 equally spaced samples
/// ω_{k−2}, ω_{k−1}, ω_k, ω_{k+1} on the last interval `[t_k, t_{k+1}]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HistoryRate<T> {
    /// Samples at c = −2, −1, 0, 1 (oldest first); with fewer, the leading entries are zero.
    pub(crate) w: [Vec3<T>; 4],
    /// 2, 3 or 4 samples.
    pub(crate) count: u8,
}

impl<T: Real> HistoryRate<T> {
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

impl<T: Real> Segment<T> for HistoryRate<T> {
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
    /// `∫₀¹` of the Lagrange basis: cubic (1, −5, 19, 9)/24 (Adams–Moulton); quadratic (−1, 8, 5)/12;
    /// linear (1, 1)/2.
    #[inline(always)]
    fn half_angle(&self, hh: T) -> Vec3<T> {
        let integral = match self.count {
            4 => [1.0 / 24.0, -5.0 / 24.0, 19.0 / 24.0, 9.0 / 24.0],
            3 => [0.0, -1.0 / 12.0, 8.0 / 12.0, 5.0 / 12.0],
            _ => [0.0, 0.0, 0.5, 0.5],
        };
        self.combine(integral) * hh
    }
    /// `ω(½) × (ω_{k+1} − ω_k)`, ω(½) from the interpolant; the difference is `ω'(½)` to O(h³).
    #[inline(always)]
    fn rate_commutator(&self) -> Option<Vec3<T>> {
        let mid = self.combine(self.weights(0.5));
        Some(mid.cross(self.w[3] - self.w[2]))
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
}

/// Rates at the two Gauss–Legendre nodes of the step; linear between (and beyond) them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GaussRates<T> {
    pub(crate) w1: Vec3<T>,
    pub(crate) w2: Vec3<T>,
}

impl<T: Real> Segment<T> for GaussRates<T> {
    #[inline(always)]
    fn rate_at(&self, c: f64) -> Vec3<T> {
        if c == gauss::NODE_1 {
            self.w1
        } else if c == gauss::NODE_2 {
            self.w2
        } else {
            let f = (c - gauss::NODE_1) * gauss::INV_GAP;
            self.w1 + (self.w2 - self.w1) * T::from_f64(f)
        }
    }
    /// The Gauss rule: `½∫ω = (hh/2)(ω₁ + ω₂)`.
    #[inline(always)]
    fn half_angle(&self, hh: T) -> Vec3<T> {
        (self.w1 + self.w2) * (hh * T::HALF)
    }
    /// `ω(½) × ω'(½) = ½(ω₁ + ω₂) × √3(ω₂ − ω₁) = √3 ω₁ × ω₂` exactly for the linear interpolant.
    #[inline(always)]
    fn rate_commutator(&self) -> Option<Vec3<T>> {
        Some(self.w1.cross(self.w2) * T::from_f64(gauss::INV_GAP))
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.w1 * h)
            .norm_squared()
            .max((self.w2 * h).norm_squared())
    }
}

/// The step's rotation vector φ (rad) given directly (delta angles after a coning correction). Runge–Kutta
/// schemes see the constant rate `φ/h`; the exponential map applies φ exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotationVector<T> {
    pub(crate) phi: Vec3<T>,
    pub(crate) h: T,
}

impl<T: Real> Segment<T> for RotationVector<T> {
    #[inline(always)]
    fn rate_at(&self, _c: f64) -> Vec3<T> {
        self.phi * (T::ONE / self.h)
    }
    #[inline(always)]
    fn held_rate(&self) -> Option<Vec3<T>> {
        Some(self.phi * (T::ONE / self.h))
    }
    #[inline(always)]
    fn half_angle(&self, _hh: T) -> Vec3<T> {
        self.phi * T::HALF
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, _h: T) -> T {
        self.phi.norm_squared()
    }
}
