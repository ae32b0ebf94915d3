//! A gyro sample as a sensor driver delivers it: the rate and whether the sensor clipped.

use crate::Vec3;

/// One gyro reading: body-frame rate (rad/s) and whether any axis sat at the sensor's full scale.
///
/// A saturated sample is still a lower bound of the true rate, so the propagator integrates it, but it
/// counts it ([`crate::Propagator::saturated_samples`]): an attitude built from clipped samples is suspect,
/// and peers (Fusion, Betaflight, Cleanflight) lose attitude silently when the gyro clips.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GyroSample<T> {
    /// Body-frame rate (rad/s).
    pub rate: Vec3<T>,
    /// `true` if at least one axis read the sensor's full-scale value.
    pub saturated: bool,
}
