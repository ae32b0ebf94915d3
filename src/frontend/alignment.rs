//! Sensor-to-body alignment: the 24 orthogonal axis remaps by name, or a rotation matrix.

use crate::{Error, GyroSample, Real, Vec3};

/// The largest deviation of `RᵀR` from the identity (any entry) and of `det R` from 1 that
/// [`Alignment::from_matrix`] accepts as a rotation. A calibration matrix printed to 6 digits is orthogonal
/// to about 1e-6; one off by 1e-4 is a scale or shear error, not a rotation, and is refused.
pub const ROTATION_TOLERANCE: f64 = 1e-4;

/// One of the 24 proper rotations that map sensor axes onto body axes (a sensor mounted square to the
/// body). The name lists the signed sensor axis that becomes body x, then body y, then body z:
/// `PyNxPz` is body x = +sensor y, body y = −sensor x, body z = +sensor z (a sensor turned 90° about z).
/// Only right-handed maps exist (a mirror is no rotation); the third axis follows from the first two.
///
/// ```
/// use quatprop::frontend::AxisRemap;
/// use quatprop::{GyroSample, Vec3};
/// let s = AxisRemap::PyNxPz.apply(GyroSample::new(Vec3::new(1.0_f32, 2.0, 3.0)));
/// assert_eq!(s.rate, Vec3::new(2.0, -1.0, 3.0));
/// assert_eq!(AxisRemap::ALL.len(), 24);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum AxisRemap {
    /// body x = +sensor x, body y = +sensor y, body z = +sensor z.
    PxPyPz,
    /// body x = +sensor x, body y = −sensor y, body z = −sensor z.
    PxNyNz,
    /// body x = +sensor x, body y = +sensor z, body z = −sensor y.
    PxPzNy,
    /// body x = +sensor x, body y = −sensor z, body z = +sensor y.
    PxNzPy,
    /// body x = −sensor x, body y = +sensor y, body z = −sensor z.
    NxPyNz,
    /// body x = −sensor x, body y = −sensor y, body z = +sensor z.
    NxNyPz,
    /// body x = −sensor x, body y = +sensor z, body z = +sensor y.
    NxPzPy,
    /// body x = −sensor x, body y = −sensor z, body z = −sensor y.
    NxNzNy,
    /// body x = +sensor y, body y = +sensor x, body z = −sensor z.
    PyPxNz,
    /// body x = +sensor y, body y = −sensor x, body z = +sensor z.
    PyNxPz,
    /// body x = +sensor y, body y = +sensor z, body z = +sensor x.
    PyPzPx,
    /// body x = +sensor y, body y = −sensor z, body z = −sensor x.
    PyNzNx,
    /// body x = −sensor y, body y = +sensor x, body z = +sensor z.
    NyPxPz,
    /// body x = −sensor y, body y = −sensor x, body z = −sensor z.
    NyNxNz,
    /// body x = −sensor y, body y = +sensor z, body z = −sensor x.
    NyPzNx,
    /// body x = −sensor y, body y = −sensor z, body z = +sensor x.
    NyNzPx,
    /// body x = +sensor z, body y = +sensor x, body z = +sensor y.
    PzPxPy,
    /// body x = +sensor z, body y = −sensor x, body z = −sensor y.
    PzNxNy,
    /// body x = +sensor z, body y = +sensor y, body z = −sensor x.
    PzPyNx,
    /// body x = +sensor z, body y = −sensor y, body z = +sensor x.
    PzNyPx,
    /// body x = −sensor z, body y = +sensor x, body z = −sensor y.
    NzPxNy,
    /// body x = −sensor z, body y = −sensor x, body z = +sensor y.
    NzNxPy,
    /// body x = −sensor z, body y = +sensor y, body z = +sensor x.
    NzPyPx,
    /// body x = −sensor z, body y = −sensor y, body z = −sensor x.
    NzNyNx,
}

