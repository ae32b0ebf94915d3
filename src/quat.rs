//! Quaternions: scalar first, Hamilton product, body-to-reference attitude.
//!
//! Conventions (used everywhere in the crate):
//! - `Quat { w, x, y, z }` is `w + x i + y j + z k`, with `i² = j² = k² = ijk = −1` (Hamilton).
//! - An attitude `q` maps body-frame vectors to the reference frame: `v_ref = q ⊗ (0, v_body) ⊗ q*`.
//! - Body rates compose on the right: `q' = ½ q ⊗ (0, ω)`, the seed paper's eq. (1); a body-frame rotation
//!   vector `φ` advances the attitude as `q ← q ⊗ exp_q(φ)`.

use crate::real::sealed::Float;
use crate::{Real, Vec3};
use core::ops::{Add, Mul, Neg, Sub};

/// A quaternion `w + x i + y j + z k` (scalar first, Hamilton convention).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Quat<T> {
    /// Scalar part.
    pub w: T,
    /// `i` component.
    pub x: T,
    /// `j` component.
    pub y: T,
    /// `k` component.
    pub z: T,
}

impl<T: Real> Quat<T> {
    /// The identity rotation `(1, 0, 0, 0)`.
    pub const IDENTITY: Self = Self {
        w: T::ONE,
        x: T::ZERO,
        y: T::ZERO,
        z: T::ZERO,
    };

    /// The zero quaternion (not a rotation).
    pub const ZERO: Self = Self {
        w: T::ZERO,
        x: T::ZERO,
        y: T::ZERO,
        z: T::ZERO,
    };

    /// Builds `w + x i + y j + z k`.
    #[inline(always)]
    #[must_use]
    pub const fn new(w: T, x: T, y: T, z: T) -> Self {
        Self { w, x, y, z }
    }

    /// Builds `(w, v)` from a scalar and a vector part.
    #[inline(always)]
    #[must_use]
    pub const fn from_parts(w: T, v: Vec3<T>) -> Self {
        Self {
            w,
            x: v.x,
            y: v.y,
            z: v.z,
        }
    }

    /// The vector part `(x, y, z)`.
    #[inline(always)]
    #[must_use]
    pub fn vector(self) -> Vec3<T> {
        Vec3::new(self.x, self.y, self.z)
    }

    /// Conjugate `(w, −x, −y, −z)`: the inverse rotation for a unit quaternion.
    #[inline(always)]
    #[must_use]
    pub fn conjugate(self) -> Self {
        Self::new(self.w, -self.x, -self.y, -self.z)
    }

