//! An attitude estimator (6D: gyroscope and accelerometer, no magnetometer) built on quatprop's predict
//! step: an error-state Kalman filter, written once for the host example and the firmware.
//!
//! Only `quatprop` and `core`: no `std`, no heap, no panic on a data path (every fallible call returns a
//! [`FilterError`]), so a `no_std` firmware can include this file with `#[path]` and run the same `f32`
//! code as the host, bit for bit.
//!
//! # The model
//! - **Attitude**: a [`Propagator`] (ExpMap + [`Hold`] + FirstOrder) integrates `ω_m − b̂`, the bias
//!   estimate `b̂` held in a [`FixedBias`]. Samples come at a fixed period. [`Hold`] takes each sample as
//!   the mean rate over the period that ends at it (as VQF integrates): a MEMS gyro's output is filtered
//!   and late. What is left of its lag is the sensor's group delay ([`Params::group_delay`]): the
//!   attitude reported is carried forward by it at the latest corrected rate.
//! - **Error state** `x = (δθ, δb)`: `q = q̂ ⊗ exp_q(δθ)` (attitude error in the **body** frame) and
//!   `b = b̂ + δb`. Its covariance is kept as `U D Uᵀ` ([`Ud`]).
//! - **Predict**: every [`Params::predict_every`] gyro samples, [`Step::between`] the attitude at the
//!   start and at the end of the interval gives the closed-form `Φ` and `Q`, and [`Ud::predict`] applies
//!   them.
//! - **Accelerometer low-pass** ([`Params::accel_tau`], as VQF does): every sample is rotated into the
//!   reference frame with the current attitude and low-passed there (second-order Butterworth, cut-off
//!   `√2/(2πτ)`), where the gyro keeps the frame almost inertial and the linear accelerations of a motion
//!   that comes back average out. A correction `q̂ ← q̂ ⊗ exp(δθ)` is `exp(R(q̂)δθ) ⊗ q̂`: the filter's
//!   state is rotated by the same reference-frame rotation, as if the past samples had been rotated with
//!   the corrected attitude. The measurement is the low-pass output seen in body axes now.
//! - **Update** (every [`Params::update_every`] epochs, ~0.1 s: the low-passed direction is correlated
//!   in time; its variance is the measured equivalent, not a white sample's): the accelerometer's
//!   direction `â = a/|a|` against the predicted
//!   "up" in body axes `ĝ = R(q̂)ᵀ e_z` (reference z up; at rest an accelerometer measures `+g e_z`). The
//!   measured tilt error is the rotation vector `ρ` taking `ĝ` to `â` with its sign such that `ρ ≈ δθ_⊥`
//!   (`ρ = (â × ĝ)/|â × ĝ| · angle(â, ĝ)`, exact in the angle), observed as two scalar rows `zᵢ = tᵢ·ρ`
//!   with `hᵢ = (tᵢ, 0)`, `t₁, t₂` an orthonormal basis of the plane normal to `ĝ`. Heading (the
//!   component of `δθ` along `ĝ`) is not observed: the reference frame's heading is the one the filter
//!   started with.
//! - **Measurement variance** (rad², per row): `r = (σ_a/g)² + σ_floor² + (k · (|a| − g)/g)²` (`a`
//!   the low-passed specific force when the low-pass is on): `σ_a` (m/s² per axis: with the low-pass, an
//!   equivalent noise of the filtered direction, chosen for consistency on BROAD) as a direction, a floor
//!   `σ_floor` for what does
//!   not average out (accelerometer bias and misalignment), and an inflation when the norm departs from
//!   gravity (a linear acceleration of magnitude `L` tilts the measured direction by up to `L/g`, and
//!   `||a| − g| ≤ L`: the norm flags the part of it along gravity), plus `(c · |ω̂|)²` with the rate
//!   `|ω̂|` of the last interval ([`Params::rotating`]: centripetal and tangential accelerations come
//!   with rotation; 0 in the shipped set: with the low-pass it only made things worse on BROAD).
//! - **Innovation gate**: the two rows' normalized innovation squared `νᵀ S⁻¹ ν` (`S = T P_θθ Tᵀ + r I`,
//!   2 degrees of freedom) above [`Params::gate`] rejects the epoch's update (a linear acceleration the
//!   norm did not flag). So that a filter that is wrong cannot lock itself out, after
//!   [`Params::gate_timeout`] seconds of consecutive rejections the next update is taken anyway
//!   (counted in [`Counts::forced`]).
//! - **Correction and reset**: `x` from the two sequential Bierman updates (`x ← x + K (z − h·x)`) is
//!   folded into the nominal state: [`Propagator::rotate_body`]`(δθ)`, [`FixedBias::correct_bias`]`(δb)` and
//!   [`Propagator::correct_bias`]`(δb)` (the same `δb`, so the input model's kept samples move with it),
//!   and `x` is reset to zero. For a body-frame error the reset's covariance transform is
//!   `G = I − ½[δθ×]` on the attitude block, `I` to first order in `|δθ|` (a few mrad per update): it is
//!   taken as `I`, the covariance is left as the update made it.
//! - **Rest detector** ([`Params::rest_window`]): a [`BiasEstimator`] fed the raw gyro and the
//!   accelerometer; each still window it takes ([`BiasEstimator::last_window`]) is a measurement of all
//!   three bias components (three scalar rows on `δb`, its mean's variance), the vertical one included,
//!   which the accelerometer alone never observes. A window that disagrees with the filter's bias beyond
//!   their joint uncertainty (χ²₃ at 1 − 10⁻⁴) is a fault of the filter: its bias restarts from the window
//!   ([`Counts::restarts`]), which holds a bias that ran away while the body moved.
//! - **Inclination uncertainty**: the horizontal components of the attitude error in the reference frame
//!   (`R(q̂) δθ`) are the components of `δθ` normal to `ĝ`; [`Filter::inclination_sigma`] is the square
//!   root of the larger eigenvalue of their 2 × 2 covariance. For an isotropic 2D Gaussian error the
//!   error's magnitude is inside 3σ with probability `1 − e^{−4.5}` = 98.9 %.
//! - **Start**: the first sample's accelerometer gives the tilt (heading zero), with the variance
//!   [`Params::initial_tilt`]² about both horizontal axes; the bias starts at zero with
//!   [`Params::initial_bias`]² per axis.

