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

use super::inclination::{check_input, clip, inverse, Inclination, LowPass};
use crate::{Error, Real, Vec3};

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
    /// The shadow attitude and its inclination correction, designed for the sample period given.
    inclination: Inclination<T>,
    r_lp: LowPass<T, 9>,
    bias_lp: LowPass<T, 2>,
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
    /// [`Error::NonPositiveStep`] / [`Error::NonFiniteStep`] for a period that is not finite and positive;
    /// [`Error::InvalidEstimator`] for one so long (beyond 10³⁰⁶ s; 10³⁸ s in f32) that the bias
    /// variance's growth per sample overflows.
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
        // For a period beyond 10³⁰⁶ s (10³⁸ s in f32) the growth overflows: an infinite variance would
        // stop the filter learning.
        if !(v.is_finite() && T::from_f64(v).is_finite()) {
            return Err(Error::InvalidEstimator);
        }
        let w_motion = p_motion * p_motion / v + p_motion;
        let p_rest = (0.03 * 100.0_f64) * (0.03 * 100.0);
        let t = T::from_f64;
        let p0t = t(p0);
        Ok(Self {
            inclination: Inclination::new(ts),
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
        check_input(rate, accel, dt)?;
        let before = *self;
        self.step(rate, accel, dt);
        if !(self.bias.is_finite()
            && self.inclination.is_finite()
            && self.r_lp.is_finite()
            && self.bias_lp.is_finite())
        {
            *self = before;
            return Err(Error::NonFiniteResult);
        }
        Ok(())
    }

    fn step(&mut self, rate: Vec3<T>, accel: Vec3<T>, dt: T) {
        // The shadow attitude: the corrected rate integrated.
        let w = rate - self.bias;
        let Some(o) = self.inclination.step(w, accel, dt) else {
            return;
        };
        let [cx, cy] = o.correction_rate;
        // The bias Kalman filter: R of the 6D attitude, R·b and R low-passed like the measurement.
        let m = o.rotation;
        let r = [
            m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2],
        ];
        let b = self.bias;
        let rb = [
            r[0] * b.x + r[1] * b.y + r[2] * b.z,
            r[3] * b.x + r[4] * b.y + r[5] * b.z,
        ];
        let f = &self.inclination.filter;
        let r = self.r_lp.step(r, f);
        let rb = self.bias_lp.step(rb, f);
        let e = [
            cx + rb[0] - (r[0] * b.x + r[1] * b.y + r[2] * b.z),
            cy + rb[1] - (r[3] * b.x + r[4] * b.y + r[5] * b.z),
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
