//! A gyro's own calibration (offset, per-axis sensitivity, misalignment of its axes), apart from how
//! the sensor is mounted ([`Alignment`](super::Alignment)).

use crate::{Error, GyroSample, Real, Vec3};

/// A gyro's calibration in the sensor's axes: `ω = M · (s ⊙ (r − o))`, applied to a reading `r` (rad/s)
/// before the mounting rotation.
///
/// - `offset` `o` (rad/s): the zero-rate output a calibration measured, subtracted first. A bias that
///   drifts is the [`BiasEstimator`](super::BiasEstimator)'s job, after the mounting.
/// - `sensitivity` `s`: the per-axis scale factors (dimensionless, near 1) multiplying the offset-free
///   reading component by component.
/// - `misalignment` `M`: the non-orthogonality of the sensor's axes (near the identity; not a rotation:
///   the mounting is [`Alignment`](super::Alignment)'s).
///
/// The arithmetic and its order are Fusion's `FusionCalibrationInertial` (subtract, multiply per axis,
/// then each row of `M` as `m₀x + m₁y + m₂z` from the left), so the same numbers give the same bits.
/// The order of the front end is: counts ([`CountScale`](super::CountScale)), this, the mounting, the
/// bias.
///
/// ```
/// use quatprop::frontend::Calibration;
/// use quatprop::{Error, GyroSample, Vec3};
/// let cal = Calibration::new(
///     Vec3::new(0.5_f32, -0.25, 0.0),                     // offset (rad/s)
///     Vec3::new(1.5, 0.5, 1.0),                           // sensitivity
///     [[1.0, 0.25, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], // misalignment
/// )?;
/// // r − o = (1, 1, 0.5); ⊙ s = (1.5, 0.5, 0.5); M: (1.5 + 0.25·0.5, 0.5, 0.5).
/// let w = cal.apply(GyroSample::new(Vec3::new(1.5, 0.75, 0.5))).rate;
/// assert_eq!(w, Vec3::new(1.625, 0.5, 0.5));
/// // A singular matrix (here a zero sensitivity) is refused.
/// let flat = Calibration::new(Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0), [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0_f32]]);
/// assert_eq!(flat, Err(Error::InvalidCalibration));
/// # Ok::<(), Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Calibration<T> {
    offset: Vec3<T>,
    sensitivity: Vec3<T>,
    misalignment: [[T; 3]; 3],
}

impl<T: Real> Calibration<T> {
    /// The largest condition number `‖A‖∞ ‖A⁻¹‖∞` of `A = M · diag(s)` that [`Calibration::new`]
    /// accepts. A gyro's calibration is near the identity (a few per cent of scale, a few milliradians
    /// of axis error: a condition number near 1); one that amplifies a reading's relative error 100-fold
    /// is a mistake in its numbers.
    pub const CONDITION_LIMIT: f64 = 100.0;

    /// A calibration from its offset (rad/s), sensitivity and misalignment matrix.
    ///
    /// # Errors
    /// [`Error::InvalidCalibration`] unless every number is finite and `A = M · diag(s)` is invertible
    /// with a condition number `‖A‖∞ ‖A⁻¹‖∞` (computed in f64) of at most
    /// [`CONDITION_LIMIT`](Self::CONDITION_LIMIT).
    pub fn new(
        offset: Vec3<T>,
        sensitivity: Vec3<T>,
        misalignment: [[T; 3]; 3],
    ) -> Result<Self, Error> {
        let finite = offset.is_finite()
            && sensitivity.is_finite()
            && misalignment.iter().flatten().all(|e| e.is_finite());
        if !finite {
            return Err(Error::InvalidCalibration);
        }
        let s = [sensitivity.x, sensitivity.y, sensitivity.z].map(|e| e.to_f64());
        let a: [[f64; 3]; 3] =
            core::array::from_fn(|i| core::array::from_fn(|j| misalignment[i][j].to_f64() * s[j]));
        match condition_number(&a) {
            Some(k) if k <= Self::CONDITION_LIMIT => Ok(Self {
                offset,
                sensitivity,
                misalignment,
            }),
            _ => Err(Error::InvalidCalibration),
        }
    }

    /// No correction: zero offset, unit sensitivity, identity misalignment.
    #[must_use]
    pub fn identity() -> Self {
        let (o, l) = (T::ZERO, T::ONE);
        Self {
            offset: Vec3::ZERO,
            sensitivity: Vec3::new(l, l, l),
            misalignment: [[l, o, o], [o, l, o], [o, o, l]],
        }
    }

    /// `ω = m·(r − offset)` as a calibration: the sensitivity is `m`'s diagonal, the misalignment `m`'s
    /// columns divided by it. For a gain near the identity (what
    /// [`CalibrationEstimator`](super::CalibrationEstimator) learns: each term within 5 %), unchecked.
    pub(super) fn from_gain(offset: Vec3<T>, m: [[T; 3]; 3]) -> Self {
        let s = [m[0][0], m[1][1], m[2][2]];
        Self {
            offset,
            sensitivity: Vec3::new(s[0], s[1], s[2]),
            misalignment: core::array::from_fn(|i| {
                core::array::from_fn(|j| if i == j { T::ONE } else { m[i][j] / s[j] })
            }),
        }
    }