// The matrix code reads clearest with the indices of its formulas; `!(x <= gate)` is meant: a NaN fails it.
#![allow(clippy::needless_range_loop, clippy::neg_cmp_op_on_partial_ord)]

use quatprop::covariance::Ud;
use quatprop::error_state::{GyroNoise, Step};
use quatprop::frontend::{Aux, BiasEstimator, FixedBias, SampleTiming};
use quatprop::input::Hold;
use quatprop::scheme::ExpMap;
use quatprop::stabilize::FirstOrder;
use quatprop::{Error, GyroSample, Propagator, Quat, Real, Vec3};

/// The filter's parameters, in the units a datasheet uses (converted once, in [`Filter::new`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    /// The sample period (s): gyro and accelerometer are sampled together, at a fixed rate.
    pub sample_period: f64,
    /// Gyro samples per covariance predict and accelerometer update (≥ 1).
    pub predict_every: u32,
    /// Gyro angle random walk (°/√h), as [`GyroNoise::from_datasheet`] takes it.
    pub gyro_arw: f64,
    /// Gyro bias random walk (°/h/√h).
    pub gyro_bias_walk: f64,
    /// Gyro scale-factor and misalignment error (1σ, a fraction of the rotation): the attitude noise
    /// `(gyro_scale · |φ|)²` (rad², every axis) added per interval in which the body turned by `φ`.
    pub gyro_scale: f64,
    /// Accelerometer white noise (m/s², 1σ per axis, per sample).
    pub accel_noise: f64,
    /// Floor of the accelerometer's direction error (rad, 1σ per axis): bias and misalignment.
    pub accel_floor: f64,
    /// Gravity (m/s²).
    pub gravity: f64,
    /// The inflation factor `k` of `||a| − g|/g` (dimensionless; 0: none).
    pub dynamic: f64,
    /// The inflation with the rotation rate (s): `σ = rotating · |ω̂|` (rad) added to the measurement's
    /// (centripetal and tangential accelerations come with rotation, on a lever arm not known here).
    pub rotating: f64,
    /// Gate on the normalized innovation squared (2 degrees of freedom; 0: no gate).
    pub gate: f64,
    /// Consecutive rejections (s) after which the next update is taken anyway.
    pub gate_timeout: f64,
    /// Initial tilt uncertainty (rad, 1σ about each horizontal axis).
    pub initial_tilt: f64,
    /// Initial bias uncertainty (rad/s, 1σ per axis).
    pub initial_bias: f64,
    /// Time constant (s) of the accelerometer's low-pass in the reference frame (a second-order
    /// Butterworth, as VQF's); 0: the raw sample is the measurement.
    pub accel_tau: f64,
    /// Epochs per accelerometer update (≥ 1): the low-passed direction is correlated in time.
    pub update_every: u32,
    /// The rest detector's window (s; 0: no rest updates): a [`BiasEstimator`] fed the raw gyro and the
    /// accelerometer; each still window it takes is a measurement of all three bias components.
    pub rest_window: f64,
    /// The rest detector's gate (rad/s per axis, around its own bias estimate).
    pub rest_gate: f64,
    /// The gyro's group delay (s): how long after the motion a sample comes out of the sensor's filter.
    /// The attitude reported is carried forward by it at the latest corrected rate
    /// ([`SampleTiming::ahead`]); the filter itself runs on the samples as they come.
    pub group_delay: f64,
}