impl AxisRemap {
    /// All 24 remaps.
    pub const ALL: [AxisRemap; 24] = [
        AxisRemap::PxPyPz,
        AxisRemap::PxNyNz,
        AxisRemap::PxPzNy,
        AxisRemap::PxNzPy,
        AxisRemap::NxPyNz,
        AxisRemap::NxNyPz,
        AxisRemap::NxPzPy,
        AxisRemap::NxNzNy,
        AxisRemap::PyPxNz,
        AxisRemap::PyNxPz,
        AxisRemap::PyPzPx,
        AxisRemap::PyNzNx,
        AxisRemap::NyPxPz,
        AxisRemap::NyNxNz,
        AxisRemap::NyPzNx,
        AxisRemap::NyNzPx,
        AxisRemap::PzPxPy,
        AxisRemap::PzNxNy,
        AxisRemap::PzPyNx,
        AxisRemap::PzNyPx,
        AxisRemap::NzPxNy,
        AxisRemap::NzNxPy,
        AxisRemap::NzPyPx,
        AxisRemap::NzNyNx,
    ];

    /// For body x, y, z: the sensor axis (0, 1, 2) and whether it is negated.
    #[inline]
    const fn table(self) -> [(usize, bool); 3] {
        match self {
            AxisRemap::PxPyPz => [(0, false), (1, false), (2, false)],
            AxisRemap::PxNyNz => [(0, false), (1, true), (2, true)],
            AxisRemap::PxPzNy => [(0, false), (2, false), (1, true)],
            AxisRemap::PxNzPy => [(0, false), (2, true), (1, false)],
            AxisRemap::NxPyNz => [(0, true), (1, false), (2, true)],
            AxisRemap::NxNyPz => [(0, true), (1, true), (2, false)],
            AxisRemap::NxPzPy => [(0, true), (2, false), (1, false)],
            AxisRemap::NxNzNy => [(0, true), (2, true), (1, true)],
            AxisRemap::PyPxNz => [(1, false), (0, false), (2, true)],
            AxisRemap::PyNxPz => [(1, false), (0, true), (2, false)],
            AxisRemap::PyPzPx => [(1, false), (2, false), (0, false)],
            AxisRemap::PyNzNx => [(1, false), (2, true), (0, true)],
            AxisRemap::NyPxPz => [(1, true), (0, false), (2, false)],
            AxisRemap::NyNxNz => [(1, true), (0, true), (2, true)],
            AxisRemap::NyPzNx => [(1, true), (2, false), (0, true)],
            AxisRemap::NyNzPx => [(1, true), (2, true), (0, false)],
            AxisRemap::PzPxPy => [(2, false), (0, false), (1, false)],
            AxisRemap::PzNxNy => [(2, false), (0, true), (1, true)],
            AxisRemap::PzPyNx => [(2, false), (1, false), (0, true)],
            AxisRemap::PzNyPx => [(2, false), (1, true), (0, false)],
            AxisRemap::NzPxNy => [(2, true), (0, false), (1, true)],
            AxisRemap::NzNxPy => [(2, true), (0, true), (1, false)],
            AxisRemap::NzPyPx => [(2, true), (1, false), (0, false)],
            AxisRemap::NzNyNx => [(2, true), (1, true), (0, true)],
        }
    }

    /// The remap as a rotation matrix `R` with `v_body = R v_sensor`.
    #[must_use]
    pub fn matrix<T: Real>(self) -> [[T; 3]; 3] {
        let mut r = [[T::ZERO; 3]; 3];
        for (row, (axis, neg)) in r.iter_mut().zip(self.table()) {
            if let Some(e) = row.get_mut(axis) {
                *e = if neg { -T::ONE } else { T::ONE };
            }
        }
        r
    }

    /// The vector `v` (sensor axes) in body axes: sign flips and a permutation, exact.
    #[inline]
    #[must_use]
    pub fn rotate<T: Real>(self, v: Vec3<T>) -> Vec3<T> {
        let s = [v.x, v.y, v.z];
        let pick = |(axis, neg): (usize, bool)| {
            let c = match axis {
                0 => s[0],
                1 => s[1],
                _ => s[2],
            };
            if neg {
                -c
            } else {
                c
            }
        };
        let [a, b, c] = self.table();
        Vec3::new(pick(a), pick(b), pick(c))
    }

    /// The sample in body axes (the saturation flag kept).
    #[inline]
    #[must_use]
    pub fn apply<T: Real>(self, s: GyroSample<T>) -> GyroSample<T> {
        GyroSample {
            rate: self.rotate(s.rate),
            saturated: s.saturated,
        }
    }
}

