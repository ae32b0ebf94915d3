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

    /// Moves the offset by `delta` (rad/s): an estimator's bias correction (`b̂ ← b̂ + δb`), in place as
    /// [`BiasEstimator::correct_bias`] and [`Propagator::correct_bias`](crate::Propagator::correct_bias)
    /// do. Give the same `delta` to [`Propagator::correct_bias`](crate::Propagator::correct_bias), so the
    /// samples the input model keeps move with it.
    ///
    /// ```
    /// use quatprop::frontend::FixedBias;
    /// use quatprop::{Error, Vec3};
    /// let mut b = FixedBias::new(Vec3::new(0.01_f32, 0.0, 0.0))?;
    /// b.correct_bias(Vec3::new(0.002, 0.0, -0.001))?;
    /// let moved = Vec3::new(0.01 + 0.002, 0.0, -0.001);
    /// assert_eq!(b.bias(), moved);
    /// assert_eq!(b.correct_bias(Vec3::new(f32::NAN, 0.0, 0.0)), Err(Error::NonFiniteRate));
    /// assert_eq!(b.bias(), moved); // unchanged
    /// # Ok::<(), Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] if `delta` or the new offset is NaN or infinite; the offset is then
    /// unchanged.
    pub fn correct_bias(&mut self, delta: Vec3<T>) -> Result<(), Error> {
        *self = Self::new(self.bias + delta)?;
        Ok(())
    }
}

/// Learns the gyro bias while the body is still, follows it as it drifts and when it steps at rest, and
/// subtracts it — without taking a slow turn or the end of a motion for a bias.
///
/// **Windows and blocks.** Samples are taken in windows of `window` samples, each cut into
/// [`BiasEstimator::BLOCKS`] blocks. A window is a candidate for rest when every sample in it, minus the
/// current estimate, stays within `gate` (rad/s) on every axis and none is saturated (and, with
/// [`BiasEstimator::with_accel_gate`], every acceleration within that gate of the window's first); a
/// sample that fails aborts the window.
///
/// **Flat.** A window is *still* only if it is also flat: its block means scatter no more than the
/// sensor's block means scatter at rest (a χ² test per axis, `p = 10⁻⁴`), and, when accelerations are
/// given, so do theirs. The scatter at rest is learned from the still windows themselves (a pooled
/// variance, started by the first window), or given by the sensor's noise
/// ([`BiasEstimator::with_noise`]: `N²/τ_block`). A turn's onset, a ramp, a slow turn about a horizontal
/// axis (the acceleration's direction moves) is not flat: nothing is learned from it.
///
/// **Drift.** The estimate is a Kalman filter on a bias that walks with density `drift` (rad/s/√s,
/// [`BiasEstimator::with_drift`]; default [`BiasEstimator::DEFAULT_DRIFT`]): each still window's mean
/// is a measurement of it, with the variance of a mean of its blocks. A still window that disagrees with
/// the estimate by more than five standard deviations of the difference (the estimate's uncertainty
/// grown by `drift²` per second since it was last updated, plus the window's) is not a measurement: a
/// slow turn or a bias changed in motion. **`drift` is the one knob between following a changing bias and
/// keeping a slow turn:** after `t` seconds without a still window that agrees, a still window that is
/// `5·drift·√t` off is believed. A slow turn faster than that is kept; a bias that changed faster than
/// that in motion stays stale until it does (a stale bias is the smaller harm).
///
/// **Steps at rest.** A bias that steps while the body is still (a shock, a glitch) is followed within
/// two windows: the window that holds the step is not flat, but is two flat levels with one block
/// between (the first at the estimate: the body was still before), and the next still window that agrees
/// with the new level confirms it; a step at a window's boundary is confirmed by the two still windows
/// after it, the window before having agreed with the estimate. A ramp is not a step, and every link of
/// the chain must follow the last without a sample in motion: the end of a motion is never taken for a
/// step.
///
/// **Temperature.** With [`BiasEstimator::with_temperature_model`] and temperatures given through
/// [`BiasEstimator::update_with`], each still window also records its mean temperature, and a straight
/// line bias(T) is fitted through the learned windows (per axis, least squares, over an exponential
/// memory of 64 windows). Once their temperatures span enough, the bias subtracted at a sample is the
/// estimate moved along that line to the sample's temperature: learned at rest, applied in motion. Give
/// a temperature with every sample or with none.
///
/// **What it cannot tell apart.** A gyroscope alone cannot tell a bias from a rotation at a constant
/// rate. A turn that starts as abruptly as a step (within one block) from a still body, and about the
/// vertical (the acceleration, if given, does not move), is taken for a step; a turn that starts slower,
/// or from motion, is kept until `drift` says the bias could have moved as far.
///
/// ```
/// use quatprop::frontend::BiasEstimator;
/// use quatprop::{GyroSample, Vec3};
/// // Windows of 64 ms at 1 kHz (64 samples, blocks of 8), gate 0.05 rad/s.
/// let mut est = BiasEstimator::new(0.064, 1.0e-3, 0.05_f64)?;
/// let bias = Vec3::new(0.0078125, -0.015625, 0.00390625);
/// let noise = |k: u32| if k % 2 == 0 { 1e-4 } else { -1e-4 }; // a still sensor's noise
/// for k in 0..64 {
///     est.update(GyroSample::new(bias + Vec3::new(noise(k), 0.0, 0.0)))?;
/// }
/// assert_eq!(est.bias(), bias); // learned from one still window
/// // A turn at 0.06 rad/s is faster than the gate: never learned.
/// for k in 0..1000 {
///     est.update(GyroSample::new(bias + Vec3::new(0.06 + noise(k), 0.0, 0.0)))?;
/// }
/// assert_eq!(est.bias(), bias);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BiasEstimator<T> {
    /// Samples per window and per block (`window = BLOCKS · block` when the window holds 8 or more).
    window: u32,
    block: u32,
    /// The sample period (s).
    period: T,
    gate: T,
    /// The bias's random walk density (rad/s/√s) while it is not seen: the knob.
    drift: T,
    /// Its density between still windows that agree (rad/s/√s): the sensor's wander at rest.
    rest_drift: T,
    /// Acceleration gate (per axis, the unit of the accelerations given), if used.
    accel_gate: Option<T>,
    /// The estimate and its variance per axis ((rad/s)²), as of the last update.
    bias: Vec3<T>,
    variance: Vec3<T>,
    /// Samples since the variance last grew by the drift.
    since: u32,
    /// The mean temperature of the learned windows, with the estimate's weights: where `bias` holds.
    bias_temperature: Option<T>,
    /// The variance of a block's mean at rest, per axis (gyro, then acceleration), and the degrees of
    /// freedom it was pooled over (zero: not known yet; infinite: given by the noise model).
    rest_scatter: Vec3<T>,
    rest_dof: T,
    accel_scatter: Vec3<T>,
    accel_dof: T,
    /// The current window: the sum of `ω − b` in the current block, the means of the finished blocks,
    /// the samples so far.
    block_sum: Vec3<T>,
    in_block: u32,
    blocks: [Vec3<T>; BLOCKS],
    count: u32,
    /// The accelerations in the current window: the current block's sum, the sum and the sum of squares
    /// of the finished blocks' means, how many samples had one, and the window's first (for the gate).
    accel_block_sum: Vec3<T>,
    accel_means: Vec3<T>,
    accel_means_sq: Vec3<T>,
    accel_count: u32,
    accel_reference: Option<Vec3<T>>,
    /// Sum of the temperatures given in the current window, and how many.
    temperature_sum: T,
    temperature_count: u32,
    /// Still windows learned so far (saturating).
    learned: u32,
    /// The last of them, as a measurement of the bias.
    taken: Option<Measurement<T>>,
    /// What the last window showed, for the steps at rest.
    last: Last<T>,
    /// The bias(T) line, if asked for.
    thermal: Option<Thermal<T>>,
}

