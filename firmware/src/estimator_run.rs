//! The example estimator (`examples/estimator/filter.rs`, included as it is) on a BROAD excerpt
//! (`firmware/data/broad07_imu.bin`: 7 s of trial 07's gyroscope and accelerometer, CC BY 4.0, see
//! `firmware/data/README.md`), in f32: the `estimator` program prints what this returns on every QEMU board,
//! and the host test compares it with `expected/estimator.txt`, bit for bit.

#[allow(dead_code)]
#[path = "../../examples/estimator/filter.rs"]
pub mod filter;

use filter::{Filter, FilterError, Params};
use quatprop::{Quat, Vec3};

/// The excerpt: float32 little-endian rows `gx gy gz ax ay az` (rad/s, m/s²).
const IMU: &[u8] = include_bytes!("../data/broad07_imu.bin");
/// BROAD's sampling rate (Hz).
pub const RATE_HZ: f64 = 2000.0 / 7.0;
/// Samples between two reported states.
pub const EVERY: usize = 500;

/// Sample `k` of the excerpt (`None` past its end).
fn sample(k: usize) -> Option<(Vec3<f32>, Vec3<f32>)> {
    let row = IMU.get(k * 24..k * 24 + 24)?;
    let f = |i: usize| -> Option<f32> {
        let b: [u8; 4] = row.get(4 * i..4 * i + 4)?.try_into().ok()?;
        Some(f32::from_le_bytes(b))
    };
    Some((
        Vec3::new(f(0)?, f(1)?, f(2)?),
        Vec3::new(f(3)?, f(4)?, f(5)?),
    ))
}

/// The samples in the excerpt.
#[must_use]
pub fn len() -> usize {
    IMU.len() / 24
}

/// The filter's state after a sample: attitude, bias and inclination σ (their bit patterns are what the
/// program prints).
// A plain record, one documented field a line: alike in shape only to other records.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State {
    /// Samples taken.
    pub samples: usize,
    /// The attitude (body to reference).
    pub q: Quat<f32>,
    /// The bias estimate (rad/s).
    pub bias: Vec3<f32>,
    /// The inclination's 1σ (rad).
    pub sigma: f32,
    /// Updates applied and rejected so far.
    pub updates: u64,
    /// Updates the gate rejected.
    pub rejected: u64,
}

/// Runs the filter over the excerpt, calling `report` after every [`EVERY`]-th sample and the last.
///
/// # Errors
/// The filter's, at the first refused sample (none on this excerpt).
pub fn run(mut report: impl FnMut(&State)) -> Result<(), FilterError> {
    let mut f = Filter::<f32>::new(Params::mems(1.0 / RATE_HZ))?;
    let n = len();
    for k in 0..n {
        let Some((gyro, accel)) = sample(k) else {
            break;
        };
        f.push(gyro, accel)?;
        if (k + 1) % EVERY == 0 || k + 1 == n {
            let c = f.counts();
            report(&State {
                samples: k + 1,
                q: f.attitude(),
                bias: f.bias(),
                sigma: f.inclination_sigma()?,
                updates: c.updates,
                rejected: c.rejected,
            });
        }
    }
    Ok(())
}

/// One reported state as a line of hexadecimal bit patterns (the program's defmt format, the host
/// test's text).
#[must_use]
pub fn line(s: &State) -> [u32; 8] {
    [
        s.q.w.to_bits(),
        s.q.x.to_bits(),
        s.q.y.to_bits(),
        s.q.z.to_bits(),
        s.bias.x.to_bits(),
        s.bias.y.to_bits(),
        s.bias.z.to_bits(),
        s.sigma.to_bits(),
    ]
}
