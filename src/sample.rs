//! What one push into the propagator carries: a gyro rate sample or an angle increment, each with its
//! saturation flag.

use crate::Vec3;

/// A sensor reading as the propagator takes it: every input model names its sample type, and the
/// propagator counts saturated samples on every path ([`crate::Propagator::saturated_samples`]).
pub trait Sample: Copy {
    /// `true` if the sensor clipped (an axis at full scale).
    fn is_saturated(&self) -> bool;
}

/// One gyro reading: body-frame rate (rad/s) and whether any axis sat at the sensor's full scale.
///
/// Every rate input model ([`crate::input::Hold`], [`crate::input::Linear`], [`crate::input::History`],
/// [`crate::input::TwiceRate`], [`crate::input::GaussPoints`]) takes this type. A saturated sample is a lower
/// bound of the true rate, so it is integrated, and counted: an attitude built from clipped samples is
/// suspect, and peers (Fusion, Betaflight, Cleanflight) lose attitude silently when the gyro clips.
///
/// ```
/// use quatprop::{GyroSample, Vec3};
/// let s = GyroSample::new(Vec3::new(0.0_f32, 0.0, 1.0));
/// assert!(!s.saturated);
/// assert!(GyroSample::clipped(Vec3::new(0.0_f32, 0.0, 35.0)).saturated);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GyroSample<T> {
    /// Body-frame rate (rad/s).
    pub rate: Vec3<T>,
    /// `true` if at least one axis read the sensor's full-scale value.
    pub saturated: bool,
}

impl<T> GyroSample<T> {
    /// A rate (rad/s, body frame) that did not clip.
    #[inline]
    #[must_use]
    pub const fn new(rate: Vec3<T>) -> Self {
        Self {
            rate,
            saturated: false,
        }
    }

    /// A rate (rad/s, body frame) read with at least one axis at the sensor's full scale.
    #[inline]
    #[must_use]
    pub const fn clipped(rate: Vec3<T>) -> Self {
        Self {
            rate,
            saturated: true,
        }
    }
}

impl<T: Copy> Sample for GyroSample<T> {
    #[inline(always)]
    fn is_saturated(&self) -> bool {
        self.saturated
    }
}

/// One delta-angle reading: the angle increment `Δθ = ∫ω dt` (rad, body frame) over one sensor sample
/// interval, and whether the sensor clipped during it. Taken by [`crate::input::DeltaAngles`].
///
/// ```
/// use quatprop::{DeltaAngle, Vec3};
/// let d = DeltaAngle::new(Vec3::new(0.0_f64, 0.0, 1.0e-3));
/// assert_eq!(d.angle.z, 1.0e-3);
/// assert!(!d.saturated);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DeltaAngle<T> {
    /// Angle increment (rad, body frame).
    pub angle: Vec3<T>,
    /// `true` if the sensor clipped during the interval.
    pub saturated: bool,
}

impl<T> DeltaAngle<T> {
    /// An increment (rad, body frame) that did not clip.
    #[inline]
    #[must_use]
    pub const fn new(angle: Vec3<T>) -> Self {
        Self {
            angle,
            saturated: false,
        }
    }
}

impl<T: Copy> Sample for DeltaAngle<T> {
    #[inline(always)]
    fn is_saturated(&self) -> bool {
        self.saturated
    }
}
