//! The README's FIFO quick start, verbatim between the markers (the firmware's host tests,
//! firmware/src/tests/quick_start.rs, check that the README shows exactly this code): a crate of its own
//! because three others run it, the same f32 arithmetic everywhere: the firmware (its `quickstart`
//! program on the M4F, its host tests) and the C API's comparison harness (`ffi`, feature
//! `rust-baseline`).
#![no_std]

// Spelled out as users paste it: the C API's comparison harness keeps its own copy on the run-time kinds
// (`ffi/src/baseline.rs`), which cannot share this code without changing what the README shows.
// quick start: begin
use quatprop::frontend::{AxisRemap, BiasEstimator, CountScale, FixedPeriod};
use quatprop::{Error, GyroSample, Propagator, Quat, Recommended};

/// Samples converted per batch of a FIFO read.
const BATCH: usize = 8;
/// The gyro's sample period (s): 1 kHz.
const PERIOD: f64 = 1.0e-3;

/// One attitude, fed from a gyro's FIFO: raw counts → body axes → bias removed → integrated.
pub struct Attitude {
    scale: CountScale<f32>,
    mounting: AxisRemap,
    bias: BiasEstimator<f32>,
    period: FixedPeriod<f32>,
    propagator: Recommended<f32>,
    batch: [GyroSample<f32>; BATCH],
    refused: u32,
}

impl Attitude {
    /// A ±2000 °/s, 16-bit gyro at 1 kHz, mounted turned 90° about z (body x = sensor y).
    pub fn new() -> Result<Self, Error> {
        Ok(Self {
            scale: CountScale::full_scale_dps(2000.0)?,
            mounting: AxisRemap::PyNxPz,
            // Learns the bias over 1 s windows while every axis stays within 0.05 rad/s (2.9 °/s).
            bias: BiasEstimator::new(1.0, PERIOD, 0.05)?,
            period: FixedPeriod::new(PERIOD)?,
            propagator: Propagator::recommended(Quat::IDENTITY)?,
            batch: [GyroSample::default(); BATCH],
            refused: 0,
        })
    }

    /// Takes one FIFO read of raw counts `[x, y, z]` (sensor axes), one sample per period, any length.
    pub fn on_fifo(&mut self, fifo: &[[i16; 3]]) {
        for batch in fifo.chunks(BATCH) {
            for (slot, &counts) in self.batch.iter_mut().zip(batch) {
                let sample = self.mounting.apply(self.scale.sample(counts));
                // Counts are always finite, so the estimator never refuses them.
                *slot = self.bias.update(sample).unwrap_or(sample);
            }
            // A refused sample stops the burst with the state as it was; its interval carries into the next.
            let mut rest = self.batch.get(..batch.len()).unwrap_or(&[]);
            while let Err(refused) = self.propagator.push_burst(rest, &mut self.period) {
                self.refused += 1;
                rest = rest.get(refused.index + 1..).unwrap_or(&[]);
            }
        }
    }

    /// The attitude (body to reference) and how many samples were refused.
    pub fn attitude(&self) -> (Quat<f32>, u32) {
        (self.propagator.attitude(), self.refused)
    }
}
// quick start: end
