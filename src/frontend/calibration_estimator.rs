//! The gyro's gain (scale factor and axis misalignment) and its residual bias, learned in the run from the
//! accelerometer.
//!
//! A gyro whose gain is off by `G` (`ω_true = (I − G)(ω − b)`) turns a rotation of the body into a wrong
//! rotation of the attitude: the inclination drifts at the rate `R·(b + G·(ω − b))` in the reference
//! frame, which depends on how the body turns. The accelerometer, low-passed so that linear accelerations
//! average out, shows that drift as the correction its direction asks for (VQF's construction, shared with
//! [`MotionBias`](super::MotionBias), which models a bias alone). A Kalman filter on twelve states (three
//! of bias, nine of gain) takes that correction rate as a measurement of `LP(R·H)·θ`, with `H` the
//! Jacobian of the drift rate and `LP` the same low-pass filter: the principle of Tedaldi, Pretto and
//! Menegatti's calibration without external equipment ("A robust and easy to implement method for IMU
//! calibration without external equipments", ICRA 2014), causal and over any motion instead of between
//! rests.
//!
//! What decides what it can learn: a term of the gain shows only while the body turns about the axis it
//! scales, and only in the horizontal components of the drift. A turn about the vertical shows none of
//! its own scale; oscillating about one axis and back shows little (the drift it causes cancels over each
//! swing); many turns at different attitudes show every term. What it has not seen stays at its prior,
//! and its standard deviation ([`CalibrationEstimator::gain_std_dev`]) says so.

use super::inclination::{check_input, clip, inverse, Inclination, LowPass};
use super::Calibration;
use crate::{Error, GyroSample, Quat, Real, Vec3};

/// The bias state's unit (rad/s): 0.01 °/s, as VQF keeps it (the filter's numbers near 1 in f32).
const BIAS_UNIT: f64 = 0.01 * core::f64::consts::PI / 180.0;
/// The gain state's unit: 10⁻³ (a thousandth of the rate).
const GAIN_UNIT: f64 = 1.0e-3;

/// The number of states: 3 of bias, then the gain matrix `G` by rows.
const N: usize = 12;

type Matrix<T> = [[T; N]; N];

/// The gyro's gain and residual bias learned in the run from the accelerometer; hands a
/// [`Calibration`] to the front end.
///
/// Feed it the rates after the rest estimator ([`crate::frontend::BiasEstimator`]) with the accelerometer
/// in the same axes; integrate [`CalibrationEstimator::correct`] of each rate (the correction it had
/// before the sample, as [`MotionBias`](super::MotionBias) is used); call
/// [`CalibrationEstimator::at_rest`] when the rest estimator learns a window. The correction is
/// `ω = (I − G)·(ω_c − b)`, which is [`CalibrationEstimator::calibration`] applied: the same bits.
///
/// ```
/// use quatprop::frontend::CalibrationEstimator;
/// use quatprop::{GyroSample, Quat, Vec3};
/// // A gyro reading 1 % high on x, tumbling about an axis that sweeps the body; a still accelerometer
/// // (no linear acceleration: a measurement noise of 0.01 °/s rather than the default for a hand-held
/// // sensor).
/// let dt = 0.01_f64;
/// let mut est = CalibrationEstimator::<f64>::with_motion_noise(dt, 0.01, 0.0087, 0.001_f64.to_radians())?;
/// let mut q = Quat::<f64>::IDENTITY; // the true attitude (body to a frame whose z is up)
/// for k in 0..12_000 {
///     let t = k as f64 * dt;
///     let w = Vec3::new(t.cos(), (0.37 * t).sin(), 0.6 * (0.21 * t).cos()); // true rate (rad/s)
///     q = (q * Quat::from_rotation_vector(w * dt)).normalized().unwrap();
///     let gravity = q.conjugate().rotate(Vec3::new(0.0, 0.0, 9.81)); // at the sample's end
///     est.update(Vec3::new(1.01 * w.x, w.y, w.z), gravity, dt)?;
/// }
/// // After 2 min the correction multiplies x by 1/1.01 to 0.02 %; the other terms stay within 0.05 %.
/// let m = est.gain();
/// assert!((m[0][0] - 1.0 / 1.01).abs() < 2.0e-4);
/// assert!((m[1][1] - 1.0).abs() < 5.0e-4 && m[0][1].abs() < 5.0e-4);
/// let corrected = est.correct(GyroSample::new(Vec3::new(1.01, 0.0, 0.0)));
/// assert!((corrected.rate.x - 1.0).abs() < 5.0e-4);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CalibrationEstimator<T> {
    /// The shadow attitude and its inclination correction.
    inclination: Inclination<T>,
    /// `LP(R·H)`, row by row (the vertical frame's x, y, z).
    h_lp: [LowPass<T, N>; 3],
    /// `LP(R·H·θ̂)` with the estimate of each sample (x and y).
    prediction_lp: LowPass<T, 2>,
    /// The states: bias (units of 0.01 °/s), then `G` by rows (units of 10⁻³).
    theta: [T; N],
    /// Their covariance.
    p: Matrix<T>,
    /// The correction in use: `(I − G)` and `b`, as the front end applies it.
    calibration: Calibration<T>,
    /// The bias's prior variance, its growth per sample (VQF's forgetting) and its variance at rest.
    p0: T,
    v: T,
    p_rest: T,
    /// The gain's prior standard deviations (units of 10⁻³): diagonal, off-diagonal.
    sigma0: [T; 2],
    /// The gain's growth per sample (units of 10⁻³, squared).
    gain_walk: T,
    /// The measurement variances (horizontal, vertical).
    w_motion: T,
    w_vertical: T,
    /// Clips: the innovation and the bias (units of 0.01 °/s), the gain (units of 10⁻³).
    clip_e: T,
    clip_gain: T,
}

