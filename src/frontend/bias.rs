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

    /// The offset moved by `delta` (rad/s): an estimator's bias correction. Give the same `delta` to
    /// [`Propagator::correct_bias`](crate::Propagator::correct_bias), so the samples the input model keeps
    /// move with it.
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] if `delta` or the new offset is NaN or infinite.
    pub fn correct(self, delta: Vec3<T>) -> Result<Self, Error> {
        Self::new(self.bias + delta)
    }
}

/// Learns the gyro bias while the body is still, follows it when it changes, and subtracts it.
///
/// **Stillness.** Samples are taken in windows of `window` samples. A window is *still* when every sample
/// in it, minus the current bias estimate, stays within `gate` (rad/s) on every axis and none is saturated;
/// with [`BiasEstimator::with_accel_gate`], also every acceleration sample within that gate of the window's
/// first, on every axis. A moving or saturated sample aborts the window: nothing is learned from it (nor
/// from a window whose numbers overflow the running means, with gates too wide for the numbers given).
///
/// **Learning.** The mean of a still window measures the bias, the sensor's noise averaged over the window;
/// its standard error comes from the window's own spread. The first still window sets the estimate. A
/// later one that agrees with it refines it: a running mean over the last `memory` still windows, so noise
/// keeps averaging down and a slow drift is tracked.
///
/// **Following a change.** A still window that disagrees with the estimate, on some axis by more than
/// both the `change` threshold ([`BiasEstimator::with_change`], default [`BiasEstimator::DEFAULT_CHANGE`])
/// and five standard errors of the difference, is held as a candidate. If the next still window agrees
/// with it (by the same test), the bias has changed: the estimate restarts from the two windows' mean. So a
/// bias step at rest is followed within three windows (one that straddles the step, two that confirm it),
/// and a single odd window is never learned.
///
/// **Temperature.** With [`BiasEstimator::with_temperature_model`] and temperatures given through
/// [`BiasEstimator::update_with`], each still window also records its mean temperature, and a straight
/// line bias(T) is fitted through the learned windows (per axis, least squares, over the last `memory`
/// windows). Once their temperatures span enough, the bias subtracted at a sample is the estimate moved
/// along that line to the sample's temperature: learned at rest, applied in motion. Give a temperature with
/// every sample or with none.
///
/// **What it cannot tell apart.** A gyroscope alone cannot distinguish a bias from a real rotation at a
/// constant rate: a rotation slower than `gate` on every axis, held for two windows (and, with the
/// accelerometer, one that leaves the acceleration still: a turn about the vertical), *is* learned as bias.
/// A rotation faster than `gate` on any axis (minus the bias already learned) is never learned. Choose
/// `gate` above the sensor's bias plus its noise peaks and below the slowest real rotation you must keep
/// (Fusion's `FusionBias` uses 3 °/s; the comparison with it is docs/bias.md).
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
/// // The bias steps by 0.0078125 rad/s on z at rest: followed after two windows that agree.
/// let stepped = bias + Vec3::new(0.0, 0.0, 0.0078125);
/// for _ in 0..128 {
///     est.update(GyroSample::new(stepped))?;
/// }
/// assert_eq!(est.bias(), stepped);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BiasEstimator<T> {
    window: u32,
    gate: T,
    memory: u32,
    /// The smallest disagreement (rad/s, any axis) that can start a change; infinity: never.
    change: T,
    /// Acceleration gate (per axis, the unit of the accelerations given), if used.
    accel_gate: Option<T>,
    /// The running mean of the learned windows' bias measurements.
    bias: Vec3<T>,
    /// The running mean of their temperatures, with the same weights: where `bias` holds.
    bias_temperature: Option<T>,
    /// Sum of `ω − b` over the current window (`b`: the bias subtracted at each sample).
    sum: Vec3<T>,
    /// Sum of `(ω − b)²` over the current window.
    sum_sq: Vec3<T>,
    /// Samples in the current window.
    count: u32,
    /// Sum of the temperatures given in the current window, and how many.
    temperature_sum: T,
    temperature_count: u32,
    /// The current window's first acceleration.
    accel_reference: Option<Vec3<T>>,
    /// Still windows learned so far (saturates at `memory`).
    learned: u32,
    /// A still window that disagreed with the estimate, waiting for the next to confirm a change.
    candidate: Option<Measurement<T>>,
    /// The bias(T) line, if asked for.
    thermal: Option<Thermal<T>>,
}