impl Params {
    /// The parameter set shipped with the example for a MEMS IMU sampled every `sample_period` seconds: one
    /// covariance step per ~10 ms and one accelerometer update per ~0.1 s; `gyro_scale` and
    /// `accel_noise` as leave-one-trial-out cross-validation chooses them on BROAD (docs/estimator.md),
    /// the rest's provenance in docs/defaults.md. A sensor's own `gyro_arw` (identified at rest) and
    /// `group_delay` are its own to give.
    #[must_use]
    pub fn mems(sample_period: f64) -> Self {
        let per = round_half_away(0.01 / sample_period);
        Self {
            sample_period,
            predict_every: if per >= 1.0 { per as u32 } else { 1 },
            gyro_arw: 0.5,
            gyro_bias_walk: 20.0,
            gyro_scale: 0.03,
            accel_noise: 0.5,
            accel_floor: 0.005,
            gravity: 9.81,
            dynamic: 1.0,
            rotating: 0.0,
            gate: 13.8,
            gate_timeout: 1.0,
            initial_tilt: 0.035,
            initial_bias: 0.01,
            accel_tau: 1.5,
            update_every: 10,
            rest_window: 1.0,
            rest_gate: 0.0524,
            group_delay: 0.0,
        }
    }

    fn valid(&self) -> bool {
        let positive = [
            self.sample_period,
            self.gravity,
            self.initial_tilt,
            self.initial_bias,
            self.rest_gate,
        ];
        let non_negative = [
            self.gyro_arw,
            self.gyro_bias_walk,
            self.gyro_scale,
            self.accel_noise,
            self.accel_floor,
            self.dynamic,
            self.rotating,
            self.gate,
            self.gate_timeout,
            self.accel_tau,
            self.rest_window,
            self.group_delay,
        ];
        positive.iter().all(|&v| v > 0.0 && v.is_finite())
            && non_negative.iter().all(|&v| v >= 0.0 && v.is_finite())
            && self.predict_every >= 1
            && self.update_every >= 1
            && (self.accel_noise > 0.0 || self.accel_floor > 0.0)
    }
}

/// Round half away from zero, in `core` only (no `f64::round` without `std`).
fn round_half_away(v: f64) -> f64 {
    let t = v as i64 as f64; // truncation toward zero (saturating for huge values)
    if v - t >= 0.5 {
        t + 1.0
    } else if t - v >= 0.5 {
        t - 1.0
    } else {
        t
    }
}

/// Why a push (or [`Filter::new`]) failed. The filter is then unchanged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FilterError {
    /// From quatprop: a non-finite gyro sample, a step beyond the scheme's bound, a covariance that
    /// overflowed, ...
    Core(Error),
    /// An accelerometer component is NaN or infinite.
    NonFiniteAccel,
    /// The first sample's accelerometer is zero: no tilt to start from (push the next one).
    NoGravity,
    /// A parameter is out of range ([`Params`]).
    InvalidParams,
}

impl From<Error> for FilterError {
    fn from(e: Error) -> Self {
        Self::Core(e)
    }
}

impl core::fmt::Display for FilterError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Core(e) => write!(f, "quatprop: {e}"),
            Self::NonFiniteAccel => f.write_str("non-finite accelerometer sample"),
            Self::NoGravity => f.write_str("zero accelerometer sample at the start"),
            Self::InvalidParams => f.write_str("invalid filter parameters"),
        }
    }
}

/// What a push did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pushed {
    /// The first sample: attitude levelled from the accelerometer, the propagator started.
    Started,
    /// The gyro sample was integrated (no epoch).
    Propagated,
    /// An epoch: predict, then the accelerometer update (`forced`: taken past the gate's timeout).
    Updated {
        /// The gate rejected it but had rejected for longer than its timeout.
        forced: bool,
    },
    /// An epoch: predict; the update was gated out (or `|a|` was zero).
    Rejected,
    /// An epoch: predict only (no accelerometer update due, [`Params::update_every`]).
    Predicted,
}

/// What the filter counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    /// Samples taken (the first included).
    pub samples: u64,
    /// Covariance predict steps (epochs).
    pub predicts: u64,
    /// Accelerometer updates applied (forced ones included).
    pub updates: u64,
    /// Updates rejected by the gate (or a zero accelerometer).
    pub rejected: u64,
    /// Updates taken after the gate's timeout.
    pub forced: u64,
    /// Bias updates from still windows (the rest detector's).
    pub rests: u64,
    /// Still windows that disagreed with the filter's bias beyond its uncertainty: the bias restarted
    /// from them.
    pub restarts: u64,
}