impl<T: Real> CalibrationEstimator<T> {
    /// The measurement noise that [`CalibrationEstimator::new`] assumes (rad/√s): the density of the
    /// inclination drift that the low-passed accelerometer shows and the gyro did not cause (linear
    /// acceleration left after the low-pass). 0.1 °/√s times √3: the factor leave-one-trial-out
    /// cross-validation chose on BROAD (`python/benchmarks/calibration.py`, docs/calibration.md).
    pub const DEFAULT_MOTION_NOISE: f64 =
        0.1 * 1.732_050_807_568_877_2 * core::f64::consts::PI / 180.0;

    /// How fast the gain may change (1/√s, a random walk's density): a gain term's variance grows by
    /// `GAIN_WALK²` per second. A gyro's gain is a constant; this lets the filter forget what it learned
    /// while its estimate was far from the truth (where the linearization is poor).
    pub const GAIN_WALK: f64 = 1.0e-5;

    /// The largest gain term it learns (beyond, the estimate is clipped): 5 % of the rate.
    pub const GAIN_LIMIT: f64 = 0.05;

    /// An estimator for samples every `sample_period` (s) that starts from no error, with the prior
    /// standard deviations of the scale factors (`sensitivity_sigma`, dimensionless: 0.01 for a
    /// datasheet's ±1 %) and of the cross-axis terms (`misalignment_sigma`, rad: 0.0087 for ±0.5°). The
    /// bias starts as VQF's motion bias does (0.5 °/s, forgetting time 100 s, clipped to ±2 °/s); the
    /// measurement noise density is [`DEFAULT_MOTION_NOISE`](Self::DEFAULT_MOTION_NOISE).
    ///
    /// # Errors
    /// [`Error::NonFiniteStep`] / [`Error::NonPositiveStep`] for a period that is not finite and positive;
    /// [`Error::InvalidEstimator`] for a sigma that is negative, not finite or beyond
    /// [`GAIN_LIMIT`](Self::GAIN_LIMIT).
    pub fn new(
        sample_period: f64,
        sensitivity_sigma: f64,
        misalignment_sigma: f64,
    ) -> Result<Self, Error> {
        Self::with_motion_noise(
            sample_period,
            sensitivity_sigma,
            misalignment_sigma,
            Self::DEFAULT_MOTION_NOISE,
        )
    }

