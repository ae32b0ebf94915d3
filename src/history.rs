//! The last gyro samples, for the fourth-order sample-history input ([`crate::rates::History`]).

use crate::rates::History;
use crate::{Real, Vec3};

/// The three most recent gyro samples (body rates, rad/s), equally spaced in time.
///
/// Feed it with [`crate::Propagator::step_history`]: each new sample advances the attitude over the interval
/// from the previous sample to it, using up to three earlier samples — fourth order once four samples have
/// arrived, with no latency (the step ends at the newest sample). Start-up: the first sample only starts the
/// history (no step), the second gives a linear step (second order), the third a quadratic one (third).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SampleHistory<T> {
    w: [Vec3<T>; 3],
    count: u8,
}

impl<T: Real> SampleHistory<T> {
    /// An empty history.
    #[must_use]
    pub fn new() -> Self {
        Self {
            w: [Vec3::ZERO; 3],
            count: 0,
        }
    }

    /// Samples held (0 to 3).
    #[must_use]
    pub fn len(&self) -> usize {
        self.count as usize
    }

    /// `true` before the first sample.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Forgets every sample (after a gap in the data: the next sample restarts at second order).
    pub fn clear(&mut self) {
        self.count = 0;
    }

    /// The rate model of the step ending at `newest`, or `None` if there is no earlier sample yet.
    #[must_use]
    pub fn model(&self, newest: Vec3<T>) -> Option<History<T>> {
        let [a, b, c] = self.w;
        match self.count {
            0 => None,
            1 => History::new(&[c, newest]),
            2 => History::new(&[b, c, newest]),
            _ => History::new(&[a, b, c, newest]),
        }
    }

    /// Appends `newest`, dropping the oldest beyond three.
    pub fn push(&mut self, newest: Vec3<T>) {
        self.w = [self.w[1], self.w[2], newest];
        self.count = (self.count + 1).min(3);
    }
}
