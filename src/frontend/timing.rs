//! What a gyro sample stands for in time, and how each meaning is honoured.
//!
//! | a sample is | honoured by |
//! |---|---|
//! | the rate **at its timestamp** (an instantaneous reading) | the rate input models, which interpolate between samples ([`crate::input::History`], [`crate::input::Linear`]; the default) |
//! | the **mean rate over the interval** that ends at its timestamp (a sensor that integrates or averages between reads) | [`SampleTiming::increment`]: the rate times the interval is the exact angle increment, for [`crate::input::DeltaAngles`] and its coning correction |
//! | either, **delayed** by a filter's group delay `τ` (s) | [`SampleTiming::ahead`]: the attitude after the sample is the attitude at `t − τ`; it is carried forward by `τ` at the sample's rate |
//!
//! Which one a sensor gives is in its datasheet (an output data rate with a digital low-pass filter: a
//! filtered rate with its group delay; a "delta angle" or "integrated" output: interval means), or is
//! found by fitting the shift between the gyro and a reference (docs/broad.md does so on real recordings).

use crate::{DeltaAngle, Error, GyroSample, Quat, Real};

/// What a rate sample means in time: a reading at its timestamp or a mean over the interval before it,
/// and a group delay (s) behind its timestamp.
///
/// ```
/// use quatprop::frontend::SampleTiming;
/// use quatprop::{GyroSample, Quat, Vec3};
/// // A mean over each 1 ms interval, read 2 ms after the motion it measures (a low-pass filter's delay).
/// let timing = SampleTiming::interval_mean().with_group_delay(2.0e-3_f64)?;
/// let s = GyroSample::new(Vec3::new(0.0, 0.0, 1.0));
/// assert_eq!(timing.increment(s, 1.0e-3).angle, Vec3::new(0.0, 0.0, 1.0e-3));
/// // The attitude after that sample is the attitude 2 ms ago: carried forward by 2 ms at 1 rad/s.
/// let now = timing.ahead(Quat::IDENTITY, s.rate);
/// assert!((now.angle_to(Quat::IDENTITY) - 2.0e-3).abs() < 1e-15);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SampleTiming<T> {
    interval_mean: bool,
    group_delay: T,
}

impl<T: Real> SampleTiming<T> {
    /// The rate at the sample's timestamp, no delay: what the rate input models assume.
    #[must_use]
    pub fn instant() -> Self {
        Self {
            interval_mean: false,
            group_delay: T::ZERO,
        }
    }

    /// The mean rate over the interval that ends at the sample's timestamp, no delay.
    #[must_use]
    pub fn interval_mean() -> Self {
        Self {
            interval_mean: true,
            group_delay: T::ZERO,
        }
    }

    /// The same meaning, `seconds` behind the timestamp (a filter's group delay; 0 for none).
    ///
    /// # Errors
    /// [`Error::NonFiniteStep`] for a NaN or infinite delay, [`Error::NonPositiveStep`] for a negative
    /// one (a sample cannot measure the future).
    pub fn with_group_delay(mut self, seconds: T) -> Result<Self, Error> {
        if !seconds.is_finite() {
            return Err(Error::NonFiniteStep);
        }
        if seconds < T::ZERO {
            return Err(Error::NonPositiveStep);
        }
        self.group_delay = seconds;
        Ok(self)
    }

    /// `true` for a mean over the interval (give the propagator [`SampleTiming::increment`]s).
    #[must_use]
    pub fn is_interval_mean(&self) -> bool {
        self.interval_mean
    }

    /// The group delay (s).
    #[must_use]
    pub fn group_delay(&self) -> T {
        self.group_delay
    }

    /// An interval-mean sample as the exact angle increment over its interval `dt` (s): `rate · dt` (the
    /// saturation flag kept).
    #[inline]
    #[must_use]
    pub fn increment(&self, s: GyroSample<T>, dt: T) -> DeltaAngle<T> {
        DeltaAngle {
            angle: s.rate * dt,
            saturated: s.saturated,
        }
    }

    /// The attitude `q` after a sample (the attitude at `t − τ`) carried to the sample's timestamp `t`:
    /// `q ⊗ exp(½ ω τ)` for the body rate `ω` (rad/s). Exact for a rate constant over the delay; the
    /// propagator's own state is not touched, so nothing accumulates.
    #[inline]
    #[must_use]
    pub fn ahead(&self, q: Quat<T>, rate: crate::Vec3<T>) -> Quat<T> {
        if self.group_delay == T::ZERO {
            return q;
        }
        q * Quat::from_rotation_vector(rate * self.group_delay)
    }
}

impl<T: Real> Default for SampleTiming<T> {
    fn default() -> Self {
        Self::instant()
    }
}
