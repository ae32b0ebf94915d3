//! The one error type of the crate. On every error the propagator's state is left bit-for-bit unchanged.

use core::fmt;

/// Why a step or a construction was refused. The propagator state is unchanged whenever one is returned.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error {
    /// A rate sample (or rotation increment) has a NaN or infinite component.
    NonFiniteRate,
    /// The step `dt` is NaN or infinite.
    NonFiniteStep,
    /// The step `dt` is zero or negative.
    NonPositiveStep,
    /// The step angle `dt · max|ω|` (rad) exceeds the scheme's stability bound
    /// (see [`crate::scheme::Scheme::step_angle_limit`]).
    StepAngleBeyondStability {
        /// `dt · max|ω|` of the refused step (rad).
        step_angle: f64,
        /// The scheme's bound (rad).
        limit: f64,
    },
    /// Baumgarte's `4 k dt` exceeds the scheme's bound ([`crate::scheme::Scheme::gain_step_limit`], half its
    /// stability interval on the negative real axis), beyond which the stabilizing term itself can make the
    /// propagation oscillate or diverge.
    GainBeyondStability {
        /// `4 k dt` of the refused step.
        gain_step: f64,
        /// The scheme's bound.
        limit: f64,
    },
    /// The initial quaternion is zero (or so small that its norm underflows).
    ZeroQuaternion,
    /// The initial quaternion has a NaN or infinite component.
    NonFiniteQuaternion,
    /// A stabilizer parameter is invalid: `Every(0)`, or a Baumgarte `k` that is negative or not finite.
    InvalidStabilizer,
    /// The step produced a non-finite attitude (arithmetic overflow); the step was discarded.
    NonFiniteResult,
    /// A delta-angle update got another number of increments than its coning correction takes.
    SampleCount {
        /// Increments the correction takes.
        expected: u32,
        /// Increments given.
        got: u32,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::NonFiniteRate => f.write_str("rate sample is NaN or infinite"),
            Error::NonFiniteStep => f.write_str("step dt is NaN or infinite"),
            Error::NonPositiveStep => f.write_str("step dt is zero or negative"),
            Error::StepAngleBeyondStability { step_angle, limit } => write!(
                f,
                "step angle dt*|w| = {step_angle} rad exceeds the scheme's stability bound {limit} rad"
            ),
            Error::GainBeyondStability { gain_step, limit } => write!(
                f,
                "Baumgarte 4*k*dt = {gain_step} exceeds the scheme's gain bound {limit} (half its real-axis stability interval)"
            ),
            Error::ZeroQuaternion => f.write_str("quaternion is zero"),
            Error::NonFiniteQuaternion => f.write_str("quaternion is NaN or infinite"),
            Error::InvalidStabilizer => {
                f.write_str("invalid stabilizer: Every(0) or Baumgarte k negative or not finite")
            }
            Error::NonFiniteResult => f.write_str("step overflowed to a non-finite attitude"),
            Error::SampleCount { expected, got } => write!(
                f,
                "coning correction takes {expected} angle increments per update, got {got}"
            ),
        }
    }
}

impl core::error::Error for Error {}