/// The error-state Kalman filter ([module documentation](self)). `Copy`, allocation-free.
#[derive(Clone, Copy, Debug)]
pub struct Filter<T: Real> {
    prop: Propagator<T, ExpMap, Hold, FirstOrder>,
    bias: FixedBias<T>,
    cov: Ud<T, 6>,
    /// The attitude at the start of the current covariance interval (after the last correction).
    q_start: Quat<T>,
    started: bool,
    /// Samples integrated since the last epoch.
    pending: u32,
    rejected_run: u32,
    counts: Counts,
    // Parameters, converted.
    dt: T,
    interval: T,
    every: u32,
    noise: GyroNoise<T>,
    scale_var: T,
    accel_var: T,
    gravity: T,
    dynamic: T,
    /// `rotating / Δt` for the interval's turn `|φ|`.
    rotating: T,
    /// The body's turn over the last interval squared (rad²).
    turned_sq: T,
    gate: T,
    gate_epochs: u32,
    tilt_var: T,
    bias_var: T,
    /// The accelerometer low-pass ([`Lowpass`]), `None` when `accel_tau` is 0.
    lowpass: Option<Lowpass<T>>,
    update_every: u32,
    /// Epochs since the last accelerometer update (taken or not).
    since_update: u32,
    /// The rest detector, and the number of its still windows already used.
    rest: Option<BiasEstimator<T>>,
    rest_used: u32,
    /// The gyro's group delay, and the latest corrected rate (rad/s) to carry the attitude forward with.
    timing: SampleTiming<T>,
    rate: Vec3<T>,
}

impl<T: Real> Filter<T> {
    /// A filter waiting for its first sample.
    ///
    /// # Errors
    /// [`FilterError::InvalidParams`] for a parameter out of range (or one that overflows `T`).
    pub fn new(params: Params) -> Result<Self, FilterError> {
        if !params.valid() {
            return Err(FilterError::InvalidParams);
        }
        let noise = GyroNoise::from_datasheet(params.gyro_arw, params.gyro_bias_walk)
            .map_err(|_| FilterError::InvalidParams)?;
        let dir = params.accel_noise / params.gravity;
        let accel_var = dir * dir + params.accel_floor * params.accel_floor;
        let epoch = params.sample_period * f64::from(params.predict_every);
        let timeout =
            round_half_away(params.gate_timeout / (epoch * f64::from(params.update_every)));
        let gate_epochs = if timeout >= f64::from(u32::MAX) {
            u32::MAX
        } else {
            timeout as u32
        };
        let conv = |v: f64| {
            let t = T::from_f64(v);
            if t.is_finite() {
                Ok(t)
            } else {
                Err(FilterError::InvalidParams)
            }
        };
        let filter = Self {
            prop: Propagator::new(Quat::IDENTITY, ExpMap, Hold::new(), FirstOrder)?,
            bias: FixedBias::new(Vec3::ZERO)?,
            cov: Ud::from_diagonal([T::ZERO; 6])?,
            q_start: Quat::IDENTITY,
            started: false,
            pending: 0,
            rejected_run: 0,
            counts: Counts::default(),
            dt: conv(params.sample_period)?,
            interval: conv(epoch)?,
            every: params.predict_every,
            noise,
            scale_var: conv(params.gyro_scale * params.gyro_scale)?,
            accel_var: conv(accel_var)?,
            gravity: conv(params.gravity)?,
            dynamic: conv(params.dynamic)?,
            rotating: conv(params.rotating / epoch)?,
            turned_sq: T::ZERO,
            gate: conv(params.gate)?,
            gate_epochs,
            tilt_var: conv(params.initial_tilt * params.initial_tilt)?,
            bias_var: conv(params.initial_bias * params.initial_bias)?,
            lowpass: if params.accel_tau > 0.0 {
                Some(
                    Lowpass::new(params.accel_tau, params.sample_period)
                        .ok_or(FilterError::InvalidParams)?,
                )
            } else {
                None
            },
            update_every: params.update_every,
            since_update: 0,
            rest: if params.rest_window > 0.0 {
                Some(BiasEstimator::new(
                    params.rest_window,
                    params.sample_period,
                    conv(params.rest_gate)?,
                )?)
            } else {
                None
            },
            rest_used: 0,
            timing: SampleTiming::instant().with_group_delay(conv(params.group_delay)?)?,
            rate: Vec3::ZERO,
        };
        if filter.dt > T::ZERO && filter.accel_var > T::ZERO {
            Ok(filter)
        } else {
            Err(FilterError::InvalidParams)
        }
    }

