//! The gyro bias in motion, from the accelerometer: VQF's motion bias estimation (D. Laidig, T. Seel, "VQF:
//! Highly accurate IMU orientation estimation with bias estimation and magnetic disturbance rejection",
//! Information Fusion 91, 2023; the algorithm of its reference implementation, MIT licence), on the rates
//! the rest estimator has already corrected.
//!
//! A shadow attitude is integrated from the corrected rates; the accelerometer, turned into that attitude's
//! reference frame and low-passed (a second-order Butterworth filter, τ = 3 s, so that linear
//! accelerations average out), shows how the inclination drifts; a Kalman filter on the bias takes that
//! drift, low-passed the same way, as a measurement of the horizontal components of `R·b`. As the body
//! turns, every component of the bias becomes observable. The shadow attitude (gyro and accelerometer) is
//! internal: the accelerometer informs the bias, never the attitude the propagator integrates.

use crate::{Error, Quat, Real, Vec3};

/// A second-order Butterworth low-pass filter over up to 9 channels, started by averaging its first `τ`
/// of input (as VQF does: no start-up transient from a single sample).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct LowPass<T> {
    /// Direct form II transposed state; while averaging, `s0` holds the sum.
    s0: [T; 9],
    s1: [T; 9],
    /// Samples averaged so far; `None` once filtering.
    count: Option<u32>,
}

/// The filter's coefficients `b0, b1, b2, a1, a2` and the samples to average first.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Butterworth<T> {
    b: [T; 3],
    a: [T; 2],
    average: u32,
}

impl<T: Real> Butterworth<T> {
    /// Time constant `tau` (s) of the non-oscillating part of the step response (cut-off `√2/(2πτ)`),
    /// sample period `ts` (s); a pass-through for `tau < ts/2`.
    fn new(tau: f64, ts: f64) -> Self {
        let average = libm::ceil(tau / ts).clamp(1.0, f64::from(u32::MAX)) as u32;
        if tau < ts / 2.0 {
            return Self {
                b: [T::ONE, T::ZERO, T::ZERO],
                a: [T::ZERO, T::ZERO],
                average: 1,
            };
        }
        let fc = core::f64::consts::SQRT_2 / (2.0 * core::f64::consts::PI * tau);
        let c = libm::tan(core::f64::consts::PI * fc * ts);
        let d = c * c + core::f64::consts::SQRT_2 * c + 1.0;
        let b0 = c * c / d;
        Self {
            b: [T::from_f64(b0), T::from_f64(2.0 * b0), T::from_f64(b0)],
            a: [
                T::from_f64(2.0 * (c * c - 1.0) / d),
                T::from_f64((1.0 - core::f64::consts::SQRT_2 * c + c * c) / d),
            ],
            average,
        }
    }
}

impl<T: Real> LowPass<T> {
    fn new() -> Self {
        Self {
            s0: [T::ZERO; 9],
            s1: [T::ZERO; 9],
            count: Some(0),
        }
    }

    /// The filtered `x` (the first `x.len()` channels; at most 9).
    fn step<const N: usize>(&mut self, x: [T; N], f: &Butterworth<T>) -> [T; N] {
        let mut y = [T::ZERO; N];
        match self.count {
            Some(n) => {
                let n = n.saturating_add(1);
                let inv = T::ONE / T::from_f64(f64::from(n));
                for (i, (yi, xi)) in y.iter_mut().zip(x).enumerate().take(9) {
                    self.s0[i] += xi;
                    *yi = self.s0[i] * inv;
                }
                if n >= f.average {
                    // The steady state of the mean: y = x = mean in the filter's equations.
                    for (i, &m) in y.iter().enumerate().take(9) {
                        self.s0[i] = m * (T::ONE - f.b[0]);
                        self.s1[i] = m * (f.b[2] - f.a[1]);
                    }
                    self.count = None;
                } else {
                    self.count = Some(n);
                }
            }
            None => {
                for (i, (yi, xi)) in y.iter_mut().zip(x).enumerate().take(9) {
                    *yi = f.b[0] * xi + self.s0[i];
                    self.s0[i] = f.b[1] * xi - f.a[0] * *yi + self.s1[i];
                    self.s1[i] = f.b[2] * xi - f.a[1] * *yi;
                }
            }
        }
        y
    }
}

/// `x` clipped to `[−c, c]`.
fn clip<T: Real>(x: T, c: T) -> T {
    if x > c {
        c
    } else if x < -c {
        -c
    } else {
        x
    }
}