    /// [`CalibrationEstimator::new`] with the measurement noise `motion_noise` (rad/√s, the density of
    /// the inclination drift the gyro did not cause: larger trusts the accelerometer less and learns
    /// slower).
    ///
    /// # Errors
    /// As [`CalibrationEstimator::new`]; [`Error::InvalidEstimator`] for a noise that is not finite and
    /// positive, or one (with the period) whose vertical variance, `(noise / 0.01 °/s)² / period / 10⁻⁴`,
    /// or whose bias growth, `period` per sample, overflows `T`.
    pub fn with_motion_noise(
        sample_period: f64,
        sensitivity_sigma: f64,
        misalignment_sigma: f64,
        motion_noise: f64,
    ) -> Result<Self, Error> {
        if !sample_period.is_finite() {
            return Err(Error::NonFiniteStep);
        }
        if !(sample_period > 0.0) {
            return Err(Error::NonPositiveStep);
        }
        let sigma_ok = |s: f64| (0.0..=Self::GAIN_LIMIT).contains(&s);
        if !(sigma_ok(sensitivity_sigma)
            && sigma_ok(misalignment_sigma)
            && motion_noise.is_finite()
            && motion_noise > 0.0)
        {
            return Err(Error::InvalidEstimator);
        }
        let ts = sample_period;
        let t = T::from_f64;
        // VQF's bias filter in units of 0.01 °/s: prior 0.5 °/s, growth (0.1 °/s)² per 100 s.
        let p0 = 50.0_f64 * 50.0;
        let v = 10.0_f64 * 10.0 * ts / 100.0;
        // The measurement's variance per sample: a density over one period.
        let noise = motion_noise / BIAS_UNIT;
        let w_motion = noise * noise / ts;
        // The vertical variance is the largest (10⁴ times the horizontal one) and the bias growth grows
        // with the period: both must be numbers in f64 and in `T`, or the filter would keep an infinity
        // and never update.
        let w_vertical = w_motion / 1.0e-4;
        if !([w_vertical, v]
            .iter()
            .all(|&x| x.is_finite() && T::from_f64(x).is_finite()))
        {
            return Err(Error::InvalidEstimator);
        }
        let sigma0 = [
            sensitivity_sigma / GAIN_UNIT,
            misalignment_sigma / GAIN_UNIT,
        ];
        let mut p = [[T::ZERO; N]; N];
        for (i, row) in p.iter_mut().enumerate() {
            row[i] = if i < 3 {
                t(p0)
            } else if (i - 3) / 3 == (i - 3) % 3 {
                t(sigma0[0] * sigma0[0])
            } else {
                t(sigma0[1] * sigma0[1])
            };
        }
        Ok(Self {
            inclination: Inclination::new(ts),
            h_lp: [LowPass::new(); 3],
            prediction_lp: LowPass::new(),
            theta: [T::ZERO; N],
            p,
            calibration: Calibration::identity(),
            p0: t(p0),
            v: t(v),
            p_rest: t(3.0 * 3.0),
            sigma0: [t(sigma0[0]), t(sigma0[1])],
            gain_walk: t((Self::GAIN_WALK / GAIN_UNIT) * (Self::GAIN_WALK / GAIN_UNIT) * ts),
            w_motion: t(w_motion),
            w_vertical: t(w_vertical),
            clip_e: t(200.0),
            clip_gain: t(Self::GAIN_LIMIT / GAIN_UNIT),
        })
    }

    /// The correction learned so far as a [`Calibration`]: offset `b` (rad/s), sensitivity the diagonal
    /// of `I − G`, misalignment its rows divided by it, so that [`Calibration::apply`] gives the
    /// corrected rate.
    #[must_use]
    pub fn calibration(&self) -> Calibration<T> {
        self.calibration
    }

    /// The rate corrected with what has been learned (`calibration().apply(s)`).
    #[inline]
    #[must_use]
    pub fn correct(&self, s: GyroSample<T>) -> GyroSample<T> {
        self.calibration.apply(s)
    }

    /// The residual bias (rad/s).
    #[must_use]
    pub fn bias(&self) -> Vec3<T> {
        let u = T::from_f64(BIAS_UNIT);
        Vec3::new(self.theta[0] * u, self.theta[1] * u, self.theta[2] * u)
    }

    /// The gain correction `I − G` (rows): the matrix that multiplies the bias-free rate.
    #[must_use]
    pub fn gain(&self) -> [[T; 3]; 3] {
        let u = T::from_f64(GAIN_UNIT);
        core::array::from_fn(|i| {
            core::array::from_fn(|j| {
                let d = if i == j { T::ONE } else { T::ZERO };
                d - self.theta[3 + 3 * i + j] * u
            })
        })
    }

    /// The standard deviation of each term of [`CalibrationEstimator::gain`] (rows): a term still at its
    /// prior (the sigma given to [`CalibrationEstimator::new`]) has not been observed.
    #[must_use]
    pub fn gain_std_dev(&self) -> [[T; 3]; 3] {
        let u = T::from_f64(GAIN_UNIT);
        core::array::from_fn(|i| {
            core::array::from_fn(|j| {
                let k = 3 + 3 * i + j;
                self.p[k][k].max(T::ZERO).sqrt() * u
            })
        })
    }