    /// Takes one sample: `gyro` (rad/s, body axes) and `accel` (m/s², body axes, the specific force: `+g`
    /// up at rest), taken together one sample period after the previous one. On an error the filter is
    /// unchanged (the sample is dropped; the next one is taken as one period later still).
    ///
    /// # Errors
    /// [`FilterError::NonFiniteAccel`]; [`FilterError::NoGravity`] for a zero accelerometer on the first
    /// sample; [`FilterError::Core`] from the propagator or the covariance (e.g. a non-finite gyro sample).
    pub fn push(&mut self, gyro: Vec3<T>, accel: Vec3<T>) -> Result<Pushed, FilterError> {
        if !accel.is_finite() {
            return Err(FilterError::NonFiniteAccel);
        }
        if !self.started {
            return self.start(gyro, accel);
        }
        let mut next = *self;
        let corrected = next.bias.apply(GyroSample::new(gyro));
        next.prop.push(corrected, next.dt)?;
        next.rate = corrected.rate;
        next.pending += 1;
        if let Some(rest) = next.rest.as_mut() {
            let aux = Aux {
                accel: Some(accel),
                temperature: None,
            };
            rest.update_with(GyroSample::new(gyro), aux)?;
        }
        if let Some(lp) = next.lowpass.as_mut() {
            lp.push(next.prop.attitude().rotate(accel));
        }
        let out = if next.pending >= next.every {
            next.epoch(accel)?
        } else {
            Pushed::Propagated
        };
        next.counts.samples += 1;
        *self = next;
        Ok(out)
    }

    fn start(&mut self, gyro: Vec3<T>, accel: Vec3<T>) -> Result<Pushed, FilterError> {
        let up = accel.normalized().ok_or(FilterError::NoGravity)?;
        let q0 = level(up)?;
        let mut next = *self;
        next.prop.set_attitude(q0)?;
        next.prop.start(next.bias.apply(GyroSample::new(gyro)))?;
        // P_θθ = σ_t² (I − ĝĝᵀ) + σ_h² ĝĝᵀ (body axes), σ_h small: the heading is the filter's own.
        let head_var = next.tilt_var * T::from_f64(1e-4);
        let g = [up.x, up.y, up.z];
        let mut p = [[T::ZERO; 6]; 6];
        for i in 0..3 {
            for j in 0..3 {
                let id = if i == j { T::ONE } else { T::ZERO };
                p[i][j] = next.tilt_var * (id - g[i] * g[j]) + head_var * g[i] * g[j];
            }
            p[i + 3][i + 3] = next.bias_var;
        }
        // Symmetric by construction up to the order of the products: mirror the upper triangle.
        for i in 0..6 {
            for j in 0..i {
                p[i][j] = p[j][i];
            }
        }
        next.cov = Ud::from_matrix(&p)?;
        next.q_start = next.prop.attitude();
        if let Some(lp) = next.lowpass.as_mut() {
            lp.reset(next.q_start.rotate(accel));
        }
        next.started = true;
        next.pending = 0;
        next.counts.samples += 1;
        *self = next;
        Ok(Pushed::Started)
    }