/// The residual gyro bias in motion, learned from the accelerometer (VQF's motion bias estimation).
///
/// Feed it the rates after the rest estimator ([`crate::frontend::BiasEstimator`]) with the accelerometer in
/// the same axes; subtract [`MotionBias::bias`] from them; call [`MotionBias::at_rest`] when the rest
/// estimator learns a window (the rest estimate is then the better one, and the residual restarts at zero).
///
/// ```
/// use quatprop::frontend::MotionBias;
/// use quatprop::Vec3;
/// // A residual bias of 0.5 °/s about x, the body tumbling slowly about z under gravity.
/// let mut m = MotionBias::<f64>::new(1.0e-2)?;
/// let b = Vec3::new(0.5_f64.to_radians(), 0.0, 0.0);
/// let mut yaw = 0.0_f64;
/// for _ in 0..60_000 {
///     yaw += 0.3 * 1.0e-2;
///     let g = Vec3::new(0.0, 0.0, 9.81); // a turn about the vertical: gravity stays on body z
///     m.update(Vec3::new(0.0, 0.0, 0.3) + b, g, 1.0e-2)?;
/// }
/// // Only the horizontal bias is observable under a turn about the vertical; after 10 min it is learned.
/// assert!((m.bias().x - b.x).abs() < 0.02_f64.to_radians());
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MotionBias<T> {
    filter: Butterworth<T>,
    /// The sample period the filter was designed for (s): each update's `dt` should be near it.
    period: T,
    gyr_quat: Quat<T>,
    acc_quat: Quat<T>,
    acc_lp: LowPass<T>,
    r_lp: LowPass<T>,
    bias_lp: LowPass<T>,
    bias: Vec3<T>,
    /// The bias covariance, in (0.01 °/s)² as VQF keeps it.
    p: [[T; 3]; 3],
    p0: T,
    v: T,
    w_motion: T,
    w_vertical: T,
    p_rest: T,
    clip: T,
}

impl<T: Real> MotionBias<T> {
    /// VQF's defaults for samples every `sample_period` (s): τ_acc = 3 s, initial bias uncertainty 0.5 °/s,
    /// forgetting time 100 s, bias clipped to ±2 °/s, motion measurement noise 0.1 °/s, vertical
    /// forgetting factor 10⁻⁴; the residual restarts at rest with an uncertainty of 0.03 °/s.
    ///
    /// # Errors
    /// [`Error::NonPositiveStep`] / [`Error::NonFiniteStep`] for a period that is not finite and positive.
    pub fn new(sample_period: f64) -> Result<Self, Error> {
        if !sample_period.is_finite() {
            return Err(Error::NonFiniteStep);
        }
        if !(sample_period > 0.0) {
            return Err(Error::NonPositiveStep);
        }
        let ts = sample_period;
        let p0 = (0.5 * 100.0_f64) * (0.5 * 100.0);
        let v = (0.1 * 100.0_f64) * (0.1 * 100.0) * ts / 100.0;
        let p_motion = (0.1 * 100.0_f64) * (0.1 * 100.0);
        let w_motion = p_motion * p_motion / v + p_motion;
        let p_rest = (0.03 * 100.0_f64) * (0.03 * 100.0);
        let t = T::from_f64;
        let p0t = t(p0);
        Ok(Self {
            filter: Butterworth::new(3.0, ts),
            period: t(ts),
            gyr_quat: Quat::IDENTITY,
            acc_quat: Quat::IDENTITY,
            acc_lp: LowPass::new(),
            r_lp: LowPass::new(),
            bias_lp: LowPass::new(),
            bias: Vec3::ZERO,
            p: [
                [p0t, T::ZERO, T::ZERO],
                [T::ZERO, p0t, T::ZERO],
                [T::ZERO, T::ZERO, p0t],
            ],
            p0: p0t,
            v: t(v),
            w_motion: t(w_motion),
            w_vertical: t(w_motion / 1.0e-4),
            p_rest: t(p_rest),
            clip: t(2.0_f64.to_radians()),
        })
    }

    /// The residual bias estimate (rad/s), to subtract from the rates it is fed.
    #[must_use]
    pub fn bias(&self) -> Vec3<T> {
        self.bias
    }

    /// The rest estimator has just learned the bias: the residual restarts at zero, with the uncertainty
    /// of a rest measurement.
    pub fn at_rest(&mut self) {
        self.bias = Vec3::ZERO;
        let p = self.p_rest;
        self.p = [
            [p, T::ZERO, T::ZERO],
            [T::ZERO, p, T::ZERO],
            [T::ZERO, T::ZERO, p],
        ];
    }

