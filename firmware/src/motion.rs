//! A body turning in every direction under gravity, sampled at 1 kHz as the front end's in-motion estimators
//! (`frontend::CalibrationEstimator`, `frontend::MotionBias`) see it: the gyro reading with a gain error
//! and a residual bias, the accelerometer without linear acceleration (gravity in the body frame, m/s²).
//! What the `predict` program counts them on and the `stack` program paints them with.

use quatprop::{Quat, Real, Vec3};

/// The sample period (s): 1 kHz.
pub const PERIOD: f32 = 1.0e-3;

/// Samples that take the estimators past their start-up (the accelerometer's low-pass filter averages its
/// first τ = 3 s, `ceil(3 / PERIOD)` samples, before their Kalman filters run), with 100 ms to spare.
pub const WARM_UP: usize = 3_100;

/// The gyro's gain error `G` (reading = `(I + G)·ω + b`): 1 % on x, −0.5 % on y, 0.8 % on z, and
/// cross-axis terms of a few thousandths.
const GAIN: [[f32; 3]; 3] = [
    [0.01, 0.003, 0.0],
    [-0.002, -0.005, 0.004],
    [0.0, 0.001, 0.008],
];
/// The residual bias (rad/s): about 0.1 °/s per axis.
const BIAS: Vec3<f32> = Vec3::new(2.0e-3, -1.0e-3, 1.5e-3);

/// The trajectory: time, the true attitude (body to a frame whose z is up).
pub struct Motion {
    t: f32,
    q: Quat<f32>,
}

impl Default for Motion {
    fn default() -> Self {
        Self::new()
    }
}

impl Motion {
    /// At rest, level, at t = 0.
    pub fn new() -> Self {
        Self {
            t: 0.0,
            q: Quat::IDENTITY,
        }
    }

    /// The next sample: the gyro's reading (rad/s) and the accelerometer (m/s², at the sample's end). The
    /// true rate turns about every axis at up to about 1.2 rad/s (`(0.9 cos 1.1t, 0.7 sin 0.53t,
    /// 0.5 cos 0.29t + 0.2)`), so every term of the gain shows in the inclination over time.
    pub fn next_sample(&mut self) -> (Vec3<f32>, Vec3<f32>) {
        let t = self.t;
        let w = Vec3::new(
            0.9 * Real::cos(1.1 * t),
            0.7 * Real::sin(0.53 * t),
            0.5 * Real::cos(0.29 * t) + 0.2,
        );
        let q = self.q * Quat::from_rotation_vector(w * PERIOD);
        self.q = q.normalized().unwrap_or(self.q);
        self.t = t + PERIOD;
        let row = |g: [f32; 3], k: f32| k + g[0] * w.x + g[1] * w.y + g[2] * w.z;
        let reading = Vec3::new(row(GAIN[0], w.x), row(GAIN[1], w.y), row(GAIN[2], w.z)) + BIAS;
        let gravity = self.q.conjugate().rotate(Vec3::new(0.0, 0.0, 9.81));
        (reading, gravity)
    }
}
