//! Conversions between unit quaternions and axis-angle, rotation matrices and Euler angles.
//!
//! All angles are radians. A rotation matrix `R` maps body vectors to the reference frame, `v_ref = R v_body`,
//! exactly like [`Quat::rotate`]. Both Euler conventions are computed from half-angle `atan2` formulas on
//! the quaternion components, so the middle angle stays accurate to a few ulp right up to the gimbal lock
//! (the seed's "frame barrier", where its eq. (5)-(6) `acos` form loses half the digits); at the lock itself
//! only the sum (or difference) of the outer angles is defined and the split puts it all in the first angle.

use crate::{Quat, Real, Vec3};

/// Aerospace Euler angles, intrinsic Z-Y'-X'' (yaw, then pitch, then roll): `R = Rz(yaw) Ry(pitch) Rx(roll)`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EulerZyx<T> {
    /// Heading about the reference z axis (rad, in (−π, π]).
    pub yaw: T,
    /// Elevation (rad, in [−π/2, π/2]).
    pub pitch: T,
    /// Bank about the body x axis (rad, in (−π, π]).
    pub roll: T,
}

/// Classical Euler angles, intrinsic Z-X'-Z'': `R = Rz(psi) Rx(theta) Rz(phi)`
/// (the seed's precession ψ, nutation ϑ, spin φ; its eq. (5) is `cos ϑ = w² − x² − y² + z²`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EulerZxz<T> {
    /// Precession ψ (rad, in (−π, π]).
    pub psi: T,
    /// Nutation ϑ (rad, in [0, π]).
    pub theta: T,
    /// Spin φ (rad, in (−π, π]).
    pub phi: T,
}

/// Wraps an angle from (−2π, 2π] into (−π, π].
#[inline]
fn wrap_pi<T: Real>(a: T) -> T {
    if a > T::PI {
        a - T::TWO * T::PI
    } else if a <= -T::PI {
        a + T::TWO * T::PI
    } else {
        a
    }
}

#[inline]
fn half_angle_quat<T: Real>(angle: T, axis: usize) -> Quat<T> {
    let h = angle * T::HALF;
    let (c, s) = (h.cos(), h.sin());
    match axis {
        0 => Quat::new(c, s, T::ZERO, T::ZERO),
        1 => Quat::new(c, T::ZERO, s, T::ZERO),
        _ => Quat::new(c, T::ZERO, T::ZERO, s),
    }
}

impl<T: Real> Quat<T> {
    /// Rotation by `angle` (rad) about `axis` (any non-zero length; it is normalized).
    /// `None` if the axis is zero or anything is non-finite.
    ///
    /// ```
    /// use quatprop::{Quat, Vec3};
    /// let q = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 2.0_f64), 1.0).unwrap();
    /// assert!((q.w - 0.5_f64.cos()).abs() < 1e-16 && (q.z - 0.5_f64.sin()).abs() < 1e-16);
    /// assert_eq!(Quat::from_axis_angle(Vec3::new(0.0, 0.0, 0.0_f64), 1.0), None);
    /// ```
    #[must_use]
    pub fn from_axis_angle(axis: Vec3<T>, angle: T) -> Option<Self> {
        if !angle.is_finite() {
            return None;
        }
        let u = axis.normalized()?;
        let h = angle * T::HALF;
        Some(Self::from_parts(h.cos(), u * h.sin()))
    }

    /// Unit axis and angle (rad, in [0, π]) of a unit quaternion. The identity gives axis `(1, 0, 0)`, angle 0.
    ///
    /// ```
    /// use quatprop::{Quat, Vec3};
    /// let q = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0_f64), -0.3).unwrap();
    /// let (axis, angle) = q.to_axis_angle();
    /// assert!((angle - 0.3).abs() < 1e-15 && (axis.x + 1.0).abs() < 1e-15); // angle ≥ 0, axis flips
    /// ```
    #[must_use]
    pub fn to_axis_angle(self) -> (Vec3<T>, T) {
        let phi = self.to_rotation_vector();
        let angle = phi.norm();
        // Scaled by the largest component first (division, not a reciprocal that overflows): a subnormal
        // angle still gives a unit axis.
        let m = phi.x.abs().max(phi.y.abs()).max(phi.z.abs());
        if !(m > T::ZERO) {
            return (Vec3::new(T::ONE, T::ZERO, T::ZERO), T::ZERO);
        }
        let u = Vec3::new(phi.x / m, phi.y / m, phi.z / m);
        (u * (T::ONE / u.norm()), angle)
    }

