//! A sensor's noise: the densities a datasheet gives ([`GyroNoise`]), and their identification from a
//! recording at rest by the Allan variance ([`AllanVariance`], computed as the samples arrive, and
//! [`NoiseFit`], the white noise, bias instability and random walk fitted to it with their standard
//! errors).
//!
//! ```
//! use quatprop::noise::{AllanVariance, GyroNoise, NoiseFit};
//! use quatprop::Vec3;
//! let mut avar = AllanVariance::<f32, 16>::new(1.0 / 200.0)?; // a gyro at 200 Hz
//! # let mut x: u32 = 7;
//! for _ in 0..60 * 200 {
//!     # x ^= x << 13; x ^= x >> 17; x ^= x << 5;
//!     # let n = (x as f32 / u32::MAX as f32 - 0.5) * 0.01;
//!     let rest = Vec3::new(0.002 + n, -0.001 - n, 0.0005 + n); // rad/s, one minute at rest
//!     avar.push(rest)?;
//! }
//! let fit = NoiseFit::pooled(&avar).expect("a minute gives many octaves");
//! let noise = GyroNoise::<f32>::from_fit(&fit)?;   // the white noise (and the random walk if seen)
//! assert!(noise.arw() > 0.0);
//! # Ok::<(), quatprop::Error>(())
//! ```

mod allan;
mod density;
mod fit;

pub use allan::{AllanVariance, Cluster};
pub use density::GyroNoise;
pub use fit::{NoiseFit, Point, Term, FLICKER_FLOOR};