    /// Four-dimensional dot product.
    #[inline(always)]
    #[must_use]
    pub fn dot(self, o: Self) -> T {
        self.w * o.w + self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// `|q|²` in working precision.
    #[inline(always)]
    #[must_use]
    pub fn norm_squared(self) -> T {
        self.dot(self)
    }

    /// `|q|`, computed without overflow or underflow for any finite quaternion.
    #[must_use]
    pub fn norm(self) -> T {
        self.w.hypot(self.x).hypot(self.y.hypot(self.z))
    }

    /// The seed's normalization error `N = |q|² − 1` (eq. (2)), evaluated with an error far below ε
    /// (f32: summed in f64, where the squares are exact; f64: exact squares by `fma`, compensated sum).
    #[must_use]
    pub fn norm_error(self) -> T {
        T::sum_sq_minus_one(self.w, self.x, self.y, self.z)
    }

    /// `true` if every component is finite (with an FPU one multiply-add chain, `Σ cᵢ·0` is ±0 iff all are
    /// finite; in software float, bit tests).
    #[inline(always)]
    #[must_use]
    pub fn is_finite(self) -> bool {
        if T::HARDWARE_FLOAT {
            self.w * T::ZERO + self.x * T::ZERO + self.y * T::ZERO + self.z * T::ZERO == T::ZERO
        } else {
            self.w.is_finite() && self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
        }
    }

    /// The unit quaternion `q / |q|`, or `None` for a zero or non-finite quaternion.
    ///
    /// Robust for any finite non-zero input (scales by the largest component first), so tiny and huge
    /// quaternions normalize correctly. The step path uses the cheaper [`crate::stabilize`] policies instead.
    #[must_use]
    pub fn normalized(self) -> Option<Self> {
        if !self.is_finite() {
            return None;
        }
        let m = self
            .w
            .abs()
            .max(self.x.abs())
            .max(self.y.abs())
            .max(self.z.abs());
        if m == T::ZERO {
            return None;
        }
        // Divide (not multiply by 1/m): 1/m overflows for a subnormal m.
        let s = Self::new(self.w / m, self.x / m, self.y / m, self.z / m);
        let n = s.norm_squared().sqrt();
        Some(s * (T::ONE / n))
    }

    /// Inverse `q* / |q|²`, or `None` for a zero or non-finite quaternion.
    #[must_use]
    pub fn inverse(self) -> Option<Self> {
        let n2 = self.norm_squared();
        if n2 > T::ZERO && n2.is_finite() {
            Some(self.conjugate() * (T::ONE / n2))
        } else {
            None
        }
    }

    /// `q ⊗ (0, v)`: the product with a pure quaternion, 12 multiplications.
    ///
    /// With `v = ½ω` this is the right-hand side of the kinematic equation `q' = ½ q ⊗ (0, ω)`.
    #[inline(always)]
    #[must_use]
    pub fn mul_pure(self, v: Vec3<T>) -> Self {
        Self {
            w: -(self.x * v.x + self.y * v.y + self.z * v.z),
            x: self.w * v.x + self.y * v.z - self.z * v.y,
            y: self.w * v.y - self.x * v.z + self.z * v.x,
            z: self.w * v.z + self.x * v.y - self.y * v.x,
        }
    }

    /// Rotates a body-frame vector into the reference frame: `q ⊗ (0, v) ⊗ q*` (for unit `q`).
    ///
    /// ```
    /// use quatprop::{Quat, Vec3};
    /// let yaw90 = Quat::from_rotation_vector(Vec3::new(0.0, 0.0, core::f64::consts::FRAC_PI_2));
    /// let v = yaw90.rotate(Vec3::new(1.0, 0.0, 0.0)); // body x is reference y
    /// assert!((v - Vec3::new(0.0, 1.0, 0.0)).norm() < 1e-15);
    /// ```
    #[inline]
    #[must_use]
    pub fn rotate(self, v: Vec3<T>) -> Vec3<T> {
        let u = self.vector();
        let t = u.cross(v) * T::TWO;
        v + t * self.w + u.cross(t)
    }

    /// The exponential map `exp_q(φ) = (cos(|φ|/2), sin(|φ|/2) φ/|φ|)` of a rotation vector `φ` (rad):
    /// the unit quaternion of a rotation by `|φ|` about `φ`.
    ///
    /// Exact for any angle, including beyond π. Small angles use a Taylor branch (no square root, no
    /// trigonometry) that keeps every bit of the rotation: a rotation of 1e-9 rad is 1e-9 rad, not zero.
    ///
    /// ```
    /// use quatprop::{Quat, Vec3};
    /// let q = Quat::from_rotation_vector(Vec3::new(0.0, 1e-9_f32, 0.0));
    /// assert_eq!(q.y, 5e-10); // kept, where a `|φ| < ε → identity` shortcut would drop it
    /// let big = Quat::from_rotation_vector(Vec3::new(4.0_f64, 0.0, 0.0)); // beyond π
    /// assert!((big.w - 2.0_f64.cos()).abs() < 1e-16);
    /// ```
    #[inline]
    #[must_use]
    pub fn from_rotation_vector(phi: Vec3<T>) -> Self {
        let v = phi * T::HALF;
        let q = Self::exp_half(v);
        if q.w.is_finite() {
            q
        } else {
            // Beyond the step path's sine (f32: a half angle over 8192 rad), or a non-finite input.
            Self::exp_half_any_angle(v)
        }
    }

    /// `exp_q(φ) − 1` for a rotation vector `φ` (rad): the increment form of a rotation (`q ⊗ exp_q(φ) = q
    /// + q ⊗ (exp_q(φ) − 1)`), free of the cancellation in `cos − 1` for small angles, with the step path's
    /// sine (no libm sine linked in f32): NaN components beyond [`Self::INCREMENT_ANGLE_LIMIT`] in f32,
    /// or for a non-finite `φ`; f64 takes any finite angle.
    #[inline]
    #[must_use]
    pub(crate) fn rotation_increment(phi: Vec3<T>) -> Self {
        let v = phi * T::HALF;
        let m = Self::exp_half_minus_one(v);
        // f64's step sine is libm's (any angle): only an overflowed |v|² fails it, and libm's hypot then
        // takes the angle. f32 keeps its NaN (no libm sine linked; the caller refuses the rotation).
        if m.w.is_finite() || T::EPSILON > T::from_f64(1e-10) {
            m
        } else {
            let e = Self::exp_half_any_angle(v);
            Self::from_parts(e.w - T::ONE, e.vector())
        }
    }

    /// The largest rotation (rad) [`Self::rotation_increment`] takes in f32: the step path's sine covers
    /// half angles up to 8192 rad.
    pub(crate) const INCREMENT_ANGLE_LIMIT: f64 = 16384.0;

    /// [`Self::exp_half`] for any angle, with libm's general sine (its argument reduction covers every
    /// `T`). Out of line: a firmware that only steps never links it.
    #[cold]
    #[inline(never)]
    fn exp_half_any_angle(v: Vec3<T>) -> Self {
        let x = v.norm();
        let half = (x * T::HALF).sin();
        Self::from_parts(T::ONE - T::TWO * half * half, v * (x.sin() / x))
    }

    /// `exp((0, v)) = (cos|v|, sin|v| v/|v|)` for a half-angle vector `v` (rad).
    ///
    /// The Taylor branch (every step below 0.2 rad in f32, 0.01 rad in f64) is inlined; the trigonometric
    /// branch is a cold out-of-line call.
    #[inline(always)]
    #[must_use]
    pub(crate) fn exp_half(v: Vec3<T>) -> Self {
        let m = Self::exp_half_minus_one(v);
        Self::from_parts(T::ONE + m.w, m.vector())
    }

    /// `exp((0, v)) − 1 = (cos|v| − 1, sin|v| v/|v|)`, with `cos|v| − 1` free of cancellation: the increment
    /// form of a rotation, `q ⊗ exp = q + q ⊗ (exp − 1)`.
    #[inline(always)]
    #[must_use]
    pub(crate) fn exp_half_minus_one(v: Vec3<T>) -> Self {
        let x2 = v.norm_squared();
        if x2 < T::EXP_TAYLOR_MAX_SQ {
            let (cm1, sm1) = Self::exp_taylor(x2);
            // v·(1 + (sin x/x − 1)): the factor rounds next to 1, but so would v + v·(sin x/x − 1) (the
            // correction is below half an ulp of v for small steps); only a carried low part keeps it
            // (`exp_half_minus_one_split`, the float-float accumulator).
            Self::from_parts(cm1, v * (T::ONE + sm1))
        } else {
            Self::exp_half_minus_one_trig(v, x2)
        }
    }

    /// `(cos x − 1, sin x/x − 1)` for `x² < EXP_TAYLOR_MAX_SQ`: `−x²/2 + x⁴/24` and `−x²/6 + x⁴/120`
    /// (the next terms are below ¼ ulp, see `Real`).
    #[inline(always)]
    fn exp_taylor(x2: T) -> (T, T) {
        let cm1 = -(x2 * (T::HALF - x2 * T::from_f64(1.0 / 24.0)));
        let sm1 = -(x2 * (T::from_f64(1.0 / 6.0) - x2 * T::from_f64(1.0 / 120.0)));
        (cm1, sm1)
    }

    /// `exp((0, v + low)) − 1` as an unevaluated sum `hi + lo` for a rotation vector given as `v + low`
    /// (`low` far below `v`): `hi = (cos|v| − 1, v)`, `lo = (0, low + v·(sin|v|/|v| − 1))`, so the vector
    /// part keeps `v` and `low` unrounded. Dropped: `O(|low|·|v|)` in the scalar part, which only scales the
    /// attitude (the stabilizer's business), and `O(|low|·|v|²)` in the vector part. Beyond the Taylor range
    /// the sum is rounded into `hi`.
    #[inline(always)]
    #[must_use]
    pub(crate) fn exp_half_minus_one_split(v: Vec3<T>, low: Vec3<T>) -> (Self, Self) {
        let x2 = v.norm_squared();
        if x2 < T::EXP_TAYLOR_MAX_SQ {
            let (cm1, sm1) = Self::exp_taylor(x2);
            (
                Self::from_parts(cm1, v),
                Self::from_parts(T::ZERO, low + v * sm1),
            )
        } else {
            (
                Self::exp_half_minus_one_trig(v + low, (v + low).norm_squared()),
                Self::ZERO,
            )
        }
    }

    #[cold]
    #[inline(never)]
    fn exp_half_minus_one_trig(v: Vec3<T>, x2: T) -> Self {
        // The step path's sine: f32 covers x ≤ 8192 rad and gives NaN beyond (the step is then refused as
        // a non-finite result), so no general argument reduction is linked (src/trig.rs). An overflowed
        // |v|² (f32: |v| > 1.8e19, f64: 1.3e154) gives x = ∞ and a NaN result the same way;
        // `from_rotation_vector` takes those angles through libm.
        let x = Float::sqrt_step(x2);
        let half = Float::sin_step(x * T::HALF);
        // cos x − 1 = −2 sin²(x/2).
        Self::from_parts(-(T::TWO * half * half), v * (Float::sin_step(x) / x))
    }

    /// The rotation vector `φ` (rad) with `exp_q(φ) = ±q`, choosing `|φ| ≤ π` (the logarithm map).
    ///
    /// Expects a unit quaternion; the result scales with `atan2`, so a slightly non-unit input still
    /// gives the angle of its direction.
    ///
    /// ```
    /// use quatprop::{Quat, Vec3};
    /// let phi = Vec3::new(0.1, -0.2, 0.3_f64);
    /// let back = Quat::from_rotation_vector(phi).to_rotation_vector();
    /// assert!((back - phi).norm() < 1e-16);
    /// ```
    #[must_use]
    pub fn to_rotation_vector(self) -> Vec3<T> {
        let q = if self.w < T::ZERO { -self } else { self };
        let u = q.vector();
        let s = u.norm();
        if s == T::ZERO {
            return Vec3::ZERO;
        }
        u * (T::TWO * s.atan2(q.w) / s)
    }

    /// Converts each component to `f64`.
    ///
    /// ```
    /// use quatprop::Quat;
    /// assert_eq!(Quat::new(0.5_f32, 0.1, 0.0, 0.0).to_f64().x, 0.1_f32 as f64); // exact widening
    /// ```
    #[must_use]
    pub fn to_f64(self) -> Quat<f64> {
        Quat::new(
            self.w.to_f64(),
            self.x.to_f64(),
            self.y.to_f64(),
            self.z.to_f64(),
        )
    }

    /// Converts each component from `f64` (rounding to nearest for `f32`).
    ///
    /// ```
    /// use quatprop::Quat;
    /// assert_eq!(Quat::<f32>::from_f64(Quat::new(1.0, 0.1, 0.0, 0.0)).x, 0.1_f32);
    /// ```
    #[must_use]
    pub fn from_f64(q: Quat<f64>) -> Self {
        Self::new(
            T::from_f64(q.w),
            T::from_f64(q.x),
            T::from_f64(q.y),
            T::from_f64(q.z),
        )
    }

    /// The rotation angle (rad, in [0, π]) between two attitudes, treating `q` and `−q` as the same.
    ///
    /// Computed as `2 atan2(|vec(a* ⊗ b)|, |scalar(a* ⊗ b)|)`, accurate for tiny and near-π angles.
    ///
    /// ```
    /// use quatprop::{Quat, Vec3};
    /// let a = Quat::from_rotation_vector(Vec3::new(0.0, 0.0, 0.2_f64));
    /// let b = Quat::from_rotation_vector(Vec3::new(0.0, 0.0, 0.5_f64));
    /// assert!((a.angle_to(b) - 0.3).abs() < 1e-15);
    /// assert_eq!(a.angle_to(-a), 0.0); // q and −q are the same rotation
    /// ```
    #[must_use]
    pub fn angle_to(self, other: Self) -> T {
        let d = self.conjugate() * other;
        T::TWO * d.vector().norm().atan2(d.w.abs())
    }
}

impl<T: Real> Mul for Quat<T> {
    type Output = Self;
    /// Hamilton product `self ⊗ o`.
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Self {
            w: self.w * o.w - self.x * o.x - self.y * o.y - self.z * o.z,
            x: self.w * o.x + self.x * o.w + self.y * o.z - self.z * o.y,
            y: self.w * o.y - self.x * o.z + self.y * o.w + self.z * o.x,
            z: self.w * o.z + self.x * o.y - self.y * o.x + self.z * o.w,
        }
    }
}