    /// The calibrated sample (the saturation flag kept).
    #[inline]
    #[must_use]
    pub fn apply(&self, s: GyroSample<T>) -> GyroSample<T> {
        let d = s.rate - self.offset;
        let v = Vec3::new(
            d.x * self.sensitivity.x,
            d.y * self.sensitivity.y,
            d.z * self.sensitivity.z,
        );
        GyroSample {
            rate: super::mat_vec(&self.misalignment, v),
            saturated: s.saturated,
        }
    }

    /// The offset (rad/s).
    #[must_use]
    pub fn offset(&self) -> Vec3<T> {
        self.offset
    }

    /// The per-axis sensitivity.
    #[must_use]
    pub fn sensitivity(&self) -> Vec3<T> {
        self.sensitivity
    }

    /// The misalignment matrix (rows).
    #[must_use]
    pub fn misalignment(&self) -> [[T; 3]; 3] {
        self.misalignment
    }
}

/// `‖A‖∞ ‖A⁻¹‖∞` (the largest absolute row sum of each), `None` when `A` is singular or the result is
/// not finite.
fn condition_number(a: &[[f64; 3]; 3]) -> Option<f64> {
    let det = super::det3(a);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    // A⁻¹[i][j] = cof(j, i) / det (the cyclic cofactors carry their signs).
    let norm = |m: &dyn Fn(usize, usize) -> f64| {
        (0..3)
            .map(|i| (0..3).map(|j| m(i, j).abs()).sum::<f64>())
            .fold(0.0, f64::max)
    };
    let k = norm(&|i, j| a[i][j]) * norm(&|i, j| super::cofactor(a, j, i) / det);
    k.is_finite().then_some(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    const I: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

    #[test]
    fn condition_number_of_known_matrices() {
        assert_eq!(condition_number(&I), Some(1.0));
        // diag(1, 1, 1/50): ‖A‖∞ = 1, ‖A⁻¹‖∞ = 50.
        let d = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.02]];
        assert!((condition_number(&d).unwrap() - 50.0).abs() < 1e-12);
        // [[1, 1], [0, 1]] in the top corner: A⁻¹ = [[1, −1], [0, 1]]; both norms 2.
        let shear = [[1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!((condition_number(&shear).unwrap() - 4.0).abs() < 1e-12);
        let singular = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]];
        assert_eq!(condition_number(&singular), None);
    }

    #[test]
    fn condition_number_matches_numpy_on_a_realistic_calibration() {
        let a = [
            [1.02, 0.01, -0.003],
            [0.004, 0.98, 0.02],
            [-0.01, 0.005, 1.01],
        ];
        // numpy: norm(a, inf) * norm(inv(a), inf)
        let k = condition_number(&a).unwrap();
        assert!((k - 1.079460299929621).abs() < 1e-12, "{k}");
    }

    #[test]
    fn refuses_what_is_not_finite_or_too_ill_conditioned() {
        let id = I.map(|r| r.map(|e| e as f32));
        let ok = Calibration::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 1.0_f32), id);
        assert!(ok.is_ok());
        let nan = Calibration::new(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0), id);
        assert_eq!(nan, Err(Error::InvalidCalibration));
        let inf_m = {
            let mut m = id;
            m[1][2] = f32::INFINITY;
            Calibration::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 1.0), m)
        };
        assert_eq!(inf_m, Err(Error::InvalidCalibration));
        // Sensitivities 1 and 1/100: condition 100 is accepted, 1/101 is not.
        let at = Calibration::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.01_f64), I);
        assert!(at.is_ok());
        let past = Calibration::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 1.0 / 101.0_f64), I);
        assert_eq!(past, Err(Error::InvalidCalibration));
    }

    #[test]
    fn apply_is_offset_then_sensitivity_then_rows_and_keeps_the_flag() {
        let cal = Calibration::new(
            Vec3::new(0.5, -0.25, 0.125_f64),
            Vec3::new(2.0, 4.0, 0.5),
            [[1.0, 0.5, 0.0], [0.0, 1.0, 0.25], [0.125, 0.0, 1.0]],
        )
        .unwrap();
        let mut s = GyroSample::new(Vec3::new(1.5, 0.75, 2.125));
        s.saturated = true;
        let out = cal.apply(s);
        // r − o = (1, 1, 2); ⊙ s = (2, 4, 1); rows: (2 + 2, 4 + 0.25, 0.25 + 1).
        assert_eq!(out.rate, Vec3::new(4.0, 4.25, 1.25));
        assert!(out.saturated);
    }
}
