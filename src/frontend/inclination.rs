//! What the in-motion estimators ([`MotionBias`](super::MotionBias),
//! [`CalibrationEstimator`](super::CalibrationEstimator)) share: a shadow attitude integrated from the
//! corrected rates, the accelerometer turned into its reference frame and low-passed, and the inclination
//! correction that brings the low-passed accelerometer to the vertical (VQF's construction: D. Laidig,
//! T. Seel, "VQF: Highly accurate IMU orientation estimation with bias estimation and magnetic disturbance
//! rejection", Information Fusion 91, 2023). The rate of that correction is what a wrong rate (a bias, a
//! wrong gain) does to the inclination, low-passed; each estimator models it with its own states.

use crate::{Error, Quat, Real, Vec3};

/// A second-order Butterworth low-pass filter's coefficients `b0, b1, b2, a1, a2` and the samples to
/// average first.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct Butterworth<T> {
    b: [T; 3],
    a: [T; 2],
    average: u32,
}

impl<T: Real> Butterworth<T> {
    /// Time constant `tau` (s) of the non-oscillating part of the step response (cut-off `√2/(2πτ)`),
    /// sample period `ts` (s); a pass-through for `tau < ts/2`.
    pub(super) fn new(tau: f64, ts: f64) -> Self {
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

/// The [`Butterworth`] filter over `N` channels, started by averaging its first `τ` of input (as VQF
/// does: no start-up transient from a single sample).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(bound(
        serialize = "T: serde::Serialize, [T; N]: serde::Serialize",
        deserialize = "T: serde::Deserialize<'de>, [T; N]: serde::Deserialize<'de>"
    ))
)]
pub(super) struct LowPass<T, const N: usize> {
    /// Direct form II transposed state; while averaging, `s0` holds the sum.
    s0: [T; N],
    s1: [T; N],
    /// Samples averaged so far; `None` once filtering.
    count: Option<u32>,
}

impl<T: Real, const N: usize> LowPass<T, N> {
    pub(super) fn new() -> Self {
        Self {
            s0: [T::ZERO; N],
            s1: [T::ZERO; N],
            count: Some(0),
        }
    }

    /// Whether every number in the filter's state is finite.
    pub(super) fn is_finite(&self) -> bool {
        self.s0.iter().chain(self.s1.iter()).all(|x| x.is_finite())
    }

    /// Whether the start (the mean of the first `τ`) is over and the output is the filter's.
    pub(super) fn is_filtering(&self) -> bool {
        self.count.is_none()
    }

    /// The filtered `x`.
    pub(super) fn step(&mut self, x: [T; N], f: &Butterworth<T>) -> [T; N] {
        let mut y = [T::ZERO; N];
        match self.count {
            Some(n) => {
                let n = n.saturating_add(1);
                let inv = T::ONE / T::from_f64(f64::from(n));
                for ((yi, xi), s) in y.iter_mut().zip(x).zip(self.s0.iter_mut()) {
                    *s += xi;
                    *yi = *s * inv;
                }
                if n >= f.average {
                    // The steady state of the mean: y = x = mean in the filter's equations.
                    for ((s0, s1), &m) in self.s0.iter_mut().zip(self.s1.iter_mut()).zip(y.iter()) {
                        *s0 = m * (T::ONE - f.b[0]);
                        *s1 = m * (f.b[2] - f.a[1]);
                    }
                    self.count = None;
                } else {
                    self.count = Some(n);
                }
            }
            None => {
                for ((yi, xi), (s0, s1)) in y
                    .iter_mut()
                    .zip(x)
                    .zip(self.s0.iter_mut().zip(self.s1.iter_mut()))
                {
                    *yi = f.b[0] * xi + *s0;
                    *s0 = f.b[1] * xi - f.a[0] * *yi + *s1;
                    *s1 = f.b[2] * xi - f.a[1] * *yi;
                }
            }
        }
        y
    }
}

