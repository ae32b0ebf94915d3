//! The sensor front end: from what a gyro driver delivers to body rates on an exact time base. Each piece
//! is optional and independent; a firmware links only what it names.
//!
//! | piece | turns | into |
//! |---|---|---|
//! | [`CountScale`] | raw counts `[i16; 3]` | a [`GyroSample`] in rad/s, flagged `saturated` at a rail |
//! | [`Calibration`] | a reading in the sensor's own (non-orthogonal, mis-scaled) axes | the calibrated rate: offset, per-axis sensitivity, misalignment |
//! | [`Alignment`] | a sample in sensor axes | the same sample in body axes (one of the 24 [`AxisRemap`]s, or a rotation matrix) |
//! | [`FixedBias`], [`BiasEstimator`] | a biased sample | the sample minus the bias (fixed, or learned while the body is still) |
//! | [`CalibrationEstimator`] | a sample corrected at rest, and the accelerometer | the gain (scale and misalignment) and residual bias learned in motion, as a [`Calibration`] |
//! | [`MotionBias`] | a sample corrected at rest, and the accelerometer | the residual bias learned in motion (VQF's motion bias estimation; the accelerometer never touches the attitude) |
//! | [`FixedPeriod`] | a sample period given once | the `dt` of each sample, summing to `k·period` exactly |
//! | [`TickClock`] | the sensor's own timestamps (integer ticks, wrapping) | the `dt` of each sample, exact, with gaps counted |
//! | [`SampleTiming`] | what a sample means in time: the rate at its timestamp or the mean over the interval before it, and a group delay | angle increments for interval means; the attitude carried forward by the delay |
//!
//! ```
//! use quatprop::frontend::{AxisRemap, BiasEstimator, CountScale, FixedPeriod};
//! use quatprop::{input::History, scheme::ExpMap, stabilize::FirstOrder, Propagator, Quat};
//! let scale = CountScale::<f32>::full_scale_dps(2000.0)?;  // ±2000 °/s on 16 bits
//! let to_body = AxisRemap::PyNxPz;                          // body x = sensor y, body y = −sensor x
//! let mut bias = BiasEstimator::<f32>::new(1.0, 1.0e-3, 0.05)?; // 1 s windows at 1 kHz, 0.05 rad/s gate
//! let mut period = FixedPeriod::<f32>::new(1.0e-3)?;      // 1 kHz, kept exactly
//! let mut p = Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder)?;
//! let mut learned_at = Quat::IDENTITY;
//! for k in 0..3000 {
//!     let counts = [12_i16, -3, 7]; // a still sensor with a bias of 0.015 rad/s
//!     let s = bias.update(to_body.apply(scale.sample(counts)))?;
//!     p.push(s, period.next_dt())?;
//!     if k == 1002 {
//!         learned_at = p.attitude(); // the history's last 4 samples are all corrected now
//!     }
//! }
//! assert!(bias.is_learned());
//! // The first second integrated the bias (0.015 rad); once learned, nothing more goes in.
//! assert!(learned_at.angle_to(Quat::IDENTITY) > 0.015);
//! assert!(p.attitude().angle_to(learned_at) < 1e-6);
//! # Ok::<(), quatprop::Error>(())
//! ```

mod alignment;
mod bias;
mod calibration;
mod calibration_estimator;
mod inclination;
mod motion_bias;
mod scale;
mod time;
mod timing;

pub use alignment::{Alignment, AxisRemap, ROTATION_TOLERANCE};
pub use bias::{Aux, BiasEstimator, FixedBias};
pub use calibration::Calibration;
pub use calibration_estimator::CalibrationEstimator;
pub use motion_bias::MotionBias;
pub use scale::CountScale;
pub use time::{FixedPeriod, TickClock};
pub use timing::SampleTiming;

#[cfg(doc)]
use crate::GyroSample;
use crate::{Real, Vec3};

/// `m v` for a matrix given by rows, each row as `m₀x + m₁y + m₂z` from the left (Fusion's order: the
/// alignment and the calibration give its bits).
#[inline]
fn mat_vec<T: Real>(m: &[[T; 3]; 3], v: Vec3<T>) -> Vec3<T> {
    let row = |r: &[T; 3]| r[0] * v.x + r[1] * v.y + r[2] * v.z;
    Vec3::new(row(&m[0]), row(&m[1]), row(&m[2]))
}

/// The cofactor of entry `(i, j)`, its sign carried by the cyclic order of the rows and columns.
fn cofactor(a: &[[f64; 3]; 3], i: usize, j: usize) -> f64 {
    let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
    let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
    a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]
}

/// `det a`, expanded along the first row.
fn det3(a: &[[f64; 3]; 3]) -> f64 {
    a[0][0] * cofactor(a, 0, 0) + a[0][1] * cofactor(a, 0, 1) + a[0][2] * cofactor(a, 0, 2)
}
