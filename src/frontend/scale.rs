//! Raw gyro counts to body rates.

use crate::{Error, GyroSample, Real, Vec3};

/// The scale of a 16-bit gyro: rad/s per count, and the rails that mark a clipped axis.
///
/// Two ways to state it, as datasheets do: [`CountScale::full_scale_dps`] (±FS °/s spans the 16-bit range,
/// so one count is `FS/32768` °/s: the ICM-426xx and BMI088 convention) or
/// [`CountScale::sensitivity`] (counts per °/s as printed, e.g. 131, 65.5, 32.8, 16.4 for the MPU-6050's
/// ±250…±2000 °/s ranges). A count at `i16::MIN` or `i16::MAX` on any axis marks the sample saturated.
///
/// A scale that is zero, negative or not finite is refused with [`Error::InvalidScale`]: a zero scale
/// would read every rate as zero and a negative one would reverse every axis, both silently.
///
/// ```
/// use quatprop::{frontend::CountScale, Error};
/// let scale = CountScale::<f64>::full_scale_dps(2000.0)?;
/// let s = scale.sample([16384, 0, -32768]);
/// assert!((s.rate.x - 1000f64.to_radians()).abs() < 1e-12); // half of full scale
/// assert!(s.saturated); // z sits at the negative rail
/// assert!(!CountScale::<f64>::sensitivity(131.0)?.sample([131, 0, 0]).saturated);
/// assert_eq!(CountScale::<f32>::sensitivity(-131.0), Err(Error::InvalidScale));
/// # Ok::<(), Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CountScale<T> {
    rad_per_count: T,
}

impl<T: Real> CountScale<T> {
    /// ±`full_scale` °/s over the 16-bit range: `full_scale/32768` °/s per count.
    ///
    /// # Errors
    /// [`Error::InvalidScale`] if `full_scale` is zero, negative or not finite, or the scale per count is
    /// not a positive finite number in `T` (it underflows to zero or overflows).
    pub fn full_scale_dps(full_scale: f64) -> Result<Self, Error> {
        Self::from_rad_per_count(full_scale, full_scale.to_radians() / 32768.0)
    }

    /// `counts_per_dps` counts per °/s, as a datasheet prints it.
    ///
    /// # Errors
    /// [`Error::InvalidScale`] as for [`CountScale::full_scale_dps`].
    pub fn sensitivity(counts_per_dps: f64) -> Result<Self, Error> {
        Self::from_rad_per_count(counts_per_dps, 1f64.to_radians() / counts_per_dps)
    }

    /// The scale `rad_per_count` rounded once to `T`, if the datasheet figure `stated` and the scale are
    /// positive and finite.
    fn from_rad_per_count(stated: f64, rad_per_count: f64) -> Result<Self, Error> {
        let k = T::from_f64(rad_per_count);
        if stated > 0.0 && stated.is_finite() && k > T::ZERO && k.is_finite() {
            Ok(Self { rad_per_count: k })
        } else {
            Err(Error::InvalidScale)
        }
    }

    /// rad/s per count.
    #[must_use]
    pub fn rad_per_count(&self) -> T {
        self.rad_per_count
    }

    /// The sample of raw counts `[x, y, z]` (sensor axes), flagged saturated if any axis is at a rail.
    #[inline]
    #[must_use]
    pub fn sample(&self, counts: [i16; 3]) -> GyroSample<T> {
        let rail = counts.iter().any(|&c| c == i16::MAX || c == i16::MIN);
        let k = self.rad_per_count;
        let to_real = |c: i16| T::from_i32(i32::from(c));
        let rate = Vec3::new(
            to_real(counts[0]) * k,
            to_real(counts[1]) * k,
            to_real(counts[2]) * k,
        );
        GyroSample {
            rate,
            saturated: rail,
        }
    }
}
