//! Three-vectors: body rates (rad/s), rotation vectors (rad), axes.

use crate::Real;
use core::ops::{Add, AddAssign, Mul, Neg, Sub};

/// A 3-vector `(x, y, z)`. Rates are body-frame rad/s; rotation vectors are rad.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Vec3<T> {
    /// First component.
    pub x: T,
    /// Second component.
    pub y: T,
    /// Third component.
    pub z: T,
}

impl<T: Real> Vec3<T> {
    /// The zero vector.
    pub const ZERO: Self = Self {
        x: T::ZERO,
        y: T::ZERO,
        z: T::ZERO,
    };

    /// Builds `(x, y, z)`.
    #[inline(always)]
    #[must_use]
    pub const fn new(x: T, y: T, z: T) -> Self {
        Self { x, y, z }
    }

    /// Dot product.
    #[inline(always)]
    #[must_use]
    pub fn dot(self, o: Self) -> T {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Cross product `self × o` (right-handed).
    #[inline(always)]
    #[must_use]
    pub fn cross(self, o: Self) -> Self {
        Self {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }

    /// Squared Euclidean norm.
    #[inline(always)]
    #[must_use]
    pub fn norm_squared(self) -> T {
        self.dot(self)
    }

    /// Euclidean norm, computed without overflow for any finite vector.
    #[inline]
    #[must_use]
    pub fn norm(self) -> T {
        self.x.hypot(self.y).hypot(self.z)
    }

    /// `true` if every component is finite.
    #[inline(always)]
    #[must_use]
    pub fn is_finite(self) -> bool {
        all_finite(&[self])
    }

    /// The vector scaled to unit length, or `None` if it is zero or not finite.
    #[must_use]
    pub fn normalized(self) -> Option<Self> {
        let n = self.norm();
        if n > T::ZERO && n.is_finite() {
            Some(self * (T::ONE / n))
        } else {
            None
        }
    }

    /// Converts each component to `f64`.
    ///
    /// ```
    /// use quatprop::Vec3;
    /// assert_eq!(Vec3::new(0.1_f32, 0.0, 0.0).to_f64().x, 0.1_f32 as f64);
    /// ```
    #[must_use]
    pub fn to_f64(self) -> Vec3<f64> {
        Vec3::new(self.x.to_f64(), self.y.to_f64(), self.z.to_f64())
    }

    /// Converts each component from `f64` (rounding to nearest for `f32`).
    ///
    /// ```
    /// use quatprop::Vec3;
    /// assert_eq!(Vec3::<f32>::from_f64(Vec3::new(0.1, 0.0, 0.0)).x, 0.1_f32);
    /// ```
    #[must_use]
    pub fn from_f64(v: Vec3<f64>) -> Self {
        Self::new(T::from_f64(v.x), T::from_f64(v.y), T::from_f64(v.z))
    }
}

/// `true` if every component of every vector is finite.
///
/// With hardware float: `Σ cᵢ·0` is ±0 iff all are finite (∞·0 and NaN·0 are NaN), one multiply-add chain and
/// one compare for any number of values, where `is_finite` per component costs five integer instructions on a
/// Cortex-M4. In software float (f64 on Cortex-M, f32 on M0/M3) the bit tests are cheaper and used instead.
#[inline(always)]
pub(crate) fn all_finite<T: Real, const N: usize>(vs: &[Vec3<T>; N]) -> bool {
    if T::HARDWARE_FLOAT {
        let mut probe = T::ZERO;
        for v in vs {
            probe = probe + v.x * T::ZERO + v.y * T::ZERO + v.z * T::ZERO;
        }
        probe == T::ZERO
    } else {
        vs.iter()
            .all(|v| v.x.is_finite() && v.y.is_finite() && v.z.is_finite())
    }
}

impl<T: Real> Add for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<T: Real> AddAssign for Vec3<T> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<T: Real> Sub for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<T: Real> Neg for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

impl<T: Real> Mul<T> for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, s: T) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }
}