    /// Predict over the interval just integrated, then the accelerometer update and the correction.
    fn epoch(&mut self, accel: Vec3<T>) -> Result<Pushed, FilterError> {
        let end = self.prop.attitude();
        let step = Step::between(self.q_start, end, self.interval, &self.noise)?;
        let (phi, mut q) = step.matrices();
        let turned = (self.q_start.conjugate() * end).to_rotation_vector();
        self.turned_sq = turned.norm_squared();
        let extra = self.scale_var * self.turned_sq;
        for i in 0..3 {
            q[i][i] += extra;
        }
        self.cov.predict(&phi, &q)?;
        self.counts.predicts += 1;
        self.pending = 0;
        self.q_start = end;
        // A still window the rest detector took since the last epoch: a measurement of the bias.
        if let Some((n, b, v)) = self.rest.and_then(|r| r.last_window()) {
            if n != self.rest_used {
                self.rest_used = n;
                self.rest_update(b, v)?;
            }
        }
        let end = self.prop.attitude();

        self.since_update += 1;
        if self.since_update < self.update_every {
            return Ok(Pushed::Predicted);
        }
        self.since_update = 0;
        let g_hat = up_in_body(end);
        // The measured specific force: the sample itself, or the low-passed one (reference frame) seen
        // in body axes now.
        let accel = match &self.lowpass {
            Some(lp) => end.conjugate().rotate(lp.output()),
            None => accel,
        };
        let norm = accel.norm();
        let Some(a_hat) = accel.normalized() else {
            self.reject();
            return Ok(Pushed::Rejected);
        };
        let (t1, t2) = tangents(g_hat)?;
        // ρ: from ĝ to â, ρ ≈ δθ_⊥.
        let c = a_hat.cross(g_hat);
        let s = c.norm();
        let angle = s.atan2(a_hat.dot(g_hat));
        let rho = if s > T::ZERO { c * (angle / s) } else { c };
        let z = [t1.dot(rho), t2.dot(rho)];
        let excess = self.dynamic * (norm - self.gravity) / self.gravity;
        let r = self.accel_var + excess * excess + self.rotating * self.rotating * self.turned_sq;
        if !r.is_finite() {
            return Err(FilterError::Core(Error::NonFiniteResult));
        }

        let mut forced = false;
        if self.gate > T::ZERO {
            let nis = nis(&self.cov.matrix(), t1, t2, r, z);
            if !(nis <= self.gate) {
                if self.rejected_run < self.gate_epochs {
                    self.reject();
                    return Ok(Pushed::Rejected);
                }
                // The filter has disagreed with the accelerometer for longer than the timeout: take it
                // as wrong and reopen its tilt uncertainty (Φ = I, Q = σ_t² (I − ĝĝᵀ)) before updating.
                forced = true;
                let mut identity = [[T::ZERO; 6]; 6];
                let mut reopen = [[T::ZERO; 6]; 6];
                let g = [g_hat.x, g_hat.y, g_hat.z];
                for i in 0..6 {
                    identity[i][i] = T::ONE;
                }
                for i in 0..3 {
                    for j in 0..3 {
                        let id = if i == j { T::ONE } else { T::ZERO };
                        reopen[i][j] = self.tilt_var * (id - g[i] * g[j]);
                    }
                }
                self.cov.predict(&identity, &reopen)?;
            }
        }

        let mut x = [T::ZERO; 6];
        for (t, zi) in [(t1, z[0]), (t2, z[1])] {
            let h = [t.x, t.y, t.z, T::ZERO, T::ZERO, T::ZERO];
            let gain = self.cov.update(&h, r)?;
            let mut hx = T::ZERO;
            for i in 0..6 {
                hx += h[i] * x[i];
            }
            let innovation = zi - hx;
            for i in 0..6 {
                x[i] += gain.gain[i] * innovation;
            }
        }
        self.fold(x)?;
        self.rejected_run = 0;
        self.counts.updates += 1;
        if forced {
            self.counts.forced += 1;
        }
        Ok(Pushed::Updated { forced })
    }

    /// Folds the error state `x = (δθ, δb)` into the nominal state and resets it: the attitude rotated,
    /// the bias (and the samples the input model keeps) corrected.
    fn fold(&mut self, x: [T; 6]) -> Result<(), FilterError> {
        let dtheta = Vec3::new(x[0], x[1], x[2]);
        let dbias = Vec3::new(x[3], x[4], x[5]);
        let before = self.prop.attitude();
        self.prop.rotate_body(dtheta)?;
        if let Some(lp) = self.lowpass.as_mut() {
            // q ← q ⊗ exp(δθ) is exp(R(q)δθ) ⊗ q: the reference-frame correction moves the past samples
            // held in the low-pass as it moves the attitude they were rotated with.
            lp.rotate(Quat::from_rotation_vector(before.rotate(dtheta)));
        }
        self.bias.correct_bias(dbias)?;
        self.prop.correct_bias(dbias)?;
        self.q_start = self.prop.attitude();
        Ok(())
    }

    /// A still window's measurement of the bias (its mean `b`, rad/s, and that mean's variance `v` per
    /// axis): three scalar rows `δb_i = b_i − b̂_i`, then the correction. A window that disagrees with the
    /// filter beyond its own uncertainty (`Σ z_i²/(P_bb,ii + v_i)` above the χ²₃ bound of 10⁻⁴, 21.1) is a
    /// fault of the filter's bias, not noise: the bias restarts from the window (`b̂ ← b`, its variance the
    /// window's, no correlation with the attitude), counted in [`Counts::restarts`].
    fn rest_update(&mut self, b: Vec3<T>, v: Vec3<T>) -> Result<(), FilterError> {
        let z = b - self.bias.bias();
        let p = self.cov.matrix();
        let nis =
            z.x * z.x / (p[3][3] + v.x) + z.y * z.y / (p[4][4] + v.y) + z.z * z.z / (p[5][5] + v.z);
        if !(nis <= T::from_f64(RESTART_CHI2)) {
            let mut restarted = p;
            for i in 0..6 {
                for j in 0..6 {
                    if (i < 3) != (j < 3) || (i >= 3 && i != j) {
                        restarted[i][j] = T::ZERO;
                    }
                }
            }
            restarted[3][3] = v.x;
            restarted[4][4] = v.y;
            restarted[5][5] = v.z;
            self.cov = Ud::from_matrix(&restarted)?;
            self.bias.correct_bias(z)?;
            self.prop.correct_bias(z)?;
            self.q_start = self.prop.attitude();
            self.counts.restarts += 1;
            return Ok(());
        }
        let mut x = [T::ZERO; 6];
        for (i, (zi, ri)) in [(z.x, v.x), (z.y, v.y), (z.z, v.z)].into_iter().enumerate() {
            let mut h = [T::ZERO; 6];
            h[3 + i] = T::ONE;
            let gain = self.cov.update(&h, ri)?;
            let innovation = zi - x[3 + i];
            for k in 0..6 {
                x[k] += gain.gain[k] * innovation;
            }
        }
        self.fold(x)?;
        self.counts.rests += 1;
        Ok(())
    }