    /// One sample: the rate (rad/s, already corrected by the rest estimate) and the accelerometer (same
    /// axes; any unit: only its direction is used) over `dt` (s). An all-zero acceleration is skipped (no
    /// reading). The filter is designed for the period given to [`MotionBias::new`].
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`], [`Error::NonFiniteAux`], [`Error::NonFiniteStep`] /
    /// [`Error::NonPositiveStep`] for bad input; the estimator is then unchanged.
    pub fn update(&mut self, rate: Vec3<T>, accel: Vec3<T>, dt: T) -> Result<(), Error> {
        if !rate.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        if !accel.is_finite() {
            return Err(Error::NonFiniteAux);
        }
        if !dt.is_finite() {
            return Err(Error::NonFiniteStep);
        }
        if !(dt > T::ZERO) {
            return Err(Error::NonPositiveStep);
        }
        let before = *self;
        self.step(rate, accel, dt);
        if !(self.bias.is_finite() && self.gyr_quat.is_finite() && self.acc_quat.is_finite()) {
            *self = before;
            return Err(Error::NonFiniteResult);
        }
        Ok(())
    }

    fn step(&mut self, rate: Vec3<T>, accel: Vec3<T>, dt: T) {
        // The shadow attitude: the corrected rate integrated.
        let w = rate - self.bias;
        let q = self.gyr_quat * Quat::from_rotation_vector(w * dt);
        self.gyr_quat = q.normalized().unwrap_or(self.gyr_quat);
        if accel == Vec3::ZERO {
            return;
        }
        let ts = self.period;
        // The accelerometer in the shadow reference frame, low-passed, then through the inclination
        // correction so far.
        let a = self.gyr_quat.rotate(accel);
        let a = self.acc_lp.step([a.x, a.y, a.z], &self.filter);
        let a = self.acc_quat.rotate(Vec3::new(a[0], a[1], a[2]));
        let Some(a) = a.normalized() else {
            return;
        };
        // The inclination correction that brings it to the vertical.
        let qw = ((a.z + T::ONE) * T::HALF).max(T::ZERO).sqrt();
        let corr = if qw > T::from_f64(1e-6) {
            Quat::new(qw, T::HALF * a.y / qw, -T::HALF * a.x / qw, T::ZERO)
        } else {
            Quat::new(T::ZERO, T::ONE, T::ZERO, T::ZERO)
        };
        self.acc_quat = (corr * self.acc_quat).normalized().unwrap_or(self.acc_quat);
        // The bias Kalman filter: R of the 6D attitude, R·b and R low-passed like the measurement.
        let q6 = self.acc_quat * self.gyr_quat;
        let m = q6.to_rotation_matrix();
        let r = [
            m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2],
        ];
        let b = self.bias;
        let rb = [
            r[0] * b.x + r[1] * b.y + r[2] * b.z,
            r[3] * b.x + r[4] * b.y + r[5] * b.z,
        ];
        let r = self.r_lp.step(r, &self.filter);
        let rb = self.bias_lp.step(rb, &self.filter);
        let e = [
            -a.y / ts + rb[0] - (r[0] * b.x + r[1] * b.y + r[2] * b.z),
            a.x / ts + rb[1] - (r[3] * b.x + r[4] * b.y + r[5] * b.z),
            -(r[6] * b.x + r[7] * b.y + r[8] * b.z),
        ];
        let w = [self.w_motion, self.w_motion, self.w_vertical];
        for i in 0..3 {
            if self.p[i][i] < self.p0 {
                self.p[i][i] += self.v;
            }
        }
        let e = e.map(|x| clip(x, self.clip));
        let rm = [[r[0], r[1], r[2]], [r[3], r[4], r[5]], [r[6], r[7], r[8]]];
        // K = P Rᵀ (W + R P Rᵀ)⁻¹
        let prt = mul(self.p, transpose(rm));
        let mut s = mul(rm, prt);
        for (i, wi) in w.iter().enumerate() {
            s[i][i] += *wi;
        }
        let Some(si) = inverse(s) else {
            return;
        };
        let k = mul(prt, si);
        let db = [
            k[0][0] * e[0] + k[0][1] * e[1] + k[0][2] * e[2],
            k[1][0] * e[0] + k[1][1] * e[1] + k[1][2] * e[2],
            k[2][0] * e[0] + k[2][1] * e[1] + k[2][2] * e[2],
        ];
        let nb = Vec3::new(b.x + db[0], b.y + db[1], b.z + db[2]);
        let c = self.clip;
        self.bias = Vec3::new(clip(nb.x, c), clip(nb.y, c), clip(nb.z, c));
        // P ← P − K R P
        let krp = mul(mul(k, rm), self.p);
        for (row, k_row) in self.p.iter_mut().zip(krp) {
            for (p, k) in row.iter_mut().zip(k_row) {
                *p -= k;
            }
        }
    }
}

type M3<T> = [[T; 3]; 3];

fn mul<T: Real>(a: M3<T>, b: M3<T>) -> M3<T> {
    let mut c = [[T::ZERO; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    c
}

fn transpose<T: Real>(a: M3<T>) -> M3<T> {
    [
        [a[0][0], a[1][0], a[2][0]],
        [a[0][1], a[1][1], a[2][1]],
        [a[0][2], a[1][2], a[2][2]],
    ]
}

/// `a⁻¹` by cofactors, if `det a` is finite and non-zero.
fn inverse<T: Real>(a: M3<T>) -> Option<M3<T>> {
    let c = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]
    };
    let det = a[0][0] * c(0, 0) + a[0][1] * c(0, 1) + a[0][2] * c(0, 2);
    if !(det.is_finite() && det != T::ZERO) {
        return None;
    }
    let inv = T::ONE / det;
    let mut out = [[T::ZERO; 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, e) in row.iter_mut().enumerate() {
            *e = c(j, i) * inv;
        }
    }
    Some(out)
}
