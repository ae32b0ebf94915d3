//! Gyro bias: a fixed offset, or an estimator that learns it while the body is still.

use crate::{Error, GyroSample, Real, Vec3};

/// A fixed bias (rad/s, body or sensor axes: wherever it is applied), subtracted from every sample.
///
/// ```
/// use quatprop::frontend::FixedBias;
/// use quatprop::{GyroSample, Vec3};
/// let b = FixedBias::new(Vec3::new(0.01_f32, 0.0, -0.02))?;
/// assert_eq!(b.apply(GyroSample::new(Vec3::new(0.01, 1.0, 0.0))).rate, Vec3::new(0.0, 1.0, 0.02));
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FixedBias<T> {
    bias: Vec3<T>,
}

impl<T: Real> FixedBias<T> {
    /// The offset `bias` (rad/s).
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] if a component is NaN or infinite.
    pub fn new(bias: Vec3<T>) -> Result<Self, Error> {
        if bias.is_finite() {
            Ok(Self { bias })
        } else {
            Err(Error::NonFiniteRate)
        }
    }

    /// The sample minus the bias (the saturation flag kept).
    #[inline]
    #[must_use]
    pub fn apply(&self, s: GyroSample<T>) -> GyroSample<T> {
        GyroSample {
            rate: s.rate - self.bias,
            saturated: s.saturated,
        }
    }
    /// The offset (rad/s).
    #[must_use]
    pub fn bias(&self) -> Vec3<T> {
        self.bias
    }
}

/// Learns the gyro bias while the body is still, and subtracts it.
///
/// **Stillness.** Samples are taken in windows of `window` samples. A window is *still* when every sample
/// in it, minus the current bias estimate, stays within `gate` (rad/s) on every axis and none is saturated.
/// **Learning.** The mean of a still window is a measurement of the bias with the sensor's noise averaged
/// over the window. The first still window sets the estimate; later ones refine it by a running mean over
/// the last `memory` still windows (so noise keeps averaging down, and a slow thermal drift is tracked).
/// A moving or saturated sample aborts the window: nothing is learned from it.
///
/// **What it cannot tell apart.** A gyroscope alone cannot distinguish a bias from a real rotation at a
/// constant rate: a rotation slower than `gate` on every axis, held for a whole window, *is* learned as bias.
/// A rotation faster than `gate` on any axis (minus the bias already learned) is never learned. Choose
/// `gate` above the sensor's bias plus its noise peaks and below the slowest real rotation you must keep
/// (Fusion's `FusionOffset` uses 3 °/s; the comparison with it is the bias section of docs/report/README.md).
///
/// ```
/// use quatprop::frontend::BiasEstimator;
/// use quatprop::{GyroSample, Vec3};
/// // Windows of 64 ms at 1 kHz (64 samples), gate 0.05 rad/s.
/// let mut est = BiasEstimator::new(0.064, 1.0e-3, 0.05_f64)?;
/// let bias = Vec3::new(0.0078125, -0.015625, 0.00390625); // binary fractions: sums are exact
/// for _ in 0..64 {
///     est.update(GyroSample::new(bias))?;
/// }
/// assert_eq!(est.bias(), bias); // learned after one still window
/// assert_eq!(est.update(GyroSample::new(bias))?.rate, Vec3::new(0.0, 0.0, 0.0));
/// // A turn at 0.06 rad/s is faster than the gate: never learned.
/// for _ in 0..1000 {
///     est.update(GyroSample::new(bias + Vec3::new(0.06, 0.0, 0.0)))?;
/// }
/// assert_eq!(est.bias(), bias);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BiasEstimator<T> {
    window: u32,
    gate: T,
    memory: u32,
    bias: Vec3<T>,
    /// Sum of `ω − bias` over the current window.
    sum: Vec3<T>,
    /// Samples in the current window.
    count: u32,
    /// Still windows learned so far (saturates at `memory`).
    learned: u32,
}