/// One still window's measurement of the bias.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Measurement<T> {
    /// The window's bias (rad/s).
    bias: Vec3<T>,
    /// The variance of that mean, per axis ((rad/s)²), from the window's spread.
    variance: Vec3<T>,
    /// The window's mean temperature, if given.
    temperature: Option<T>,
}

/// A straight line bias(T) = b + slope·(T − T_b), fitted by least squares through the learned windows.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Thermal<T> {
    /// The standard deviation the windows' temperatures must reach before the slope is used.
    span: T,
    /// The first window's temperature: the sums are taken about it (fewer cancellations).
    origin: Option<T>,
    /// The windows in the sums (weights: the oldest fade once `memory` is reached).
    weight: T,
    sum_t: T,
    sum_tt: T,
    sum_b: Vec3<T>,
    sum_tb: Vec3<T>,
    /// rad/s per unit of temperature; zero until the span is reached.
    slope: Vec3<T>,
}

impl<T: Real> Thermal<T> {
    fn add(&mut self, m: &Measurement<T>, memory: u32) {
        let Some(temperature) = m.temperature else {
            return;
        };
        let origin = *self.origin.get_or_insert(temperature);
        let t = temperature - origin;
        let memory = T::from_f64(f64::from(memory));
        if self.weight >= memory {
            // An exponential memory of about `memory` windows.
            let keep = (memory - T::ONE) / memory;
            self.weight *= keep;
            self.sum_t *= keep;
            self.sum_tt *= keep;
            self.sum_b = self.sum_b * keep;
            self.sum_tb = self.sum_tb * keep;
        }
        self.weight += T::ONE;
        self.sum_t += t;
        self.sum_tt += t * t;
        self.sum_b += m.bias;
        self.sum_tb += m.bias * t;
        let inv = T::ONE / self.weight;
        let mean_t = self.sum_t * inv;
        let var_t = self.sum_tt * inv - mean_t * mean_t;
        if self.weight >= T::TWO && var_t >= self.span * self.span && var_t.is_finite() {
            let slope = (self.sum_tb * inv - self.sum_b * (inv * mean_t)) * (T::ONE / var_t);
            if slope.is_finite() {
                self.slope = slope;
            }
        }
    }
}

/// `|d| > change` or `d² > 25 v` on some axis: `d` disagrees with zero beyond the threshold and five
/// standard errors (`v`: the variance of `d`).
fn disagrees<T: Real>(d: Vec3<T>, v: Vec3<T>, change: T) -> bool {
    let k2 = T::from_i32(25);
    let axis = |d: T, v: T| d.abs() > change && d * d > k2 * v;
    axis(d.x, v.x) || axis(d.y, v.y) || axis(d.z, v.z)
}

impl<T: Real> BiasEstimator<T> {
    /// The default `change` threshold: 5·10⁻⁴ rad/s (0.029 °/s), far above the noise of a one-second mean
    /// of a MEMS gyro and below the bias steps a temperature change or a shock causes.
    pub const DEFAULT_CHANGE: f64 = 5.0e-4;