impl<T: Real> Mul<T> for Quat<T> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, s: T) -> Self {
        Self::new(self.w * s, self.x * s, self.y * s, self.z * s)
    }
}

impl<T: Real> Add for Quat<T> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self::new(self.w + o.w, self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<T: Real> Sub for Quat<T> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self::new(self.w - o.w, self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<T: Real> Neg for Quat<T> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::new(-self.w, -self.x, -self.y, -self.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mul_pure_matches_seed_equation_1() {
        // The seed's eq. (1): q̇ = ½ Ω q with Ω's rows as printed there.
        let q = Quat::new(0.3_f64, -0.5, 0.7, 0.4);
        let w = [0.9_f64, -1.3, 2.1];
        let omega = [
            [0.0, -w[0], -w[1], -w[2]],
            [w[0], 0.0, w[2], -w[1]],
            [w[1], -w[2], 0.0, w[0]],
            [w[2], w[1], -w[0], 0.0],
        ];
        let qv = [q.w, q.x, q.y, q.z];
        let mut expect = [0.0; 4];
        for i in 0..4 {
            for j in 0..4 {
                expect[i] += 0.5 * omega[i][j] * qv[j];
            }
        }
        let got = q.mul_pure(Vec3::new(w[0], w[1], w[2]) * 0.5);
        let full = q * Quat::new(0.0, 0.5 * w[0], 0.5 * w[1], 0.5 * w[2]);
        for (a, b) in [got.w, got.x, got.y, got.z].iter().zip(expect) {
            assert!((a - b).abs() < 1e-15, "{a} vs {b}");
        }
        assert!((full - got).norm() < 1e-15);
    }

    #[test]
    fn hamilton_units() {
        let i = Quat::new(0.0_f64, 1.0, 0.0, 0.0);
        let j = Quat::new(0.0, 0.0, 1.0, 0.0);
        let k = Quat::new(0.0, 0.0, 0.0, 1.0);
        assert_eq!(i * j, k);
        assert_eq!(j * k, i);
        assert_eq!(k * i, j);
        assert_eq!(i * j * k, -Quat::IDENTITY);
    }

    #[test]
    fn exp_map_keeps_tiny_rotations() {
        // 1e-9 rad about x: the vector part must be 0.5e-9 to full precision.
        let q = Quat::from_rotation_vector(Vec3::new(1e-9_f64, 0.0, 0.0));
        assert_eq!(q.w, 1.0);
        assert!((q.x - 0.5e-9).abs() <= 0.5e-9 * f64::EPSILON);
        let q32 = Quat::from_rotation_vector(Vec3::new(1e-9_f32, 0.0, 0.0));
        assert_eq!(q32.x, 0.5e-9_f32);
    }

    #[test]
    fn exp_map_is_continuous_across_the_taylor_threshold() {
        fn check<T: Real>(tol: f64) {
            let x = T::EXP_TAYLOR_MAX_SQ.sqrt().to_f64();
            for f in [0.999_999, 1.000_001] {
                let v = x * f;
                let q = Quat::<T>::exp_half(Vec3::new(T::from_f64(v), T::ZERO, T::ZERO));
                let (c, s) = (libm::cos(v), libm::sin(v));
                assert!((q.w.to_f64() - c).abs() <= tol, "cos at {v}");
                assert!((q.x.to_f64() - s).abs() <= tol, "sin at {v}");
            }
        }
        check::<f32>(2.0 * f32::EPSILON as f64);
        check::<f64>(2.0 * f64::EPSILON);
    }

    #[test]
    fn rotate_matches_sandwich_product() {
        let q = Quat::new(0.2_f64, 0.4, -0.5, 0.74).normalized().unwrap();
        let v = Vec3::new(1.0, -2.0, 0.5);
        let s = q * Quat::from_parts(0.0, v) * q.conjugate();
        let r = q.rotate(v);
        assert!((s.vector() - r).norm() < 1e-15);
        assert!(s.w.abs() < 1e-15);
    }

    #[test]
    fn normalized_handles_extreme_magnitudes_and_rejects_bad_input() {
        let tiny = Quat::new(1e-40_f32, 0.0, 0.0, 1e-40);
        let n = tiny.normalized().unwrap();
        assert!((n.norm_error()).abs() <= 2.0 * f32::EPSILON);
        let huge = Quat::new(3e38_f32, 3e38, 0.0, 0.0);
        assert!((huge.normalized().unwrap().w - core::f32::consts::FRAC_1_SQRT_2).abs() < 1e-7);
        assert!(Quat::<f64>::ZERO.normalized().is_none());
        assert!(Quat::new(f64::NAN, 0.0, 0.0, 0.0).normalized().is_none());
        assert!(Quat::new(f64::INFINITY, 0.0, 0.0, 0.0)
            .normalized()
            .is_none());
    }

    #[test]
    fn log_inverts_exp_up_to_pi() {
        for angle in [1e-12_f64, 1e-3, 0.5, 2.0, 3.0, core::f64::consts::PI - 1e-5] {
            let axis = Vec3::new(0.48_f64, -0.6, 0.64);
            let phi = axis * angle;
            let back = Quat::from_rotation_vector(phi).to_rotation_vector();
            assert!(
                (back - phi).norm() <= 4.0 * f64::EPSILON * angle.max(1.0),
                "{angle}"
            );
        }
        // Beyond π the logarithm returns the equivalent shorter rotation.
        let phi = Vec3::new(0.0_f64, 0.0, 4.0);
        let back = Quat::from_rotation_vector(phi).to_rotation_vector();
        assert!((back.z - (4.0 - 2.0 * core::f64::consts::PI)).abs() < 1e-14);
    }

    #[test]
    fn angle_to_treats_sign_as_same_rotation() {
        let a = Quat::from_rotation_vector(Vec3::new(0.1_f64, 0.2, 0.3));
        let b = a * Quat::from_rotation_vector(Vec3::new(1e-10, 0.0, 0.0));
        // b's components are rounded (absolute error ~ε), which bounds the resolvable angle.
        let tol = 4.0 * f64::EPSILON;
        assert!((a.angle_to(b) - 1e-10).abs() < tol);
        assert!((a.angle_to(-b) - 1e-10).abs() < tol);
        assert!(a.angle_to(-a) < tol);
    }
}