    /// How much of each gain term's prior uncertainty the data has removed, `1 − σ/σ₀` (0: not observed;
    /// near 1: learned), rows.
    #[must_use]
    pub fn gain_observed(&self) -> [[T; 3]; 3] {
        let sd = self.gain_std_dev();
        let u = T::from_f64(GAIN_UNIT);
        core::array::from_fn(|i| {
            core::array::from_fn(|j| {
                let s0 = self.sigma0[usize::from(i != j)] * u;
                if s0 > T::ZERO {
                    (T::ONE - sd[i][j] / s0).max(T::ZERO)
                } else {
                    T::ZERO
                }
            })
        })
    }

    /// The standard deviation of the residual bias (rad/s).
    #[must_use]
    pub fn bias_std_dev(&self) -> Vec3<T> {
        let u = T::from_f64(BIAS_UNIT);
        let s = |i: usize| self.p[i][i].max(T::ZERO).sqrt() * u;
        Vec3::new(s(0), s(1), s(2))
    }

    /// The rest estimator has just learned the bias: the residual restarts at zero with the uncertainty
    /// of a rest measurement (0.03 °/s) and no correlation with the gain, which stays.
    pub fn at_rest(&mut self) {
        for i in 0..3 {
            self.theta[i] = T::ZERO;
            for j in 0..N {
                self.p[i][j] = T::ZERO;
                self.p[j][i] = T::ZERO;
            }
            self.p[i][i] = self.p_rest;
        }
        self.refresh();
    }