impl<T: Real> BiasEstimator<T> {
    /// Windows of `window_seconds` (s; e.g. 1 s) of samples taken every `sample_period` (s), stillness gate
    /// `gate` (rad/s), a running mean over the last 64 still windows. The window holds
    /// `round(window_seconds / sample_period)` samples: change the rate and the window stays as long.
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] for a duration or period that is not finite and positive, a window of
    /// less than one or more than 2³¹ − 1 samples, or a `gate` that is not finite and positive.
    pub fn new(window_seconds: f64, sample_period: f64, gate: T) -> Result<Self, Error> {
        Self::with_memory(window_seconds, sample_period, gate, 64)
    }

    /// As [`BiasEstimator::new`], with the running mean over the last `memory` still windows
    /// (`memory ≥ 1`; 1 keeps only the latest window).
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] as for [`BiasEstimator::new`], and for `memory` 0.
    pub fn with_memory(
        window_seconds: f64,
        sample_period: f64,
        gate: T,
        memory: u32,
    ) -> Result<Self, Error> {
        let positive = |x: f64| x > 0.0 && x <= f64::MAX;
        if !(positive(window_seconds) && positive(sample_period)) {
            return Err(Error::InvalidEstimator);
        }
        let samples = libm::round(window_seconds / sample_period);
        if !(samples >= 1.0 && samples <= f64::from(i32::MAX)) {
            return Err(Error::InvalidEstimator);
        }
        Self::from_samples(samples as u32, gate, memory)
    }

    /// As [`BiasEstimator::with_memory`], the window given as a number of samples (`1 ≤ window ≤ 2³¹ − 1`).
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] for a window outside that range, `memory` 0, or a `gate` that is not
    /// finite and positive.
    pub fn from_samples(window: u32, gate: T, memory: u32) -> Result<Self, Error> {
        if window == 0
            || window > i32::MAX as u32
            || memory == 0
            || !(gate > T::ZERO && gate <= T::MAX)
        {
            return Err(Error::InvalidEstimator);
        }
        Ok(Self {
            window,
            gate,
            memory,
            bias: Vec3::ZERO,
            sum: Vec3::ZERO,
            count: 0,
            learned: 0,
        })
    }

    /// Starts from a known bias (e.g. stored at the last shutdown), counted as one learned window.
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] if a component is NaN or infinite.
    pub fn with_initial(mut self, bias: Vec3<T>) -> Result<Self, Error> {
        if !bias.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        self.bias = bias;
        self.learned = 1;
        self.sum = Vec3::ZERO;
        self.count = 0;
        Ok(self)
    }

    /// The current bias estimate (rad/s; zero before the first still window).
    #[must_use]
    pub fn bias(&self) -> Vec3<T> {
        self.bias
    }

    /// `true` once at least one still window has been learned.
    #[must_use]
    pub fn is_learned(&self) -> bool {
        self.learned > 0
    }

    /// Takes a sample, learns from it if the body is still, and returns it minus the bias estimate (the
    /// estimate from before this sample; the saturation flag kept).
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] for a NaN or infinite rate; the estimator is then unchanged.
    pub fn update(&mut self, s: GyroSample<T>) -> Result<GyroSample<T>, Error> {
        if !s.rate.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        let d = s.rate - self.bias;
        let out = GyroSample {
            rate: d,
            saturated: s.saturated,
        };
        let g = self.gate;
        let still = !s.saturated && d.x.abs() <= g && d.y.abs() <= g && d.z.abs() <= g;
        if !still {
            self.sum = Vec3::ZERO;
            self.count = 0;
            return Ok(out);
        }
        self.sum += d;
        self.count += 1;
        if self.count >= self.window {
            // The window mean of ω − b is this window's correction to b; a running mean over `memory`.
            self.learned = (self.learned + 1).min(self.memory);
            let n = T::from_i32(self.window as i32) * T::from_i32(self.learned as i32);
            self.bias += self.sum * (T::ONE / n);
            self.sum = Vec3::ZERO;
            self.count = 0;
        }
        Ok(out)
    }
}