    fn reject(&mut self) {
        self.rejected_run = self.rejected_run.saturating_add(1);
        self.counts.rejected += 1;
    }

    /// The attitude estimate `q̂` (body to reference, z up; heading the filter's own), now: the filter's
    /// attitude carried forward by the gyro's group delay ([`Params::group_delay`]) at the latest rate.
    #[must_use]
    pub fn attitude(&self) -> Quat<T> {
        self.timing.ahead(self.prop.attitude(), self.rate)
    }

    /// The gyro bias estimate `b̂` (rad/s, body axes).
    #[must_use]
    pub fn bias(&self) -> Vec3<T> {
        self.bias.bias()
    }

    /// The variances of `(δθ, δb)` (body axes; rad², (rad/s)²), as of the last epoch.
    #[must_use]
    pub fn variances(&self) -> [T; 6] {
        self.cov.variances()
    }

    /// The inclination's 1σ (rad): the square root of the larger eigenvalue of the covariance of the
    /// attitude error's horizontal components (reference frame), as of the last epoch. Three times it is
    /// the 3σ bound.
    ///
    /// # Errors
    /// [`FilterError::Core`] if the attitude is not finite.
    pub fn inclination_sigma(&self) -> Result<T, FilterError> {
        let (t1, t2) = tangents(up_in_body(self.prop.attitude()))?;
        let p = self.cov.matrix();
        let a = quadratic(&p, t1, t1);
        let b = quadratic(&p, t1, t2);
        let c = quadratic(&p, t2, t2);
        let half = (a - c) * T::HALF;
        let lambda = (a + c) * T::HALF + (half * half + b * b).sqrt();
        Ok(lambda.max(T::ZERO).sqrt())
    }

    /// The covariance of the inclination error in the reference frame's horizontal axes (rad²: `[xx, xy,
    /// yy]` of `R(q̂) P_θθ R(q̂)ᵀ`, reference x and y), as of the last epoch: with the error's horizontal
    /// components `e` (the rotation taking the estimate to the truth, in the reference frame), the
    /// normalized estimation error squared is `eᵀ P⁻¹ e`, 2 on average for a consistent filter.
    ///
    /// # Errors
    /// [`FilterError::Core`] if the attitude is not finite.
    pub fn inclination_covariance(&self) -> Result<[T; 3], FilterError> {
        let q = self.prop.attitude();
        if !q.is_finite() {
            return Err(FilterError::Core(Error::NonFiniteQuaternion));
        }
        // The reference x and y axes in body axes: the rows of R(q̂) that give reference x and y.
        let ex = q.conjugate().rotate(Vec3::new(T::ONE, T::ZERO, T::ZERO));
        let ey = q.conjugate().rotate(Vec3::new(T::ZERO, T::ONE, T::ZERO));
        let p = self.cov.matrix();
        Ok([
            quadratic(&p, ex, ex),
            quadratic(&p, ex, ey),
            quadratic(&p, ey, ey),
        ])
    }

    /// What the filter counted.
    #[must_use]
    pub fn counts(&self) -> Counts {
        self.counts
    }

    /// Whether the first sample has been taken.
    #[must_use]
    pub fn is_started(&self) -> bool {
        self.started
    }
}

/// The χ²₃ quantile of 1 − 10⁻⁴: a still window's disagreement with the filter's bias beyond it restarts
/// the bias.
const RESTART_CHI2: f64 = 21.11;

/// `R(q)ᵀ e_z`: the reference's up in body axes.
fn up_in_body<T: Real>(q: Quat<T>) -> Vec3<T> {
    q.conjugate().rotate(Vec3::new(T::ZERO, T::ZERO, T::ONE))
}