    /// Rotation matrix (row-major) with `v_ref = R v_body`. Expects a unit quaternion.
    ///
    /// ```
    /// use quatprop::{Quat, Vec3};
    /// let q = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0_f64), core::f64::consts::FRAC_PI_2).unwrap();
    /// let r = q.to_rotation_matrix(); // body x maps to reference y
    /// assert!(r[1][0] > 1.0 - 1e-15 && r[0][0].abs() < 1e-15);
    /// ```
    #[must_use]
    pub fn to_rotation_matrix(self) -> [[T; 3]; 3] {
        let (w, x, y, z) = (self.w, self.x, self.y, self.z);
        let two = T::TWO;
        [
            [
                T::ONE - two * (y * y + z * z),
                two * (x * y - w * z),
                two * (x * z + w * y),
            ],
            [
                two * (x * y + w * z),
                T::ONE - two * (x * x + z * z),
                two * (y * z - w * x),
            ],
            [
                two * (x * z - w * y),
                two * (y * z + w * x),
                T::ONE - two * (x * x + y * y),
            ],
        ]
    }

    /// Unit quaternion (with `w ≥ 0`) of a rotation matrix, by Shepperd's method (the largest of
    /// `1 + trace`, `1 + 2R₀₀ − trace`, … is used as the pivot, so no branch loses precision).
    /// `None` if an entry is not finite or `det R ≤ ½` (singular, a reflection, or far from any rotation);
    /// a nearly orthonormal matrix gives the quaternion of a nearby rotation.
    ///
    /// ```
    /// use quatprop::{Quat, Vec3};
    /// let q = Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0_f64), 2.5).unwrap();
    /// let back = Quat::from_rotation_matrix(q.to_rotation_matrix()).unwrap();
    /// assert!(q.angle_to(back) < 1e-15);
    /// let mirror = [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0_f64]];
    /// assert_eq!(Quat::from_rotation_matrix(mirror), None); // a reflection is no rotation
    /// ```
    #[must_use]
    pub fn from_rotation_matrix(r: [[T; 3]; 3]) -> Option<Self> {
        let det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
            - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
            + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
        if !(det > T::HALF) || !det.is_finite() {
            return None;
        }
        let t = r[0][0] + r[1][1] + r[2][2];
        let one = T::ONE;
        let cands = [
            one + t,
            one + T::TWO * r[0][0] - t,
            one + T::TWO * r[1][1] - t,
            one + T::TWO * r[2][2] - t,
        ];
        let mut k = 0;
        for i in 1..4 {
            if cands[i] > cands[k] {
                k = i;
            }
        }
        let p = cands[k];
        if !(p > T::ZERO) || !p.is_finite() {
            return None;
        }
        let s = p.sqrt(); // s = 2|q_k|
        let f = T::HALF / s;
        let q = match k {
            0 => Self::new(
                s * T::HALF,
                (r[2][1] - r[1][2]) * f,
                (r[0][2] - r[2][0]) * f,
                (r[1][0] - r[0][1]) * f,
            ),
            1 => Self::new(
                (r[2][1] - r[1][2]) * f,
                s * T::HALF,
                (r[0][1] + r[1][0]) * f,
                (r[0][2] + r[2][0]) * f,
            ),
            2 => Self::new(
                (r[0][2] - r[2][0]) * f,
                (r[0][1] + r[1][0]) * f,
                s * T::HALF,
                (r[1][2] + r[2][1]) * f,
            ),
            _ => Self::new(
                (r[1][0] - r[0][1]) * f,
                (r[0][2] + r[2][0]) * f,
                (r[1][2] + r[2][1]) * f,
                s * T::HALF,
            ),
        };
        let q = if q.w < T::ZERO { -q } else { q };
        q.normalized()
    }

    /// Quaternion of aerospace Euler angles (rad): `qz(yaw) ⊗ qy(pitch) ⊗ qx(roll)`.
    ///
    /// ```
    /// use quatprop::{EulerZyx, Quat};
    /// let q = Quat::from_euler_zyx(EulerZyx { yaw: 0.4_f64, pitch: 0.0, roll: 0.0 });
    /// assert!((q.z - 0.2_f64.sin()).abs() < 1e-16 && q.x == 0.0 && q.y == 0.0);
    /// ```
    #[must_use]
    pub fn from_euler_zyx(e: EulerZyx<T>) -> Self {
        half_angle_quat(e.yaw, 2) * half_angle_quat(e.pitch, 1) * half_angle_quat(e.roll, 0)
    }