/// `x` clipped to `[−c, c]`.
pub(super) fn clip<T: Real>(x: T, c: T) -> T {
    if x > c {
        c
    } else if x < -c {
        -c
    } else {
        x
    }
}

/// The shadow attitude and its inclination correction.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct Inclination<T> {
    pub(super) filter: Butterworth<T>,
    /// The sample period the filter was designed for (s).
    pub(super) period: T,
    /// The corrected rates integrated (body to the shadow reference frame).
    gyr_quat: Quat<T>,
    /// The inclination correction so far (shadow reference frame to a frame whose z is up).
    acc_quat: Quat<T>,
    acc_lp: LowPass<T, 3>,
}

/// What one accelerometer sample tells: the rate of the inclination correction it asked for (rad/s, the
/// vertical frame's x and y) and the rotation matrix of the corrected attitude (body to the vertical
/// frame), rows.
pub(super) struct Observation<T> {
    pub(super) correction_rate: [T; 2],
    pub(super) rotation: [[T; 3]; 3],
}

impl<T: Real> Inclination<T> {
    /// τ = 3 s (VQF's `tauAcc`) for samples every `ts` (s).
    pub(super) fn new(ts: f64) -> Self {
        Self {
            filter: Butterworth::new(3.0, ts),
            period: T::from_f64(ts),
            gyr_quat: Quat::IDENTITY,
            acc_quat: Quat::IDENTITY,
            acc_lp: LowPass::new(),
        }
    }

    /// Whether the attitudes and the filter's state are finite (a check after an update: an
    /// acceleration near the float's largest can overflow the filter's sum).
    pub(super) fn is_finite(&self) -> bool {
        self.gyr_quat.is_finite() && self.acc_quat.is_finite() && self.acc_lp.is_finite()
    }

    /// The corrected rate `w` (rad/s) over `dt` (s) into the shadow attitude, then the accelerometer
    /// (any unit; all zero: no reading, and nothing else happens). `None` without a reading or when the
    /// low-passed vector is zero.
    pub(super) fn step(&mut self, w: Vec3<T>, accel: Vec3<T>, dt: T) -> Option<Observation<T>> {
        let q = self.gyr_quat * Quat::from_rotation_vector(w * dt);
        self.gyr_quat = q.normalized().unwrap_or(self.gyr_quat);
        if accel == Vec3::ZERO {
            return None;
        }
        // The accelerometer in the shadow reference frame, low-passed, then through the inclination
        // correction so far.
        let a = self.gyr_quat.rotate(accel);
        let a = self.acc_lp.step([a.x, a.y, a.z], &self.filter);
        let a = self.acc_quat.rotate(Vec3::new(a[0], a[1], a[2]));
        let a = a.normalized()?;
        // The inclination correction that brings it to the vertical.
        let qw = ((a.z + T::ONE) * T::HALF).max(T::ZERO).sqrt();
        let corr = if qw > T::from_f64(1e-6) {
            Quat::new(qw, T::HALF * a.y / qw, -T::HALF * a.x / qw, T::ZERO)
        } else {
            Quat::new(T::ZERO, T::ONE, T::ZERO, T::ZERO)
        };
        self.acc_quat = (corr * self.acc_quat).normalized().unwrap_or(self.acc_quat);
        let ts = self.period;
        Some(Observation {
            correction_rate: [-a.y / ts, a.x / ts],
            rotation: (self.acc_quat * self.gyr_quat).to_rotation_matrix(),
        })
    }
}

/// `a⁻¹` by cofactors, if `det a` is finite and non-zero.
pub(super) fn inverse<T: Real>(a: [[T; 3]; 3]) -> Option<[[T; 3]; 3]> {
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

/// The refusals of an in-motion estimator's update: a rate, an acceleration or a `dt` that is not finite,
/// a `dt` that is not positive.
pub(super) fn check_input<T: Real>(rate: Vec3<T>, accel: Vec3<T>, dt: T) -> Result<(), Error> {
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
    Ok(())
}