    /// Windows of `window_seconds` (s; e.g. 1 s) of samples taken every `sample_period` (s), stillness gate
    /// `gate` (rad/s), a running mean over the last 64 still windows, changes followed from
    /// [`BiasEstimator::DEFAULT_CHANGE`]. The window holds `round(window_seconds / sample_period)` samples:
    /// change the rate and the window stays as long.
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] for a duration or period that is not finite and positive, a window of
    /// less than one or more than 2³¹ − 1 samples, or a `gate` that is not finite and positive.
    pub fn new(window_seconds: f64, sample_period: f64, gate: T) -> Result<Self, Error> {
        Self::with_memory(window_seconds, sample_period, gate, 64)
    }

    /// As [`BiasEstimator::new`], with the running mean over the last `memory` still windows
    /// (`1 ≤ memory ≤ 2³¹ − 1`; 1 keeps only the latest window).
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] as for [`BiasEstimator::new`], and for `memory` outside that range.
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
    /// [`Error::InvalidEstimator`] for a window or `memory` outside `1 ≤ n ≤ 2³¹ − 1`, or a `gate` that is
    /// not finite and positive.
    pub fn from_samples(window: u32, gate: T, memory: u32) -> Result<Self, Error> {
        let counted = |n: u32| n >= 1 && n <= i32::MAX as u32;
        if !(counted(window) && counted(memory) && gate > T::ZERO && gate <= T::MAX) {
            return Err(Error::InvalidEstimator);
        }
        Ok(Self {
            window,
            gate,
            memory,
            change: T::from_f64(Self::DEFAULT_CHANGE),
            accel_gate: None,
            bias: Vec3::ZERO,
            bias_temperature: None,
            sum: Vec3::ZERO,
            sum_sq: Vec3::ZERO,
            count: 0,
            temperature_sum: T::ZERO,
            temperature_count: 0,
            accel_reference: None,
            learned: 0,
            candidate: None,
            thermal: None,
        })
    }

    /// Sets the smallest disagreement (rad/s, on any axis) between a still window and the estimate that can
    /// start a change (it must also exceed five standard errors). Infinity never starts one: the estimate
    /// is then only the running mean, which takes about `memory` windows to follow a step.
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] if `change` is not positive (NaN included).
    pub fn with_change(mut self, change: T) -> Result<Self, Error> {
        if !(change > T::ZERO) {
            return Err(Error::InvalidEstimator);
        }
        self.change = change;
        Ok(self)
    }

    /// Also requires, for a still window, every acceleration given through [`BiasEstimator::update_with`]
    /// within `gate` of the window's first, on every axis (the accelerations' unit; e.g. 0.5 m/s²). A
    /// sample given without an acceleration is judged by its rate alone.
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] if `gate` is not finite and positive.
    pub fn with_accel_gate(mut self, gate: T) -> Result<Self, Error> {
        if !(gate > T::ZERO && gate <= T::MAX) {
            return Err(Error::InvalidEstimator);
        }
        self.accel_gate = Some(gate);
        Ok(self)
    }

    /// Fits bias(T), a straight line per axis, through the still windows' biases and mean temperatures
    /// (given through [`BiasEstimator::update_with`]), and applies it once the windows' temperatures have a
    /// standard deviation of at least `span` (their unit; e.g. 0.5 °C).
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] if `span` is not finite and positive.
    pub fn with_temperature_model(mut self, span: T) -> Result<Self, Error> {
        if !(span > T::ZERO && span <= T::MAX) {
            return Err(Error::InvalidEstimator);
        }
        self.thermal = Some(Thermal {
            span,
            origin: None,
            weight: T::ZERO,
            sum_t: T::ZERO,
            sum_tt: T::ZERO,
            sum_b: Vec3::ZERO,
            sum_tb: Vec3::ZERO,
            slope: Vec3::ZERO,
        });
        Ok(self)
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
        self.bias_temperature = None;
        self.learned = 1;
        self.candidate = None;
        self.restart_window();
        Ok(self)
    }

    /// Moves the estimate by `delta` (rad/s): an estimator's bias correction (a filter that also observes
    /// the bias in motion). The learned windows' measurements move with it: the running mean, a change
    /// waiting to be confirmed, and the bias(T) line's intercept (its slope stays); the window being
    /// summed restarts (its samples were corrected with the old estimate). Give the same `delta` to
    /// [`Propagator::correct_bias`](crate::Propagator::correct_bias), so the samples the input model keeps
    /// move with it.
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] if `delta` is NaN or infinite or the moved estimate overflows; the
    /// estimator is then unchanged.
    pub fn correct_bias(&mut self, delta: Vec3<T>) -> Result<(), Error> {
        if !delta.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        let mut next = *self;
        next.bias += delta;
        if let Some(c) = &mut next.candidate {
            c.bias += delta;
        }
        if let Some(th) = &mut next.thermal {
            th.sum_b += delta * th.weight;
            th.sum_tb += delta * th.sum_t;
        }
        next.restart_window();
        if !next.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        *self = next;
        Ok(())
    }

    /// The current bias estimate (rad/s; zero before the first still window): the running mean of the
    /// learned windows, at their mean temperature.
    #[must_use]
    pub fn bias(&self) -> Vec3<T> {
        self.bias
    }

    /// The bias subtracted at `temperature`: [`BiasEstimator::bias`] moved along the fitted bias(T) line
    /// (the estimate itself while there is no line, or no temperature was learned with it).
    #[must_use]
    pub fn bias_at(&self, temperature: T) -> Vec3<T> {
        match (self.thermal, self.bias_temperature) {
            (Some(th), Some(tb)) => self.bias + th.slope * (temperature - tb),
            _ => self.bias,
        }
    }

    /// The fitted slope of bias(T) (rad/s per unit of temperature), once the temperatures span enough.
    #[must_use]
    pub fn temperature_slope(&self) -> Option<Vec3<T>> {
        let th = self.thermal?;
        let spans = th.weight >= T::TWO && th.slope != Vec3::ZERO;
        spans.then_some(th.slope)
    }

    /// `true` once at least one still window has been learned.
    #[must_use]
    pub fn is_learned(&self) -> bool {
        self.learned > 0
    }

    /// [`BiasEstimator::update_with`] without an acceleration or a temperature.
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] for a NaN or infinite rate; the estimator is then unchanged.
    #[inline]
    pub fn update(&mut self, s: GyroSample<T>) -> Result<GyroSample<T>, Error> {
        self.update_with(s, Aux::NONE)
    }

    /// Takes a sample with what the IMU gave beside it, learns from it if the body is still, and returns it
    /// minus the bias (the estimate from before this sample, at the sample's temperature; the saturation
    /// flag kept): [`BiasEstimator::correct`], then [`BiasEstimator::learn`].
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] for a NaN or infinite rate, [`Error::NonFiniteAux`] for a NaN or infinite
    /// acceleration or temperature (or one so far along the fitted line that the bias there overflows); the
    /// estimator is then unchanged.
    #[inline]
    pub fn update_with(&mut self, s: GyroSample<T>, aux: Aux<T>) -> Result<GyroSample<T>, Error> {
        let out = self.correct(s, aux)?;
        self.learn(out, aux);
        Ok(out)
    }

    /// The sample minus the bias (at its temperature), without learning from it: the first half of
    /// [`BiasEstimator::update_with`], for a caller that learns only from the samples it keeps (the C API
    /// learns once the propagator has accepted the sample, so a refused one leaves the estimator as it was
    /// without a copy of it).
    ///
    /// # Errors
    /// As [`BiasEstimator::update_with`].
    #[inline]
    pub fn correct(&self, s: GyroSample<T>, aux: Aux<T>) -> Result<GyroSample<T>, Error> {
        if !s.rate.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        if !aux.is_finite() {
            return Err(Error::NonFiniteAux);
        }
        let used = match aux.temperature {
            Some(t) => {
                let used = self.bias_at(t);
                if !used.is_finite() {
                    // A temperature so far off the fitted line that the bias there overflows.
                    return Err(Error::NonFiniteAux);
                }
                used
            }
            None => self.bias,
        };
        Ok(GyroSample {
            rate: s.rate - used,
            saturated: s.saturated,
        })
    }

    /// Learns from `corrected`, what [`BiasEstimator::correct`] returned for a sample with `aux`, if the
    /// body is still: the second half of [`BiasEstimator::update_with`]. Give it exactly that, before
    /// anything else changes the estimator (a non-finite `aux` is ignored; a non-finite rate, the
    /// difference of a huge sample and a huge bias, is motion: it ends the window, as in `update_with`).
    #[inline]
    pub fn learn(&mut self, corrected: GyroSample<T>, aux: Aux<T>) {
        let d = corrected.rate;
        if !aux.is_finite() {
            return;
        }
        let g = self.gate;
        // A NaN or infinite component fails the gate: not still.
        let mut still = !corrected.saturated && d.x.abs() <= g && d.y.abs() <= g && d.z.abs() <= g;
        if let (Some(ga), Some(a)) = (self.accel_gate, aux.accel) {
            match self.accel_reference {
                Some(r) if self.count > 0 => {
                    let e = a - r;
                    still &= e.x.abs() <= ga && e.y.abs() <= ga && e.z.abs() <= ga;
                }
                _ => self.accel_reference = Some(a),
            }
        }
        if !still {
            if self.count > 0 {
                // (An empty window has nothing to forget: in motion this is the common path.)
                self.restart_window();
            }
            return;
        }
        self.sum += d;
        self.sum_sq += Vec3::new(d.x * d.x, d.y * d.y, d.z * d.z);
        self.count += 1;
        if let Some(t) = aux.temperature {
            self.temperature_sum += t;
            self.temperature_count += 1;
        }
        if self.count >= self.window {
            self.close_window();
        }
    }

    /// A full still window learned, and the next one started. Out of line: once per window, not per sample.
    #[inline(never)]
    fn close_window(&mut self) {
        let before = *self;
        self.learn_window();
        if !self.is_finite() {
            // Numbers so large that the running means overflowed: nothing learned from this window.
            *self = before;
        }
        self.restart_window();
    }

    #[inline]
    fn restart_window(&mut self) {
        self.sum = Vec3::ZERO;
        self.sum_sq = Vec3::ZERO;
        self.count = 0;
        self.temperature_sum = T::ZERO;
        self.temperature_count = 0;
        self.accel_reference = None;
    }

    /// Every learned quantity finite (the window sums are reset after each window).
    fn is_finite(&self) -> bool {
        let finite = |t: Option<T>| t.is_none_or(Real::is_finite);
        let candidate = self
            .candidate
            .is_none_or(|c| c.bias.is_finite() && c.variance.is_finite() && finite(c.temperature));
        let thermal = self.thermal.is_none_or(|th| {
            th.weight.is_finite()
                && th.sum_t.is_finite()
                && th.sum_tt.is_finite()
                && th.sum_b.is_finite()
                && th.sum_tb.is_finite()
                && th.slope.is_finite()
                && finite(th.origin)
        });
        self.bias.is_finite() && finite(self.bias_temperature) && candidate && thermal
    }

    /// A full still window: learned, held as a candidate change, or a change confirmed.
    fn learn_window(&mut self) {
        let n = T::from_f64(f64::from(self.window));
        let inv_n = T::ONE / n;
        let mean = self.sum * inv_n;
        // The variance of the window's mean, per axis: the sample variance over n (none for one sample).
        let variance = if self.window >= 2 {
            let scale = T::ONE / (n * (n - T::ONE));
            let axis = |s: T, q: T| (q - s * s * inv_n).max(T::ZERO) * scale;
            Vec3::new(
                axis(self.sum.x, self.sum_sq.x),
                axis(self.sum.y, self.sum_sq.y),
                axis(self.sum.z, self.sum_sq.z),
            )
        } else {
            Vec3::ZERO
        };
        let temperature = (self.temperature_count > 0).then(|| {
            self.temperature_sum * (T::ONE / T::from_f64(f64::from(self.temperature_count)))
        });
        // The model this window was corrected with, at the window's temperature.
        let at = |est: &Self, t: Option<T>| t.map_or(est.bias, |t| est.bias_at(t));
        let m = Measurement {
            bias: at(self, temperature) + mean,
            variance,
            temperature,
        };
        if !(m.bias.is_finite() && m.temperature.is_none_or(Real::is_finite)) {
            return; // temperatures whose sum overflowed: nothing learned from this window
        }
        if self.learned == 0 {
            self.adopt(&m, None);
            return;
        }
        let learned = T::from_f64(f64::from(self.learned));
        let disagreement = variance + variance * (T::ONE / learned);
        if !disagrees(mean, disagreement, self.change) {
            self.candidate = None;
            self.learned = (self.learned + 1).min(self.memory);
            let l = T::from_f64(f64::from(self.learned));
            match temperature {
                Some(t) if self.thermal.is_some() => {
                    let tb = self.bias_temperature.unwrap_or(t);
                    let inv_l = T::ONE / l;
                    self.bias += (m.bias - self.bias) * inv_l;
                    self.bias_temperature = Some(tb + (t - tb) * inv_l);
                }
                // The running mean's update, `sum / (n·learned)`.
                _ => self.bias += self.sum * (T::ONE / (n * l)),
            }
            self.record(&m);
            return;
        }
        match self.candidate {
            Some(c)
                if !disagrees(
                    m.bias - self.shifted(&c, temperature),
                    c.variance + variance,
                    self.change,
                ) =>
            {
                self.adopt(&m, Some(c));
            }
            _ => self.candidate = Some(m),
        }
    }

    /// `c`'s bias moved along the bias(T) line to `temperature`.
    fn shifted(&self, c: &Measurement<T>, temperature: Option<T>) -> Vec3<T> {
        match (self.thermal, c.temperature, temperature) {
            (Some(th), Some(tc), Some(t)) => c.bias + th.slope * (t - tc),
            _ => c.bias,
        }
    }

    /// Restarts the estimate from `m` (and a confirmed candidate `c`: the mean of the two).
    fn adopt(&mut self, m: &Measurement<T>, c: Option<Measurement<T>>) {
        self.candidate = None;
        match c {
            Some(c) if self.memory >= 2 => {
                self.bias = (c.bias + m.bias) * T::HALF;
                self.bias_temperature = match (c.temperature, m.temperature) {
                    (Some(a), Some(b)) => Some((a + b) * T::HALF),
                    (a, b) => b.or(a),
                };
                self.learned = 2;
                self.record(&c);
            }
            _ => {
                self.bias = m.bias;
                self.bias_temperature = m.temperature;
                self.learned = 1;
            }
        }
        self.record(m);
    }

    fn record(&mut self, m: &Measurement<T>) {
        if let Some(th) = self.thermal.as_mut() {
            th.add(m, self.memory);
        }
    }
}

/// What an IMU delivers beside the rate, for the [`BiasEstimator`]: the acceleration, which tells rest
/// from motion, and the sensor's temperature, on which the bias depends. Either may be absent.
///
/// The acceleration may be in any unit (m/s², g, counts) as long as [`BiasEstimator::with_accel_gate`]'s
/// gate is in the same; the temperature in any scale (°C, counts) as long as
/// [`BiasEstimator::with_temperature_model`]'s span is in the same. Neither ever changes the attitude: the
/// estimator only uses them to decide when to learn and what bias to subtract.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Aux<T> {
    /// The accelerometer's reading at the sample, sensor or body axes (any fixed axes).
    pub accel: Option<Vec3<T>>,
    /// The sensor's temperature at the sample.
    pub temperature: Option<T>,
}

impl<T: Real> Aux<T> {
    /// Nothing beside the rate.
    pub const NONE: Self = Self {
        accel: None,
        temperature: None,
    };

    #[inline]
    fn is_finite(&self) -> bool {
        self.accel.is_none_or(Vec3::is_finite) && self.temperature.is_none_or(Real::is_finite)
    }
}
