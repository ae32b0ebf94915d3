//! Conversions to and from other representations: arrays (always), and with the `mint` feature the
//! [`mint`] types that nalgebra (`convert-mint`) and glam (`mint-05`) convert to and from.
//!
//! Component order: arrays of a [`Quat`] are scalar first, `[w, x, y, z]` (this crate's convention).
//! `mint::Quaternion { v, s }` names the parts instead: `s = w`, `v = (x, y, z)`; glam's and nalgebra's own
//! quaternions store the scalar last, which their `mint` conversions handle.

use crate::{Quat, Vec3};

/// `[w, x, y, z]` (scalar first).
///
/// ```
/// use quatprop::Quat;
/// let q = Quat::from([1.0_f32, 0.0, 0.0, 0.0]);
/// assert_eq!(q, Quat::IDENTITY);
/// ```
impl<T> From<[T; 4]> for Quat<T> {
    #[inline]
    fn from([w, x, y, z]: [T; 4]) -> Self {
        Quat { w, x, y, z }
    }
}

/// `[w, x, y, z]` (scalar first).
///
/// ```
/// use quatprop::Quat;
/// let a: [f64; 4] = Quat::new(0.5, -0.5, 0.5, -0.5).into();
/// assert_eq!(a, [0.5, -0.5, 0.5, -0.5]);
/// ```
impl<T> From<Quat<T>> for [T; 4] {
    #[inline]
    fn from(q: Quat<T>) -> Self {
        [q.w, q.x, q.y, q.z]
    }
}

/// `[x, y, z]`.
///
/// ```
/// use quatprop::Vec3;
/// assert_eq!(Vec3::from([1.0_f32, 2.0, 3.0]), Vec3::new(1.0, 2.0, 3.0));
/// ```
impl<T> From<[T; 3]> for Vec3<T> {
    #[inline]
    fn from([x, y, z]: [T; 3]) -> Self {
        Vec3 { x, y, z }
    }
}

/// `[x, y, z]`.
///
/// ```
/// use quatprop::Vec3;
/// let a: [f32; 3] = Vec3::new(1.0, 2.0, 3.0).into();
/// assert_eq!(a, [1.0, 2.0, 3.0]);
/// ```
impl<T> From<Vec3<T>> for [T; 3] {
    #[inline]
    fn from(v: Vec3<T>) -> Self {
        [v.x, v.y, v.z]
    }
}

#[cfg(feature = "mint")]
mod with_mint {
    use crate::{Quat, Vec3};

    impl<T> Quat<T> {
        /// From anything that converts into `mint::Quaternion` (nalgebra's `Quaternion` implements `Into`
        /// only, glam's `Quat` both).
        ///
        /// ```
        /// use quatprop::Quat;
        /// let n = nalgebra::UnitQuaternion::from_euler_angles(0.3, 0.0, 0.0_f32);
        /// assert_eq!(Quat::from_mint(*n.quaternion()).x, n.i);
        /// ```
        #[cfg_attr(docsrs, doc(cfg(feature = "mint")))]
        #[inline]
        pub fn from_mint(q: impl Into<mint::Quaternion<T>>) -> Self {
            Self::from(q.into())
        }
    }

    impl<T> Vec3<T> {
        /// From anything that converts into `mint::Vector3` (nalgebra's `Vector3` implements `Into` only).
        ///
        /// ```
        /// use quatprop::Vec3;
        /// let v = Vec3::from_mint(nalgebra::Vector3::new(1.0_f64, 2.0, 3.0));
        /// assert_eq!(v, Vec3::new(1.0, 2.0, 3.0));
        /// ```
        #[cfg_attr(docsrs, doc(cfg(feature = "mint")))]
        #[inline]
        pub fn from_mint(v: impl Into<mint::Vector3<T>>) -> Self {
            Self::from(v.into())
        }
    }

    /// `s = w`, `v = (x, y, z)`. A glam or nalgebra quaternion converts in one line:
    ///
    /// ```
    /// use quatprop::{Quat, Vec3};
    /// let q = Quat::from_rotation_vector(Vec3::new(0.0, 0.0, 0.3_f32));
    /// let g = glam::Quat::from(mint::Quaternion::from(q));
    /// assert_eq!((g.w, g.z), (q.w, q.z));
    /// let n = nalgebra::Quaternion::from(mint::Quaternion::from(q));
    /// assert_eq!((n.w, n.k), (q.w, q.z));
    /// ```
    #[cfg_attr(docsrs, doc(cfg(feature = "mint")))]
    impl<T> From<Quat<T>> for mint::Quaternion<T> {
        #[inline]
        fn from(q: Quat<T>) -> Self {
            mint::Quaternion {
                v: mint::Vector3 {
                    x: q.x,
                    y: q.y,
                    z: q.z,
                },
                s: q.w,
            }
        }
    }

    /// `w = s`, `(x, y, z) = v`. From glam or nalgebra in one line:
    ///
    /// ```
    /// use quatprop::Quat;
    /// let g = glam::Quat::from_rotation_z(0.3);
    /// let q = Quat::from(mint::Quaternion::from(g));
    /// assert_eq!((q.w, q.z), (g.w, g.z));
    /// // nalgebra implements `Into<mint::Quaternion>`, not `From`: see `Quat::from_mint`.
    /// let n = nalgebra::UnitQuaternion::from_euler_angles(0.0, 0.0, 0.3_f64);
    /// let q = Quat::from_mint(*n.quaternion());
    /// assert_eq!((q.w, q.z), (n.w, n.k));
    /// ```
    #[cfg_attr(docsrs, doc(cfg(feature = "mint")))]
    impl<T> From<mint::Quaternion<T>> for Quat<T> {
        #[inline]
        fn from(q: mint::Quaternion<T>) -> Self {
            Quat {
                w: q.s,
                x: q.v.x,
                y: q.v.y,
                z: q.v.z,
            }
        }
    }

    /// ```
    /// use quatprop::Vec3;
    /// let g = glam::Vec3::from(mint::Vector3::from(Vec3::new(1.0_f32, 2.0, 3.0)));
    /// assert_eq!(g, glam::Vec3::new(1.0, 2.0, 3.0));
    /// ```
    #[cfg_attr(docsrs, doc(cfg(feature = "mint")))]
    impl<T> From<Vec3<T>> for mint::Vector3<T> {
        #[inline]
        fn from(v: Vec3<T>) -> Self {
            mint::Vector3 {
                x: v.x,
                y: v.y,
                z: v.z,
            }
        }
    }

    /// ```
    /// use quatprop::Vec3;
    /// let v = Vec3::from(mint::Vector3::from(glam::DVec3::new(1.0, 2.0, 3.0)));
    /// assert_eq!(v, Vec3::new(1.0, 2.0, 3.0));
    /// ```
    #[cfg_attr(docsrs, doc(cfg(feature = "mint")))]
    impl<T> From<mint::Vector3<T>> for Vec3<T> {
        #[inline]
        fn from(v: mint::Vector3<T>) -> Self {
            Vec3 {
                x: v.x,
                y: v.y,
                z: v.z,
            }
        }
    }
}