    /// Aerospace Euler angles (rad) of a unit quaternion.
    ///
    /// With half angles a = yaw/2, b = pitch/2, c = roll/2 the components factor as
    /// `w ± y = (cos b ± sin b)·cos(a ∓ c)`, `x ∓ z = ±(cos b ± sin b)·sin(c ∓ a)`, so
    /// `pitch = π/2 − 2 atan2(|(w − y, x + z)|, |(w + y, x − z)|)`, `(yaw + roll)/2 = atan2(x + z, w − y)`,
    /// `(yaw − roll)/2 = atan2(z − x, w + y)`: no `asin`, no loss near ±90° pitch.
    ///
    /// ```
    /// use quatprop::{EulerZyx, Quat};
    /// let e = EulerZyx { yaw: 0.3_f64, pitch: -1.2, roll: 2.9 };
    /// let back = Quat::from_euler_zyx(e).to_euler_zyx();
    /// assert!((back.yaw - e.yaw).abs() < 1e-15 && (back.pitch - e.pitch).abs() < 1e-15);
    /// assert!((back.roll - e.roll).abs() < 1e-14);
    /// ```
    #[must_use]
    pub fn to_euler_zyx(self) -> EulerZyx<T> {
        let (w, x, y, z) = (self.w, self.x, self.y, self.z);
        let (p1, p2) = (w + y, x - z); // (cos b + sin b)(cos(a−c), −sin(a−c))
        let (m1, m2) = (w - y, x + z); // (cos b − sin b)(cos(a+c), sin(a+c))
        let plus = p1.hypot(p2);
        let minus = m1.hypot(m2);
        let pitch = T::PI * T::HALF - T::TWO * minus.atan2(plus);
        let sum = m2.atan2_conversion(m1); // (yaw + roll)/2
        let diff = (-p2).atan2_conversion(p1); // (yaw − roll)/2
        EulerZyx {
            yaw: wrap_pi(sum + diff),
            pitch,
            roll: wrap_pi(sum - diff),
        }
    }

    // The Z-X-Z pair below mirrors the Z-Y-X pair above in shape (the constructor from three half-angle
    // factors, the extractor from the components); each convention's formulas are its own.

    /// Quaternion of classical Z-X-Z Euler angles (rad): `qz(psi) ⊗ qx(theta) ⊗ qz(phi)`.
    ///
    /// ```
    /// use quatprop::{EulerZxz, Quat};
    /// let q = Quat::from_euler_zxz(EulerZxz { psi: 0.0_f64, theta: 0.5, phi: 0.0 });
    /// assert!((q.x - 0.25_f64.sin()).abs() < 1e-16 && q.z == 0.0);
    /// ```
    #[must_use]
    pub fn from_euler_zxz(e: EulerZxz<T>) -> Self {
        half_angle_quat(e.psi, 2) * half_angle_quat(e.theta, 0) * half_angle_quat(e.phi, 2)
    }

    /// Classical Z-X-Z Euler angles (rad) of a unit quaternion.
    ///
    /// The components factor as `w = cos(ϑ/2) cos((ψ+φ)/2)`, `z = cos(ϑ/2) sin((ψ+φ)/2)`,
    /// `x = sin(ϑ/2) cos((ψ−φ)/2)`, `y = sin(ϑ/2) sin((ψ−φ)/2)`, so
    /// `ϑ = 2 atan2(|(x, y)|, |(w, z)|)`: accurate at ϑ → 0 and π, unlike `acos(w² − x² − y² + z²)`.
    ///
    /// ```
    /// use quatprop::{EulerZxz, Quat};
    /// let e = EulerZxz { psi: -2.0_f64, theta: 1e-9, phi: 0.7 }; // nutation near the frame barrier
    /// let back = Quat::from_euler_zxz(e).to_euler_zxz();
    /// assert!((back.theta - 1e-9).abs() < 1e-22); // the acos form would lose it entirely
    /// assert!((back.psi + back.phi - (e.psi + e.phi)).abs() < 1e-15);
    /// ```
    #[must_use]
    pub fn to_euler_zxz(self) -> EulerZxz<T> {
        let (w, x, y, z) = (self.w, self.x, self.y, self.z);
        let theta = T::TWO * x.hypot(y).atan2(w.hypot(z));
        let sum = z.atan2_conversion(w);
        let diff = y.atan2_conversion(x);
        EulerZxz {
            psi: wrap_pi(sum + diff),
            theta,
            phi: wrap_pi(sum - diff),
        }
    }
}