/// The attitude (heading zero) that takes the body vector `up` (unit) to the reference's `e_z`.
fn level<T: Real>(up: Vec3<T>) -> Result<Quat<T>, FilterError> {
    let ez = Vec3::new(T::ZERO, T::ZERO, T::ONE);
    let axis = up.cross(ez);
    let s = axis.norm();
    let q = if s > T::ZERO {
        Quat::from_rotation_vector(axis * (s.atan2(up.z) / s))
    } else if up.z > T::ZERO {
        Quat::IDENTITY
    } else {
        Quat::from_rotation_vector(Vec3::new(T::PI, T::ZERO, T::ZERO))
    };
    if q.is_finite() {
        Ok(q)
    } else {
        Err(FilterError::Core(Error::NonFiniteResult))
    }
}

/// An orthonormal basis `(t₁, t₂)` of the plane normal to the unit vector `g`.
fn tangents<T: Real>(g: Vec3<T>) -> Result<(Vec3<T>, Vec3<T>), FilterError> {
    let (ax, ay, az) = (g.x.abs(), g.y.abs(), g.z.abs());
    let e = if ax <= ay && ax <= az {
        Vec3::new(T::ONE, T::ZERO, T::ZERO)
    } else if ay <= az {
        Vec3::new(T::ZERO, T::ONE, T::ZERO)
    } else {
        Vec3::new(T::ZERO, T::ZERO, T::ONE)
    };
    let t1 = g
        .cross(e)
        .normalized()
        .ok_or(FilterError::Core(Error::NonFiniteResult))?;
    let t2 = g.cross(t1);
    Ok((t1, t2))
}

/// `uᵀ P_θθ v`.
fn quadratic<T: Real>(p: &[[T; 6]; 6], u: Vec3<T>, v: Vec3<T>) -> T {
    let (u, v) = ([u.x, u.y, u.z], [v.x, v.y, v.z]);
    let mut s = T::ZERO;
    for i in 0..3 {
        for j in 0..3 {
            s += u[i] * p[i][j] * v[j];
        }
    }
    s
}

/// The normalized innovation squared `zᵀ S⁻¹ z`, `S = T P_θθ Tᵀ + r I` (2 × 2).
fn nis<T: Real>(p: &[[T; 6]; 6], t1: Vec3<T>, t2: Vec3<T>, r: T, z: [T; 2]) -> T {
    let a = quadratic(p, t1, t1) + r;
    let b = quadratic(p, t1, t2);
    let c = quadratic(p, t2, t2) + r;
    let det = a * c - b * b;
    (c * z[0] * z[0] - T::TWO * b * z[0] * z[1] + a * z[1] * z[1]) / det
}

/// A second-order Butterworth low-pass of a vector (VQF's: cut-off `√2/(2πτ)`, bilinear transform),
/// transposed direct form II, run per axis.
#[derive(Clone, Copy, Debug)]
struct Lowpass<T: Real> {
    b0: T,
    b1: T,
    b2: T,
    a1: T,
    a2: T,
    s0: Vec3<T>,
    s1: Vec3<T>,
    y: Vec3<T>,
}

impl<T: Real> Lowpass<T> {
    fn new(tau: f64, dt: f64) -> Option<Self> {
        let fc = core::f64::consts::SQRT_2 / (2.0 * core::f64::consts::PI * tau);
        let x = core::f64::consts::PI * fc * dt;
        let c = <f64 as Real>::sin(x) / <f64 as Real>::cos(x);
        let d = c * c + core::f64::consts::SQRT_2 * c + 1.0;
        let b0 = c * c / d;
        let a1 = 2.0 * (c * c - 1.0) / d;
        let a2 = (1.0 - core::f64::consts::SQRT_2 * c + c * c) / d;
        let f = |v: f64| {
            let t = T::from_f64(v);
            if v.is_finite() && t.is_finite() {
                Some(t)
            } else {
                None
            }
        };
        if !(x > 0.0 && x < 1.5) {
            return None;
        }
        Some(Self {
            b0: f(b0)?,
            b1: f(2.0 * b0)?,
            b2: f(b0)?,
            a1: f(a1)?,
            a2: f(a2)?,
            s0: Vec3::ZERO,
            s1: Vec3::ZERO,
            y: Vec3::ZERO,
        })
    }

    /// The steady state for a constant input `x`.
    fn reset(&mut self, x: Vec3<T>) {
        self.y = x;
        self.s0 = x * (T::ONE - self.b0);
        self.s1 = x * (self.b2 - self.a2);
    }

    fn push(&mut self, x: Vec3<T>) {
        let y = x * self.b0 + self.s0;
        self.s0 = x * self.b1 - y * self.a1 + self.s1;
        self.s1 = x * self.b2 - y * self.a2;
        self.y = y;
    }

    fn output(&self) -> Vec3<T> {
        self.y
    }

    /// Rotates the filter's state and output (the filter is linear: as if every past input had been).
    fn rotate(&mut self, q: Quat<T>) {
        self.s0 = q.rotate(self.s0);
        self.s1 = q.rotate(self.s1);
        self.y = q.rotate(self.y);
    }
}