    /// One sample: the rate (rad/s, as the rest estimator corrected it, before this estimator's
    /// correction) and the accelerometer (same axes; any unit: only its direction is used) over `dt` (s).
    /// An all-zero acceleration is skipped (no reading). The low-pass filter is designed for the period
    /// given to [`CalibrationEstimator::new`].
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`], [`Error::NonFiniteAux`], [`Error::NonFiniteStep`] /
    /// [`Error::NonPositiveStep`] for bad input, [`Error::NonFiniteResult`] if the arithmetic overflows;
    /// the estimator is then unchanged.
    pub fn update(&mut self, rate: Vec3<T>, accel: Vec3<T>, dt: T) -> Result<(), Error> {
        check_input(rate, accel, dt)?;
        let before = *self;
        self.step(rate, accel, dt);
        let finite = self.theta.iter().all(|x| x.is_finite())
            && self.p.iter().flatten().all(|x| x.is_finite())
            && self.inclination.is_finite()
            && self.h_lp.iter().all(LowPass::is_finite)
            && self.prediction_lp.is_finite();
        if !finite {
            *self = before;
            return Err(Error::NonFiniteResult);
        }
        Ok(())
    }

    fn step(&mut self, rate: Vec3<T>, accel: Vec3<T>, dt: T) {
        let w = self.correct(GyroSample::new(rate)).rate;
        let Some(o) = self.inclination.step(w, accel, dt) else {
            return;
        };
        // The Jacobian of the drift rate (units of 0.01 °/s per state unit) in the body, then turned into
        // the vertical frame: δ(b + G·d) = (I − G)·δb + [d_j at (i, 3 + 3i + j)]·δG, d = ω_c − b.
        let m = self.gain();
        let b = self.bias();
        let c = T::from_f64(GAIN_UNIT / BIAS_UNIT);
        let d = [(rate.x - b.x) * c, (rate.y - b.y) * c, (rate.z - b.z) * c];
        let r = tilt_to(o.rotation, accel);
        // The vertical row keeps only the bias: it is VQF's pseudo-measurement that holds the vertical
        // bias near zero while nothing shows it, not an observation (the gain's vertical drift is real).
        let mut h = [[T::ZERO; N]; 3];
        for (row, (hr, rr)) in h.iter_mut().zip(r.iter()).enumerate() {
            for k in 0..3 {
                hr[k] = rr[0] * m[0][k] + rr[1] * m[1][k] + rr[2] * m[2][k];
            }
            if row == 2 {
                continue;
            }
            for i in 0..3 {
                for (j, dj) in d.iter().enumerate() {
                    hr[3 + 3 * i + j] = rr[i] * *dj;
                }
            }
        }
        let dot =
            |row: &[T; N], x: &[T; N]| row.iter().zip(x).fold(T::ZERO, |s, (a, b)| s + *a * *b);
        let prediction = [dot(&h[0], &self.theta), dot(&h[1], &self.theta)];
        let f = &self.inclination.filter;
        let hl: [[T; N]; 3] = [
            self.h_lp[0].step(h[0], f),
            self.h_lp[1].step(h[1], f),
            self.h_lp[2].step(h[2], f),
        ];
        let pl = self.prediction_lp.step(prediction, f);
        if !self.prediction_lp.is_filtering() {
            // The first τ: the filters' outputs are running means, whose first samples are single
            // readings; nothing to learn from yet.
            return;
        }
        let u = T::from_f64(BIAS_UNIT);
        let [cx, cy] = o.correction_rate;
        let e = [
            cx / u + pl[0] - dot(&hl[0], &self.theta),
            cy / u + pl[1] - dot(&hl[1], &self.theta),
            -dot(&hl[2], &self.theta),
        ]
        .map(|x| clip(x, self.clip_e));
        // The bias forgets (VQF's growth up to its prior); the gain walks slowly (what lets an early
        // estimate, linearized far from the truth, be forgotten).
        for i in 0..3 {
            if self.p[i][i] < self.p0 {
                self.p[i][i] += self.v;
            }
        }
        for i in 3..N {
            self.p[i][i] += self.gain_walk;
        }
        // K = P Hᵀ (H P Hᵀ + W)⁻¹; θ += K e; P −= K (H P).
        let mut ph = [[T::ZERO; 3]; N];
        for (phr, pr) in ph.iter_mut().zip(self.p.iter()) {
            for (x, hr) in phr.iter_mut().zip(hl.iter()) {
                *x = dot(pr, hr);
            }
        }
        let mut s = [[T::ZERO; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                s[i][j] = (0..N).fold(T::ZERO, |acc, k| acc + hl[i][k] * ph[k][j]);
            }
        }
        s[0][0] += self.w_motion;
        s[1][1] += self.w_motion;
        s[2][2] += self.w_vertical;
        let Some(si) = inverse(s) else {
            return;
        };
        let mut k = [[T::ZERO; 3]; N];
        for (kr, phr) in k.iter_mut().zip(ph.iter()) {
            for (j, x) in kr.iter_mut().enumerate() {
                *x = phr[0] * si[0][j] + phr[1] * si[1][j] + phr[2] * si[2][j];
            }
        }
        for (th, kr) in self.theta.iter_mut().zip(k.iter()) {
            *th += kr[0] * e[0] + kr[1] * e[1] + kr[2] * e[2];
        }
        // P −= K (P Hᵀ)ᵀ, kept symmetric by computing one triangle. Indexed by ranges: with iterators
        // (`enumerate().skip(i)`) the optimizer no longer proved `p[j][i]` in bounds, and a panic path
        // reached the C API's `update` (its link-time proof caught it).
        #[allow(clippy::needless_range_loop)]
        for i in 0..N {
            for j in i..N {
                let x =
                    self.p[i][j] - (k[i][0] * ph[j][0] + k[i][1] * ph[j][1] + k[i][2] * ph[j][2]);
                self.p[i][j] = x;
                self.p[j][i] = x;
            }
        }
        let (cb, cg) = (self.clip_e, self.clip_gain);
        for (i, th) in self.theta.iter_mut().enumerate() {
            *th = clip(*th, if i < 3 { cb } else { cg });
        }
        self.refresh();
    }

    /// The correction from the states.
    fn refresh(&mut self) {
        self.calibration = Calibration::from_gain(self.bias(), self.gain());
    }
}

/// `r` (body to the vertical frame, rows) turned by the smallest rotation that brings this sample's
/// accelerometer `a` (body axes) onto the vertical: the attitude where the accelerometer says it is now,
/// without the low-pass filter's lag. The Jacobian is taken there, so that a tilt the shadow attitude has
/// only because the filter lags does not make a turn about the true vertical look tilting (which would
/// teach the filter a vertical axis's scale it cannot see). `r` itself where `a` is zero or points down.
fn tilt_to<T: Real>(r: [[T; 3]; 3], a: Vec3<T>) -> [[T; 3]; 3] {
    let Some(a) = a.normalized() else {
        return r;
    };
    let v = Vec3::new(
        r[0][0] * a.x + r[0][1] * a.y + r[0][2] * a.z,
        r[1][0] * a.x + r[1][1] * a.y + r[1][2] * a.z,
        r[2][0] * a.x + r[2][1] * a.y + r[2][2] * a.z,
    );
    let qw = ((v.z + T::ONE) * T::HALF).max(T::ZERO).sqrt();
    if !(qw > T::from_f64(1e-3)) {
        return r;
    }
    let c = Quat::new(qw, T::HALF * v.y / qw, -T::HALF * v.x / qw, T::ZERO).to_rotation_matrix();
    core::array::from_fn(|i| {
        core::array::from_fn(|j| c[i][0] * r[0][j] + c[i][1] * r[1][j] + c[i][2] * r[2][j])
    })
}
