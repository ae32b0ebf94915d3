//! The one error type of the crate. On every error the propagator's state is left bit-for-bit unchanged.

use core::fmt;

/// Why a step or a construction was refused. The propagator state is unchanged whenever one is returned.
///
/// ```
/// use quatprop::{input::Hold, scheme::Rk4, stabilize::Off, Error, GyroSample, Propagator, Quat, Vec3};
/// let mut p = Propagator::new(Quat::IDENTITY, Rk4, Hold, Off)?;
/// let before = p;
/// assert_eq!(p.push(GyroSample::new(Vec3::new(f32::NAN, 0.0, 0.0)), 1e-3), Err(Error::NonFiniteRate));
/// assert_eq!(p.push(GyroSample::new(Vec3::new(0.0, 0.0, 1.0)), 0.0), Err(Error::NonPositiveStep));
/// assert_eq!(p, before); // bit for bit
/// assert_eq!(Error::NonFiniteRate.to_string(), "rate sample is NaN or infinite");
/// # Ok::<(), Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error {
    /// A rate sample (or rotation increment) has a NaN or infinite component.
    NonFiniteRate,
    /// A reading given beside a rate (an acceleration or a temperature, [`crate::frontend::Aux`]) has a NaN
    /// or infinite component.
    NonFiniteAux,
    /// The step `dt` is NaN or infinite.
    NonFiniteStep,
    /// The step `dt` is zero or negative.
    NonPositiveStep,
    /// The step angle `dt · max|ω|` (rad) exceeds the scheme's stability bound
    /// ([`crate::scheme::Information::step_angle_limit`]).
    StepAngleBeyondStability {
        /// `dt · max|ω|` of the refused step (rad).
        step_angle: f64,
        /// The scheme's bound (rad).
        limit: f64,
    },
    /// Baumgarte's `4 k dt` exceeds [`crate::scheme::Baumgarte::gain_step_limit`] (half the scheme's
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
    /// A stabilizer parameter is invalid: `Every(0)`.
    InvalidStabilizer,
    /// A Baumgarte gain `k` is negative or not finite.
    InvalidGain,
    /// An alignment matrix is not a rotation (within
    /// [`crate::frontend::ROTATION_TOLERANCE`]: not orthonormal, a reflection, or not finite).
    NotARotation,
    /// A timestamp does not advance: a duplicate, or one behind the previous timestamp.
    TimestampNotIncreasing,
    /// A clock's counter width is outside 1–32 bits.
    InvalidClock,
    /// A bias estimator's window holds no sample or more than 2³¹ − 1, or a period, gate, span or initial
    /// sigma is not finite and positive, or a drift is negative or not finite.
    InvalidEstimator,
    /// A gyro calibration has a number that is not finite, or its matrix `M · diag(sensitivity)` is
    /// singular or worse conditioned than [`crate::frontend::Calibration::CONDITION_LIMIT`].
    InvalidCalibration,
    /// A gyro's count scale (full scale or sensitivity) is zero, negative or not finite, or its rad/s per
    /// count is not a positive finite number in the working precision.
    InvalidScale,
    /// The step produced a non-finite attitude (arithmetic overflow); the step was discarded.
    NonFiniteResult,
    /// A [`crate::config::Config`] asks for Baumgarte's term on a scheme that is not Runge–Kutta (the
    /// term lives in the stages of the Runge–Kutta engine; the exponential maps have none).
    BaumgarteNeedsRungeKutta,
    /// A sample of the other kind: a rate sample for a [`crate::config::Configured`] propagator whose input
    /// model takes delta angles, or a delta angle for one that takes rates.
    WrongSampleKind,
    /// A noise parameter (a density, a correlation time, a measurement variance) is negative, zero where
    /// it must be positive, NaN or infinite ([`crate::error_state::GyroNoise`],
    /// [`crate::covariance::Ud::update`]).
    InvalidNoise,
    /// A covariance is not what it claims: not finite, not symmetric, or not positive semi-definite
    /// ([`crate::covariance::Ud::from_matrix`]), or a matrix given to its predict step is not finite.
    InvalidCovariance,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::NonFiniteRate => f.write_str("rate sample is NaN or infinite"),
            Error::NonFiniteAux => {
                f.write_str("acceleration or temperature given beside a rate is NaN or infinite")
            }
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
            Error::InvalidStabilizer => f.write_str("invalid stabilizer: Every(0)"),
            Error::InvalidGain => f.write_str("Baumgarte gain k is negative or not finite"),
            Error::NotARotation => f.write_str("alignment matrix is not a rotation"),
            Error::TimestampNotIncreasing => {
                f.write_str("timestamp does not advance (duplicate or backwards)")
            }
            Error::InvalidClock => f.write_str("clock counter width must be 1 to 32 bits"),
            Error::InvalidEstimator => f.write_str(
                "bias estimator: the window must hold 1 to 2^31-1 samples, the period, gates, span and sigma be positive and finite, the drifts finite and not negative",
            ),
            Error::InvalidCalibration => f.write_str(
                "gyro calibration: a number is not finite, or M*diag(sensitivity) is singular or ill-conditioned",
            ),
            Error::InvalidScale => {
                f.write_str("count scale: full scale or sensitivity must be finite and positive")
            }
            Error::NonFiniteResult => f.write_str("step overflowed to a non-finite attitude"),
            Error::BaumgarteNeedsRungeKutta => {
                f.write_str("Baumgarte's term needs a Runge-Kutta scheme (Euler, Rk2 to Rk5)")
            }
            Error::WrongSampleKind => f.write_str(
                "sample of the wrong kind: rates for a delta-angle input model, or delta angles for a rate one",
            ),
            Error::InvalidNoise => {
                f.write_str("noise parameter or variance is negative, zero where it must be positive, or not finite")
            }
            Error::InvalidCovariance => f.write_str(
                "covariance is not finite, not symmetric or not positive semi-definite",
            ),
        }
    }
}

impl core::error::Error for Error {}
