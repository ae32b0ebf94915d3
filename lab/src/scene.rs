//! What a scene is: a motion with an exact reference, attitude q(t) and body rate ω(t) ([`Scene`]), and what
//! every scene shares: its work-precision sweep ([`Sweep`]), its sample stream at a rate ([`stream`]), the
//! attitude error against its reference ([`attitude_error`]), and the Gauss-point step ([`gauss_step`]) the
//! scenes without a closed-form attitude integrate their references with. The scenes themselves: `scenes.rs`
//! (and its catalogue), `rigid_body.rs`, `recorded.rs`.

use crate::sample::Sample;
use quatprop::input::GaussPoints;
use quatprop::scheme::Scheme;
use quatprop::stabilize::Stabilizer;
use quatprop::{Error, GyroSample, Propagator, Quat, Real, Vec3};

/// A motion with an exact attitude and body rate.
pub trait Scene {
    /// Short name for the command line (`--scene`).
    fn key(&self) -> &'static str;
    fn name(&self) -> &'static str;
    fn attitude(&self, t: f64) -> Quat<f64>;
    fn rate(&self, t: f64) -> Vec3<f64>;
    /// What the scene needs in a work-precision sweep: horizon (s) and gyro sample rates (Hz).
    fn sweep(&self) -> Sweep {
        DEFAULT_SWEEP
    }
}

/// A scene's work-precision sweep: horizon (s) and gyro sample rates (Hz).
#[derive(Clone, Copy, Debug)]
pub struct Sweep {
    pub horizon: f64,
    pub rates: &'static [u32],
}

/// The default sweep: 20.37 s (not a whole number of any scene's periods) at 100 Hz to 4 kHz.
pub const DEFAULT_SWEEP: Sweep = Sweep {
    horizon: 20.37,
    rates: &[100, 200, 500, 1000, 2000, 4000],
};

/// `√3/6` to the digits of the library's own constant (`src/gauss.rs`, crate-private since quatprop 0.2's
/// surface review).
const HALF_GAP: f64 = 0.288_675_134_594_812_9;

/// The two-point Gauss–Legendre nodes `½ ∓ √3/6` as fractions of a step, where `input::GaussPoints` wants
/// its samples.
pub const GAUSS_NODES: [f64; 2] = [0.5 - HALF_GAP, 0.5 + HALF_GAP];

/// One reference step of `h` (s) through a Gauss-point propagator: the rates `rate(c)` at the two nodes
/// (`c` the fraction of the step), each pushed with dt = h/2; the second push closes the step.
pub fn gauss_step<S: Scheme<f64>, Z: Stabilizer>(
    p: &mut Propagator<f64, S, GaussPoints<f64>, Z>,
    rate: impl Fn(f64) -> Vec3<f64>,
    h: f64,
) -> Result<(), Error> {
    p.push(GyroSample::new(rate(GAUSS_NODES[0])), 0.5 * h)?;
    p.push(GyroSample::new(rate(GAUSS_NODES[1])), 0.5 * h)
}

/// Attitude error (rad) of a possibly non-unit quaternion against the exact attitude.
pub fn attitude_error<T: Real>(q: Quat<T>, exact: Quat<f64>) -> f64 {
    q.to_f64()
        .normalized()
        .map_or(f64::NAN, |u| u.angle_to(exact))
}

/// The stream of a scene at `hz`: samples ω(t_k) at t_k = k·dt with dt the precision's own value of 1/hz (so
/// dt's rounding is not counted as integration error), and `n` (even) sample intervals.
pub fn stream<T: Real>(scene: &dyn Scene, hz: u32, horizon: f64) -> (Vec<Sample<T>>, f64) {
    let n = 2 * ((horizon * hz as f64) / 2.0).round().max(1.0) as usize;
    let dt = T::from_f64(1.0 / hz as f64);
    let dt64 = dt.to_f64();
    let samples = (0..=n)
        .map(|k| Sample {
            w: Vec3::<T>::from_f64(scene.rate(k as f64 * dt64)),
            dt,
        })
        .collect();
    (samples, dt64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The nodes are the two-point Gauss–Legendre rule's: it integrates t³ exactly on [0, 1], and they lie
    /// 1/√3 apart, symmetric about ½.
    #[test]
    fn gauss_nodes_integrate_cubics_exactly() {
        let [c1, c2] = GAUSS_NODES;
        assert!((0.5 * (c1.powi(3) + c2.powi(3)) - 0.25).abs() < 1e-16);
        assert!((3f64.sqrt() * (c2 - c1) - 1.0).abs() < 1e-15);
        assert_eq!(c1 + c2, 1.0);
    }
}