/// Blocks per window.
const BLOCKS: usize = 8;

/// What the window before showed: the links of a step at rest.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
enum Last<T> {
    /// Motion, a window that was not flat, or a chain broken: no step can start here.
    Moving,
    /// A still window that agreed with the estimate (or updated it).
    AtEstimate,
    /// A window that held a step from the estimate, and the new level if two blocks or more showed it.
    Step(Option<Measurement<T>>),
    /// A still window that disagreed with the estimate right after one that agreed (or after a step):
    /// the new level, waiting for the next still window to confirm it.
    Candidate(Measurement<T>),
}

/// One still window's (or level's) measurement of the bias.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Measurement<T> {
    /// The bias (rad/s).
    bias: Vec3<T>,
    /// The variance of that mean, per axis ((rad/s)²).
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
    fn add(&mut self, m: &Measurement<T>) {
        let Some(temperature) = m.temperature else {
            return;
        };
        let origin = *self.origin.get_or_insert(temperature);
        let t = temperature - origin;
        let memory = T::from_f64(MEMORY);
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

/// `f` on each axis.
#[inline]
fn map<T: Real>(a: Vec3<T>, f: impl Fn(T) -> T) -> Vec3<T> {
    Vec3::new(f(a.x), f(a.y), f(a.z))
}

/// `f` on each axis of two vectors.
#[inline]
fn zip<T: Real>(a: Vec3<T>, b: Vec3<T>, f: impl Fn(T, T) -> T) -> Vec3<T> {
    Vec3::new(f(a.x, b.x), f(a.y, b.y), f(a.z, b.z))
}

/// `a / (a + b)` per axis: `a`'s share of two variances (a Kalman gain, the weight of the other
/// estimate), ½ where both are zero.
fn share<T: Real>(a: Vec3<T>, b: Vec3<T>) -> Vec3<T> {
    zip(a, b, |a, b| {
        let s = a + b;
        if s > T::ZERO {
            a / s
        } else {
            T::HALF
        }
    })
}

/// `d² > 25 v` on some axis: `d` disagrees with zero beyond five standard deviations (`v`: its variance).
fn disagrees<T: Real>(d: Vec3<T>, v: Vec3<T>) -> bool {
    let k2 = T::from_i32(25);
    d.x * d.x > k2 * v.x || d.y * d.y > k2 * v.y || d.z * d.z > k2 * v.z
}

/// The χ² bound a block scatter (7 degrees of freedom) or a step's residual (5 or 6) must stay under, per
/// axis: the 1 − 10⁻⁴ quantiles.
const FLAT_CHI2: f64 = 29.88;
/// The bound on a block scatter's ratio to a scatter at rest that was itself learned from `k` windows
/// (`7k` degrees of freedom): the 1 − 10⁻⁴ quantile of F(7, 7k), k = 1 … 64 (scipy.stats.f.ppf). A scatter
/// learned from one window may be a fifth of the truth; tested against χ²'s bound alone, the next windows
/// would fail and never teach it better.
const FLAT_F: [f64; 64] = [
    30.477, 10.924, 7.901, 6.745, 6.143, 5.774, 5.526, 5.348, 5.214, 5.110, 5.026, 4.957, 4.900,
    4.851, 4.810, 4.774, 4.742, 4.714, 4.690, 4.667, 4.647, 4.629, 4.613, 4.598, 4.584, 4.572,
    4.560, 4.549, 4.539, 4.530, 4.521, 4.513, 4.505, 4.498, 4.491, 4.485, 4.479, 4.473, 4.468,
    4.463, 4.458, 4.453, 4.449, 4.445, 4.441, 4.437, 4.433, 4.430, 4.426, 4.423, 4.420, 4.417,
    4.414, 4.411, 4.409, 4.406, 4.404, 4.401, 4.399, 4.397, 4.395, 4.393, 4.391, 4.389,
];
const STEP_CHI2: [f64; 2] = [25.74, 27.86];
/// The exponential memory (windows) of the pooled scatter at rest and of the bias(T) line.
const MEMORY: f64 = 64.0;

impl<T: Real> BiasEstimator<T> {
    /// Blocks per window: the flatness test and the step's shape look at their means.
    pub const BLOCKS: usize = BLOCKS;

    /// The default `drift`: 2·10⁻⁵ rad/s/√s (0.0011 °/s/√s: a still window 5·drift·√t off the estimate
    /// is believed after `t` seconds without one that agrees, 0.044 °/s after a minute, 0.34 °/s after an
    /// hour, so a slow turn of 0.5 °/s is kept for about two hours), chosen by the bias scenario mix and
    /// held out on BROAD (docs/bias.md, docs/heldout.md).
    pub const DEFAULT_DRIFT: f64 = 2.0e-5;

    /// The default `rest_drift` (rad/s/√s): how fast the bias wanders while the body stays still.
    pub const DEFAULT_REST_DRIFT: f64 = 2.0e-5;

    /// Windows of `window_seconds` (s; e.g. 1 s) of samples taken every `sample_period` (s), stillness gate
    /// `gate` (rad/s), drift [`BiasEstimator::DEFAULT_DRIFT`]. The window holds `round(window_seconds /
    /// sample_period)` samples: change the rate and the window stays as long.
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] for a duration or period that is not finite and positive, a window of
    /// less than one or more than 2³¹ − 1 samples, or a `gate` that is not finite and positive.
    pub fn new(window_seconds: f64, sample_period: f64, gate: T) -> Result<Self, Error> {
        let positive = |x: f64| x > 0.0 && x <= f64::MAX;
        if !(positive(window_seconds) && positive(sample_period)) {
            return Err(Error::InvalidEstimator);
        }
        let samples = libm::round(window_seconds / sample_period);
        if !(samples >= 1.0 && samples <= f64::from(i32::MAX)) {
            return Err(Error::InvalidEstimator);
        }
        Self::from_samples(samples as u32, sample_period, gate)
    }

    /// As [`BiasEstimator::new`], the window given as a number of samples (`1 ≤ window ≤ 2³¹ − 1`). A
    /// window of fewer than 16 samples has one sample per block… or fewer: below 8 samples the flatness
    /// and step tests are off (every window that passes the gate is still).
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] for a window outside `1 ≤ n ≤ 2³¹ − 1`, a `sample_period` that is not
    /// finite and positive, or a `gate` that is not finite and positive.
    pub fn from_samples(window: u32, sample_period: f64, gate: T) -> Result<Self, Error> {
        let period = T::from_f64(sample_period);
        if !(window >= 1
            && window <= i32::MAX as u32
            && gate > T::ZERO
            && gate <= T::MAX
            && period > T::ZERO
            && period <= T::MAX)
        {
            return Err(Error::InvalidEstimator);
        }
        let block = if window as usize >= BLOCKS {
            window / BLOCKS as u32
        } else {
            window
        };
        Ok(Self {
            window,
            block,
            period,
            gate,
            drift: T::from_f64(Self::DEFAULT_DRIFT),
            rest_drift: T::from_f64(Self::DEFAULT_REST_DRIFT),
            accel_gate: None,
            bias: Vec3::ZERO,
            variance: Vec3::ZERO,
            since: 0,
            bias_temperature: None,
            rest_scatter: Vec3::ZERO,
            rest_dof: T::ZERO,
            accel_scatter: Vec3::ZERO,
            accel_dof: T::ZERO,
            block_sum: Vec3::ZERO,
            in_block: 0,
            blocks: [Vec3::ZERO; BLOCKS],
            count: 0,
            accel_block_sum: Vec3::ZERO,
            accel_means: Vec3::ZERO,
            accel_means_sq: Vec3::ZERO,
            accel_count: 0,
            accel_reference: None,
            temperature_sum: T::ZERO,
            temperature_count: 0,
            learned: 0,
            taken: None,
            last: Last::Moving,
            thermal: None,
        })
    }

    /// Sets how fast the bias can change: the density of its random walk (rad/s/√s; over `t` seconds it
    /// wanders by about `drift·√t`). Larger follows a drifting bias (a warming sensor) sooner and keeps a
    /// slow turn for less long; zero takes the bias for a constant (changed only by a step at rest). A
    /// sensor's own rate random walk ([`GyroNoise::bias_walk`](crate::noise::GyroNoise::bias_walk), from
    /// its datasheet or [`NoiseFit`](crate::noise::NoiseFit)) is the least it can be; temperature
    /// usually moves a MEMS bias faster.
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] if `drift` is negative, NaN, or so large that its square overflows.
    pub fn with_drift(mut self, drift: T) -> Result<Self, Error> {
        if !(drift >= T::ZERO && drift * drift <= T::MAX) {
            return Err(Error::InvalidEstimator);
        }
        self.drift = drift;
        Ok(self)
    }

    /// Sets how fast the bias wanders while the body stays still (rad/s/√s): the Kalman filter's process
    /// noise between two still windows that agree with the estimate. It sets how closely the estimate
    /// follows a drift at rest and how much noise it keeps (the noise of a window's mean against the
    /// drift over a window); it does not let a slow turn in (time spent in motion or in windows that
    /// disagree grows the uncertainty by `drift`). A sensor's rate random walk and bias instability
    /// ([`GyroNoise::bias_walk`](crate::noise::GyroNoise::bias_walk)) are its physical value; a changing
    /// temperature adds to it.
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] if `rest_drift` is negative, NaN, or so large that its square
    /// overflows.
    pub fn with_rest_drift(mut self, rest_drift: T) -> Result<Self, Error> {
        if !(rest_drift >= T::ZERO && rest_drift * rest_drift <= T::MAX) {
            return Err(Error::InvalidEstimator);
        }
        self.rest_drift = rest_drift;
        Ok(self)
    }

    /// Takes the scatter of block means at rest from the sensor's white noise instead of learning it:
    /// `N²/τ_block` per axis, `N` = `noise.arw()` (rad/√s; a datasheet's, or identified from a rest
    /// recording by [`NoiseFit`](crate::noise::NoiseFit), which also sees what the sensor's own filter
    /// does to short clusters if fitted from τ ≥ a block). (Its bias walk is the rest drift's physical
    /// value: give it with [`BiasEstimator::with_rest_drift`].)
    ///
    /// # Errors
    /// [`Error::InvalidEstimator`] if the white noise is zero (nothing would ever be flat).
    pub fn with_noise(mut self, noise: &crate::noise::GyroNoise<T>) -> Result<Self, Error> {
        let tau = self.period * T::from_f64(f64::from(self.block));
        let v = noise.arw() * noise.arw() / tau;
        if !(v > T::ZERO && v <= T::MAX) {
            return Err(Error::InvalidEstimator);
        }
        self.rest_scatter = Vec3::new(v, v, v);
        self.rest_dof = T::MAX;
        Ok(self)
    }

    /// Also requires, for a still window, every acceleration given through [`BiasEstimator::update_with`]
    /// within `gate` of the window's first, on every axis (the accelerations' unit; e.g. 0.5 m/s²). The
    /// accelerations' block means are tested for flatness whether or not a gate is set; a sample given
    /// without an acceleration is judged by its rate alone.
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

    /// Starts from a known bias (e.g. stored at the last shutdown) with standard deviation `sigma` (rad/s,
    /// every axis: how far it may have moved since). The first still window within five `sigma` (and its
    /// own noise) refines it; one farther off is followed as a step at rest only.
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] if a component of `bias` is NaN or infinite; [`Error::InvalidEstimator`]
    /// if `sigma` is not positive or its square overflows.
    pub fn with_initial(mut self, bias: Vec3<T>, sigma: T) -> Result<Self, Error> {
        if !bias.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        let v = sigma * sigma;
        if !(sigma > T::ZERO && v <= T::MAX) {
            return Err(Error::InvalidEstimator);
        }
        self.bias = bias;
        self.variance = Vec3::new(v, v, v);
        self.since = 0;
        self.bias_temperature = None;
        self.learned = 1;
        self.last = Last::AtEstimate;
        self.restart_window();
        Ok(self)
    }

    /// Moves the estimate by `delta` (rad/s): an estimator's bias correction (a filter that also observes
    /// the bias in motion). The levels of a step waiting to be confirmed and the bias(T) line's intercept
    /// move with it (its slope stays); the window being summed restarts (its samples were corrected with
    /// the old estimate). Give the same `delta` to
    /// [`Propagator::correct_bias`](crate::Propagator::correct_bias), so the samples the input model keeps
    /// move with it.
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] if `delta` is NaN or infinite, or the moved estimate, a level waiting to be
    /// confirmed or the bias(T) line's sums overflow; the estimator is then unchanged.
    pub fn correct_bias(&mut self, delta: Vec3<T>) -> Result<(), Error> {
        if !delta.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        let mut next = *self;
        next.bias += delta;
        match &mut next.last {
            Last::Candidate(c) | Last::Step(Some(c)) => c.bias += delta,
            _ => {}
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

    /// The current bias estimate (rad/s; zero before the first still window), at the learned windows'
    /// mean temperature.
    #[must_use]
    pub fn bias(&self) -> Vec3<T> {
        self.bias
    }

    /// The estimate's variance per axis ((rad/s)²): the last update's, grown by `drift²` per second since;
    /// [`Real::MAX`](crate::Real) on every axis before the first still window.
    #[must_use]
    pub fn variance(&self) -> Vec3<T> {
        if self.learned == 0 {
            return Vec3::new(T::MAX, T::MAX, T::MAX);
        }
        let grown = self.growth(self.since);
        map(self.variance, |v| v + grown)
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

    /// The last still window the estimate took, as a measurement of the bias on its own: the number of
    /// windows taken so far (saturating; it tells a new one from the last), the window's mean (rad/s;
    /// a confirmed step's two windows together) and the variance of that mean per axis ((rad/s)²). An
    /// estimator that also learns the bias elsewhere (a filter's accelerometer updates) takes each new one
    /// once as an independent measurement (the windows' noises are independent; the estimate is not).
    #[must_use]
    pub fn last_window(&self) -> Option<(u32, Vec3<T>, Vec3<T>)> {
        self.taken.map(|m| (self.learned, m.bias, m.variance))
    }

    /// `true` once at least one still window has been learned (or an initial bias given).
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
        self.since = self.since.saturating_add(1);
        if self.count == 0 {
            // A window starts here: its reference is its own first acceleration (none yet), never one
            // left by a sample in motion before it.
            self.accel_reference = None;
        }
        let g = self.gate;
        // A NaN or infinite component fails the gate: not still.
        let mut still = !corrected.saturated && d.x.abs() <= g && d.y.abs() <= g && d.z.abs() <= g;
        // The window's first acceleration: the gate's reference, and the origin of the sums (the block
        // means' scatter is a few ulp of gravity: taken about it, nothing cancels).
        let accel = match (aux.accel, self.accel_reference) {
            (Some(a), Some(r)) if self.count > 0 => {
                if let Some(ga) = self.accel_gate {
                    let e = a - r;
                    still &= e.x.abs() <= ga && e.y.abs() <= ga && e.z.abs() <= ga;
                }
                Some(a - r)
            }
            (Some(a), _) => {
                self.accel_reference = Some(a);
                Some(Vec3::ZERO)
            }
            (None, _) => None,
        };
        if !still {
            if self.count > 0 || !matches!(self.last, Last::Moving) {
                // (An empty window after motion has nothing to forget: in motion this is the common path.)
                self.restart_window();
                self.last = Last::Moving;
            }
            return;
        }
        self.block_sum += d;
        if let Some(a) = accel {
            self.accel_block_sum += a;
            self.accel_count += 1;
        }
        if let Some(t) = aux.temperature {
            self.temperature_sum += t;
            self.temperature_count += 1;
        }
        self.count += 1;
        self.in_block += 1;
        if self.in_block >= self.block {
            self.close_block();
        }
        if self.count >= self.window {
            self.close_window();
        }
    }

    /// A block finished: its means kept. Out of line: once per block, not per sample.
    #[inline(never)]
    fn close_block(&mut self) {
        let j = ((self.count / self.block.max(1)) as usize).saturating_sub(1);
        let inv = T::ONE / count::<T>(self.block);
        self.in_block = 0;
        if let Some(slot) = self.blocks.get_mut(j) {
            *slot = self.block_sum * inv;
        }
        self.block_sum = Vec3::ZERO;
        // Only the window's 8 blocks count (samples past them, when the window is not a multiple of 8,
        // are gated but not summed), for the accelerations as for the rates.
        if self.accel_count > 0 && j < BLOCKS {
            let m = self.accel_block_sum * inv;
            self.accel_means += m;
            self.accel_means_sq += zip(m, m, |a, b| a * b);
        }
        self.accel_block_sum = Vec3::ZERO;
    }

    /// A full window: judged, learned from, and the next one started. Out of line: once per window.
    #[inline(never)]
    fn close_window(&mut self) {
        let before = *self;
        self.judge_window();
        if !self.is_finite() {
            // Numbers so large that the sums overflowed: nothing learned from this window.
            *self = before;
            self.last = Last::Moving;
        }
        self.restart_window();
    }

    #[inline]
    fn restart_window(&mut self) {
        self.block_sum = Vec3::ZERO;
        self.in_block = 0;
        self.count = 0;
        self.accel_block_sum = Vec3::ZERO;
        self.accel_means = Vec3::ZERO;
        self.accel_means_sq = Vec3::ZERO;
        self.accel_count = 0;
        self.temperature_sum = T::ZERO;
        self.temperature_count = 0;
        self.accel_reference = None;
    }

    /// The least scatter of block means at rest: `(gate · 2⁻¹³)²`, saturated at `T::MAX` for an absurdly
    /// wide gate.
    fn scatter_floor(&self) -> T {
        let s = self.gate * T::from_f64(1.0 / 8192.0);
        let f = s * s;
        if f <= T::MAX {
            f
        } else {
            T::MAX
        }
    }

    /// `drift²` times `samples` periods.
    fn growth(&self, samples: u32) -> T {
        self.growth_at(self.drift, samples)
    }

    /// `q²` times `samples` periods, saturated at `T::MAX` (a drift so large that its growth overflows has
    /// let the bias go anywhere; the variance stays finite).
    fn growth_at(&self, q: T, samples: u32) -> T {
        if samples == 0 {
            // No time, no growth (`q² · period` may overflow, and ∞ · 0 is NaN).
            return T::ZERO;
        }
        let g = q * q * self.period * count::<T>(samples);
        if g <= T::MAX {
            g
        } else {
            T::MAX
        }
    }

    /// Every learned quantity finite (the window sums are reset after each window).
    fn is_finite(&self) -> bool {
        let finite = |t: Option<T>| t.is_none_or(Real::is_finite);
        let measured = |m: &Measurement<T>| {
            m.bias.is_finite() && m.variance.is_finite() && finite(m.temperature)
        };
        let last = match &self.last {
            Last::Candidate(c) | Last::Step(Some(c)) => measured(c),
            _ => true,
        };
        let last = last && self.taken.as_ref().is_none_or(measured);
        let thermal = self.thermal.is_none_or(|th| {
            th.weight.is_finite()
                && th.sum_t.is_finite()
                && th.sum_tt.is_finite()
                && th.sum_b.is_finite()
                && th.sum_tb.is_finite()
                && th.slope.is_finite()
                && finite(th.origin)
        });
        self.bias.is_finite()
            && self.variance.is_finite()
            && self.rest_scatter.is_finite()
            && self.accel_scatter.is_finite()
            && finite(self.bias_temperature)
            && last
            && thermal
    }

    /// The window's verdict: motion, a step, or a still window that updates the estimate, starts a step
    /// or confirms one.
    fn judge_window(&mut self) {
        // The estimate's uncertainty grows with the time since it was last judged: by `drift` for the time
        // it was not seen; for a still window that agrees with it, by `rest_drift` over that window. Both
        // are known before the verdict: `unseen` now, the window's share added if it is taken.
        let elapsed = self.since;
        self.since = 0;
        let unseen = self.growth(elapsed.saturating_sub(self.window));
        let window_seen = self.growth_at(self.rest_drift, elapsed.min(self.window));
        let window_unseen = self.growth(elapsed.min(self.window));
        self.variance = map(self.variance, |v| v + unseen);
        let temperature = (self.temperature_count > 0)
            .then(|| self.temperature_sum * (T::ONE / count::<T>(self.temperature_count)));
        let used = temperature.map_or(self.bias, |t| self.bias_at(t));
        let tested = self.window as usize >= BLOCKS;
        // The window's mean (of the corrected rates) and the scatter of its block means.
        let (mean, scatter) = if tested {
            let inv = T::ONE / T::from_f64(BLOCKS as f64);
            let mean = self.blocks.iter().fold(Vec3::ZERO, |s, &m| s + m) * inv;
            let ss = self.blocks.iter().fold(Vec3::ZERO, |s, &m| {
                let e = m - mean;
                s + zip(e, e, |a, b| a * b)
            });
            (mean, ss * (T::ONE / T::from_f64((BLOCKS - 1) as f64)))
        } else {
            // One block per window: its mean (the flatness and step tests are off).
            (self.blocks[0], Vec3::ZERO)
        };
        // The accelerations' block scatter, if every sample had one.
        let accel = (tested && self.accel_count == self.window).then(|| {
            let n = T::from_f64(BLOCKS as f64);
            zip(self.accel_means, self.accel_means_sq, |s, q| {
                (q - s * s / n).max(T::ZERO) / (n - T::ONE)
            })
        });
        let flat_gyro = !tested
            || self.rest_dof == T::ZERO
            || self.is_flat(scatter, self.rest_scatter, self.rest_dof);
        let flat_accel = match accel {
            Some(a) => {
                self.accel_dof == T::ZERO || self.is_flat(a, self.accel_scatter, self.accel_dof)
            }
            None => true,
        };
        // The variance of the window's mean: a mean of its blocks, with the scatter at rest (this
        // window's own until one is known, floored as in `pool`).
        let reference = if self.rest_dof == T::ZERO {
            let floor = self.scatter_floor();
            map(scatter, |s| s.max(floor))
        } else {
            self.rest_scatter
        };
        let inv_blocks = T::ONE / T::from_f64(if tested { BLOCKS as f64 } else { 1.0 });
        let m = Measurement {
            bias: used + mean,
            variance: reference * inv_blocks,
            temperature,
        };
        if !(flat_gyro && flat_accel) {
            self.variance = map(self.variance, |v| v + window_unseen);
            self.last = if flat_accel && matches!(self.last, Last::AtEstimate) {
                match self.step_in_window(used) {
                    Some(level) => Last::Step(level),
                    None => Last::Moving,
                }
            } else {
                Last::Moving
            };
            return;
        }
        if !(m.bias.is_finite() && m.temperature.is_none_or(Real::is_finite)) {
            self.variance = map(self.variance, |v| v + window_unseen);
            self.last = Last::Moving;
            return; // temperatures whose sum overflowed: nothing learned from this window
        }
        // A still window: it teaches the scatter at rest.
        if tested {
            // Floors: a sensor whose block means at rest never differ (a coarse quantization) still has
            // a scatter to compare with: the gate's 2⁻¹³ for the rates, 2⁻²⁴ of |a| for accelerations.
            let floor = self.scatter_floor();
            Self::pool(&mut self.rest_scatter, &mut self.rest_dof, scatter, floor);
            if let (Some(a), Some(level)) = (accel, self.accel_reference) {
                let floor = level.norm_squared() * T::from_f64(1.0 / 281_474_976_710_656.0);
                Self::pool(&mut self.accel_scatter, &mut self.accel_dof, a, floor);
            }
        }
        if self.learned == 0 {
            self.adopt(&m, None);
            return;
        }
        let innovation = m.bias - self.bias_at_or(temperature);
        let predicted = map(self.variance, |v| v + window_seen);
        if !disagrees(innovation, predicted + m.variance) {
            self.variance = predicted;
            self.update_estimate(&m, innovation);
            self.last = Last::AtEstimate;
            return;
        }
        self.variance = map(self.variance, |v| v + window_unseen);
        self.last = match self.last {
            Last::AtEstimate | Last::Step(None) => Last::Candidate(m),
            Last::Step(Some(c)) | Last::Candidate(c) => {
                if disagrees(m.bias - c.bias, m.variance + c.variance) {
                    // Two levels in a row after the estimate: a ramp, not a step.
                    Last::Moving
                } else {
                    self.adopt(&m, Some(c));
                    Last::AtEstimate
                }
            }
            Last::Moving => Last::Moving,
        };
    }

    /// The estimate at `temperature` (the estimate itself without one).
    fn bias_at_or(&self, temperature: Option<T>) -> Vec3<T> {
        temperature.map_or(self.bias, |t| self.bias_at(t))
    }

    /// Whether a scatter of block means (7 degrees of freedom) is within the bound of a scatter at rest
    /// known with `dof` degrees of freedom (`T::MAX`: given by the noise model).
    fn is_flat(&self, scatter: Vec3<T>, rest: Vec3<T>, dof: T) -> bool {
        let bound = if dof == T::MAX {
            T::from_f64(FLAT_CHI2 / (BLOCKS - 1) as f64)
        } else {
            // Windows behind the scatter: dof/7, at least one, at most the table's 64.
            let k = (dof * T::from_f64(1.0 / (BLOCKS - 1) as f64)).to_i32();
            let k = usize::try_from(k).unwrap_or(1).clamp(1, FLAT_F.len());
            T::from_f64(FLAT_F.get(k - 1).copied().unwrap_or(FLAT_F[0]))
        };
        let ok = |s: T, r: T| s <= bound * r;
        ok(scatter.x, rest.x) && ok(scatter.y, rest.y) && ok(scatter.z, rest.z)
    }

    /// Pools a window's scatter (7 degrees of freedom) into the scatter at rest, with an exponential
    /// memory of 64 windows (a scatter given by the noise model stays).
    fn pool(rest: &mut Vec3<T>, dof: &mut T, scatter: Vec3<T>, floor: T) {
        if *dof == T::MAX {
            return;
        }
        let scatter = map(scatter, |s| s.max(floor));
        let k = T::from_f64((BLOCKS - 1) as f64);
        let cap = T::from_f64(MEMORY * (BLOCKS - 1) as f64);
        let kept = if *dof + k > cap { cap - k } else { *dof };
        let inv = T::ONE / (kept + k);
        *rest = zip(*rest, scatter, |r, s| (r * kept + s * k) * inv);
        *dof = kept + k;
    }

    /// A window that is not flat, read as a step: two flat levels with one block between, the first at
    /// the estimate. `Some(None)`: a step whose new level shows in fewer than two blocks; `Some(Some(m))`:
    /// the new level; `None`: not a step.
    fn step_in_window(&self, used: Vec3<T>) -> Option<Option<Measurement<T>>> {
        if self.rest_dof == T::ZERO {
            return None;
        }
        let r = self.rest_scatter;
        let mut best: Option<(T, usize)> = None;
        for s in 0..BLOCKS {
            // Levels before and after the transition block `s`: sums and counts.
            let (before, after) = (
                self.blocks.get(..s).unwrap_or(&[]),
                self.blocks.get(s + 1..).unwrap_or(&[]),
            );
            let level = |b: &[Vec3<T>]| {
                let n = T::from_f64(b.len() as f64);
                (
                    b.iter().fold(Vec3::ZERO, |a, &m| a + m) * (T::ONE / n.max(T::ONE)),
                    n,
                )
            };
            let ((a, _), (b, _)) = (level(before), level(after));
            let ss = |blocks: &[Vec3<T>], l: Vec3<T>| {
                blocks.iter().fold(Vec3::ZERO, |acc, &m| {
                    let e = m - l;
                    acc + zip(e, e, |x, y| x * y)
                })
            };
            let resid = ss(before, a) + ss(after, b);
            // Normalized by the scatter at rest and by the bound of its degrees of freedom.
            let bound = T::from_f64(STEP_CHI2[usize::from(s == 0 || s == BLOCKS - 1)]);
            let score = (resid.x / r.x).max(resid.y / r.y).max(resid.z / r.z) / bound;
            // The level before the step (if any) is the estimate's: the body was still there.
            let starts_at_estimate = before.is_empty()
                || !disagrees(
                    a,
                    r * (T::ONE / T::from_f64(before.len() as f64)) + self.variance,
                );
            if starts_at_estimate && score <= T::ONE && best.is_none_or(|(b, _)| score < b) {
                best = Some((score, s));
            }
        }
        let (_, s) = best?;
        let after = self.blocks.get(s + 1..).unwrap_or(&[]);
        if after.len() < 2 {
            return Some(None);
        }
        let n = T::from_f64(after.len() as f64);
        let b = after.iter().fold(Vec3::ZERO, |a, &m| a + m) * (T::ONE / n);
        Some(Some(Measurement {
            bias: used + b,
            variance: r * (T::ONE / n),
            temperature: None,
        }))
    }

    /// The Kalman filter's update with a still window that agrees with the estimate.
    fn update_estimate(&mut self, m: &Measurement<T>, innovation: Vec3<T>) {
        let gain = share(self.variance, m.variance);
        self.bias += zip(gain, innovation, |k, v| k * v);
        self.variance = zip(gain, self.variance, |k, p| (T::ONE - k) * p);
        self.taken = Some(*m);
        if let (Some(t), true) = (m.temperature, self.thermal.is_some()) {
            let tb = self.bias_temperature.unwrap_or(t);
            let k = (gain.x + gain.y + gain.z) * T::from_f64(1.0 / 3.0);
            self.bias_temperature = Some(tb + (t - tb) * k);
        }
        self.learned = self.learned.saturating_add(1);
        self.record(m);
    }

    /// Restarts the estimate from `m` (and a confirmed level `c`: their weighted mean).
    fn adopt(&mut self, m: &Measurement<T>, c: Option<Measurement<T>>) {
        self.last = Last::AtEstimate;
        match c {
            Some(c) => {
                let w = share(c.variance, m.variance);
                // The weight of m is c's share of the variance.
                self.bias = c.bias + zip(w, m.bias - c.bias, |k, d| k * d);
                self.variance = zip(w, c.variance, |k, v| (T::ONE - k) * v);
                self.taken = Some(Measurement {
                    bias: self.bias,
                    variance: self.variance,
                    temperature: m.temperature,
                });
                self.bias_temperature = match (c.temperature, m.temperature) {
                    (Some(a), Some(b)) => Some(a * T::HALF + b * T::HALF),
                    (a, b) => b.or(a),
                };
                self.record(&c);
            }
            None => {
                self.bias = m.bias;
                self.variance = m.variance;
                self.bias_temperature = m.temperature;
                self.taken = Some(*m);
            }
        }
        self.learned = self.learned.saturating_add(1);
        self.record(m);
    }

    fn record(&mut self, m: &Measurement<T>) {
        if let Some(th) = self.thermal.as_mut() {
            th.add(m);
        }
    }
}

/// A count as a number: one instruction with an FPU (saturating at 2³¹ − 1).
#[inline]
fn count<T: Real>(n: u32) -> T {
    T::from_i32(i32::try_from(n).unwrap_or(i32::MAX))
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