/// Sensor-to-body alignment: a named [`AxisRemap`] or a rotation matrix (a measured misalignment).
///
/// ```
/// use quatprop::frontend::{Alignment, AxisRemap};
/// use quatprop::{Error, GyroSample, Vec3};
/// let c = 0.01_f64.cos();
/// let s = 0.01_f64.sin(); // 0.01 rad of misalignment about z
/// let a = Alignment::from_matrix([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])?;
/// let out = a.apply(GyroSample::new(Vec3::new(1.0, 0.0, 0.0)));
/// assert!((out.rate.y - s).abs() < 1e-16);
/// let shear = [[1.0, 0.01, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0_f64]];
/// assert_eq!(Alignment::from_matrix(shear), Err(Error::NotARotation));
/// assert_eq!(Alignment::<f64>::from(AxisRemap::PxPyPz).apply(out), out);
/// # Ok::<(), Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Alignment<T> {
    /// One of the 24 square mountings.
    Remap(AxisRemap),
    /// A rotation matrix `R`, `v_body = R v_sensor`, validated by [`Alignment::from_matrix`].
    Matrix([[T; 3]; 3]),
}

impl<T: Real> From<AxisRemap> for Alignment<T> {
    fn from(r: AxisRemap) -> Self {
        Alignment::Remap(r)
    }
}

impl<T: Real> Alignment<T> {
    /// A measured alignment `R` (`v_body = R v_sensor`).
    ///
    /// # Errors
    /// [`Error::NotARotation`] unless every entry is finite, every entry of `RᵀR − I` is within
    /// [`ROTATION_TOLERANCE`] and so is `det R − 1` (a reflection has `det R = −1`).
    pub fn from_matrix(r: [[T; 3]; 3]) -> Result<Self, Error> {
        let m = r.map(|row| row.map(|e| e.to_f64()));
        if !m.iter().flatten().all(|e| e.is_finite()) {
            return Err(Error::NotARotation);
        }
        let tol = ROTATION_TOLERANCE;
        for i in 0..3 {
            for j in 0..3 {
                let dot: f64 = (0..3).map(|k| m[k][i] * m[k][j]).sum();
                let target = if i == j { 1.0 } else { 0.0 };
                if !((dot - target).abs() <= tol) {
                    return Err(Error::NotARotation);
                }
            }
        }
        if !((super::det3(&m) - 1.0).abs() <= tol) {
            return Err(Error::NotARotation);
        }
        Ok(Alignment::Matrix(r))
    }

    /// The sample in body axes (the saturation flag kept).
    #[inline]
    #[must_use]
    pub fn apply(&self, s: GyroSample<T>) -> GyroSample<T> {
        let rate = match self {
            Alignment::Remap(r) => r.rotate(s.rate),
            Alignment::Matrix(m) => super::mat_vec(m, s.rate),
        };
        GyroSample {
            rate,
            saturated: s.saturated,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_remap_is_a_distinct_proper_rotation() {
        let mut seen = [[[0i8; 3]; 3]; 24];
        for (k, r) in AxisRemap::ALL.iter().enumerate() {
            let m = r.matrix::<f64>();
            assert!(Alignment::from_matrix(m).is_ok(), "{r:?}");
            seen[k] = m.map(|row| row.map(|e| e as i8));
            // rotate() is the matrix product.
            let v = Vec3::new(1.0, 2.0, 3.0);
            let w = r.rotate(v);
            let mv = [0, 1, 2].map(|i| m[i][0] * v.x + m[i][1] * v.y + m[i][2] * v.z);
            assert_eq!([w.x, w.y, w.z], mv, "{r:?}");
        }
        for i in 0..24 {
            for j in 0..i {
                assert_ne!(seen[i], seen[j]);
            }
        }
    }

    #[test]
    fn bad_matrices_are_refused() {
        let mirror = [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0_f32]];
        assert_eq!(Alignment::from_matrix(mirror), Err(Error::NotARotation));
        let mut nan = AxisRemap::PxPyPz.matrix::<f32>();
        nan[1][2] = f32::NAN;
        assert_eq!(Alignment::from_matrix(nan), Err(Error::NotARotation));
        let scaled = [[1.001, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0_f32]];
        assert_eq!(Alignment::from_matrix(scaled), Err(Error::NotARotation));
        // Just inside the tolerance: 1 + 4e-5 squared is 1 + 8e-5.
        let inside = [[1.00004, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0_f32]];
        assert!(Alignment::from_matrix(inside).is_ok());
    }
}
