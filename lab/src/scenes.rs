//! The synthetic scenes (attitude q(t) and body rate ω(t) in closed form) and the catalogue of every scene
//! of the lab: these, the rigid bodies (`rigid_body.rs`) and the recorded motion (`recorded.rs`). What a
//! scene is: `scene.rs`.

use crate::recorded::RecordedMotion;
use crate::rigid_body::RigidBody;
use crate::scene::{Scene, Sweep, DEFAULT_SWEEP};
use quatprop::{Quat, Vec3};

fn exp_q(v: Vec3<f64>) -> Quat<f64> {
    Quat::from_rotation_vector(v)
}

/// Coning α = 0.3 rad at 1 Hz.
pub struct Coning;
// Each scene names itself through the `Scene` trait's methods, spelled out in each impl.
impl Scene for Coning {
    fn key(&self) -> &'static str {
        "coning"
    }
    fn name(&self) -> &'static str {
        "coning 0.3 rad, 1 Hz"
    }
    fn attitude(&self, t: f64) -> Quat<f64> {
        let (s, c) = (0.15f64).sin_cos();
        let p = 2.0 * core::f64::consts::PI * t;
        Quat::new(c, s * p.cos(), s * p.sin(), 0.0)
    }
    fn rate(&self, t: f64) -> Vec3<f64> {
        let o = 2.0 * core::f64::consts::PI;
        let p = o * t;
        let s2 = (0.15f64).sin();
        Vec3::new(
            -o * 0.3f64.sin() * p.sin(),
            o * 0.3f64.sin() * p.cos(),
            -2.0 * o * s2 * s2,
        )
    }
}

/// `q(t) = exp_q(a t) ⊗ q0 ⊗ exp_q(b t)`: a inertial, b body (constant). Its body rate is
/// `ω(t) = R(q0 ⊗ exp_q(b t))ᵀ a + b`. With a along the inertial z and b along the body z this is the
/// torque-free symmetric top in regular precession.
pub struct Sandwich {
    pub key: &'static str,
    pub name: &'static str,
    pub sweep: Sweep,
    pub a: Vec3<f64>,
    pub b: Vec3<f64>,
    pub q0: Quat<f64>,
}
impl Scene for Sandwich {
    fn key(&self) -> &'static str {
        self.key
    }
    fn name(&self) -> &'static str {
        self.name
    }
    fn sweep(&self) -> Sweep {
        self.sweep
    }
    fn attitude(&self, t: f64) -> Quat<f64> {
        exp_q(self.a * t) * self.q0 * exp_q(self.b * t)
    }
    fn rate(&self, t: f64) -> Vec3<f64> {
        let r = self.q0 * exp_q(self.b * t);
        r.conjugate().rotate(self.a) + self.b
    }
}

/// Symmetric top: precession 0.7 rad/s about the inertial z, spin 3 rad/s about the body z, nutation 0.5 rad.
pub fn symmetric_top() -> Sandwich {
    Sandwich {
        key: "top",
        name: "symmetric top (regular precession)",
        sweep: DEFAULT_SWEEP,
        a: Vec3::new(0.0, 0.0, 0.7),
        b: Vec3::new(0.0, 0.0, 3.0),
        q0: Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.5).unwrap(),
    }
}

/// 2000 °/s about the body x axis while the body cones: a fast roll with coning (the Betaflight case).
pub fn fast_spin() -> Sandwich {
    Sandwich {
        key: "spin2000",
        name: "2000 deg/s roll with coning",
        sweep: Sweep {
            horizon: 5.37,
            rates: &[500, 1000, 2000, 4000, 8000, 16000],
        },
        a: Vec3::new(0.0, 0.0, 2.0),
        b: Vec3::new(2000f64.to_radians(), 0.0, 0.0),
        q0: Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), 0.3).unwrap(),
    }
}

/// 10⁴ rad/s about the body x axis (a spin-stabilized projectile or a flywheel), precessing at 1 rad/s:
/// H|ω| from 5 at 2 kHz to 0.1 at 100 kHz, through every Runge–Kutta stability bound.
pub fn spin_1e4() -> Sandwich {
    Sandwich {
        key: "spin1e4",
        name: "1e4 rad/s spin, precessing",
        sweep: Sweep {
            horizon: 0.2037,
            rates: &[2000, 5000, 10_000, 20_000, 50_000, 100_000],
        },
        a: Vec3::new(0.0, 0.0, 1.0),
        b: Vec3::new(1.0e4, 0.0, 0.0),
        q0: Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), 0.3).unwrap(),
    }
}

/// A random smooth motion: `q(t) = exp_q(φ(t))` with each component of the rotation vector φ a sum of four
/// sinusoids of random frequency (0.05 to 0.8 Hz), amplitude and phase (a fixed seed), scaled so that
/// |φ'| ≤ 1.5 rad/s per axis: |ω| ≤ |φ'| ≤ 2.6 rad/s. Exact: the body rate is `J_r(φ) φ'` with the right
/// Jacobian of the exponential map, `J_r(φ) = I − (1 − cos θ)/θ² [φ]× + (θ − sin θ)/θ³ [φ]×²`, θ = |φ|.
pub struct RandomSmooth {
    /// Per axis: (amplitude (rad), angular frequency (rad/s), phase (rad)) of each sinusoid.
    terms: [[(f64, f64, f64); 4]; 3],
}

impl RandomSmooth {
    pub fn new() -> Self {
        let mut rng = crate::rng::Rng(0x005E_ED0F_5A00_7E00);
        let mut terms = [[(0.0, 0.0, 0.0); 4]; 3];
        for axis in &mut terms {
            let mut raw = [(0.0, 0.0, 0.0); 4];
            for t in &mut raw {
                let f = 0.05 + 0.75 * rng.uniform();
                *t = (
                    0.2 + rng.uniform(),
                    2.0 * core::f64::consts::PI * f,
                    2.0 * core::f64::consts::PI * rng.uniform(),
                );
            }
            // Σ amplitude·frequency = 1.5 rad/s: the bound on |φ'| per axis.
            let peak: f64 = raw.iter().map(|&(a, w, _)| a * w).sum();
            for (t, r) in axis.iter_mut().zip(raw) {
                *t = (r.0 * 1.5 / peak, r.1, r.2);
            }
        }
        Self { terms }
    }

    /// φ(t) and φ'(t).
    fn phi(&self, t: f64) -> (Vec3<f64>, Vec3<f64>) {
        let mut p = [0.0; 3];
        let mut d = [0.0; 3];
        for (i, axis) in self.terms.iter().enumerate() {
            for &(a, w, ph) in axis {
                let (s, c) = (w * t + ph).sin_cos();
                p[i] += a * s;
                d[i] += a * w * c;
            }
        }
        (Vec3::new(p[0], p[1], p[2]), Vec3::new(d[0], d[1], d[2]))
    }
}

impl Default for RandomSmooth {
    fn default() -> Self {
        Self::new()
    }
}

impl Scene for RandomSmooth {
    fn key(&self) -> &'static str {
        "random"
    }
    fn name(&self) -> &'static str {
        "random smooth motion, up to 2.6 rad/s"
    }
    fn attitude(&self, t: f64) -> Quat<f64> {
        exp_q(self.phi(t).0)
    }
    fn rate(&self, t: f64) -> Vec3<f64> {
        let (p, d) = self.phi(t);
        let th = p.norm();
        // (1 − cos θ)/θ² = 2 sin²(θ/2)/θ² (no cancellation); (θ − sin θ)/θ³ by its series below 0.1 rad
        // (first omitted term θ⁸/39916800 < 3e-16).
        let c1 = if th < 1e-8 {
            0.5
        } else {
            let s = (0.5 * th).sin();
            2.0 * s * s / (th * th)
        };
        let c2 = if th < 0.1 {
            let t2 = th * th;
            1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0 - t2 * t2 * t2 / 362_880.0
        } else {
            (th - th.sin()) / (th * th * th)
        };
        let pxd = p.cross(d);
        d - pxd * c1 + p.cross(pxd) * c2
    }
}

/// A rate step: at rest, then 5 rad/s about a fixed body axis from t = 0.5037 s (inside a step).
pub struct RateStep;
const STEP_AT: f64 = 0.5037;
impl Scene for RateStep {
    fn key(&self) -> &'static str {
        "step"
    }
    fn name(&self) -> &'static str {
        "rate step 0 to 5 rad/s"
    }
    fn attitude(&self, t: f64) -> Quat<f64> {
        let w = Vec3::new(0.36, -0.48, 0.8) * 5.0;
        exp_q(w * (t - STEP_AT).max(0.0))
    }
    fn rate(&self, t: f64) -> Vec3<f64> {
        if t < STEP_AT {
            Vec3::ZERO
        } else {
            Vec3::new(0.36, -0.48, 0.8) * 5.0
        }
    }
}

/// Idle with Earth rate only (7.29e-5 rad/s about a tilted axis): nothing may be dropped.
pub struct EarthRate;
impl Scene for EarthRate {
    fn key(&self) -> &'static str {
        "earth"
    }
    fn name(&self) -> &'static str {
        "idle, Earth rate only"
    }
    fn attitude(&self, t: f64) -> Quat<f64> {
        exp_q(Vec3::new(0.0, 0.6, 0.8) * (7.292_115e-5 * t))
    }
    fn rate(&self, _t: f64) -> Vec3<f64> {
        Vec3::new(0.0, 0.6, 0.8) * 7.292_115e-5
    }
}

/// Every scene of the lab, the rigid bodies' references tabulated up to `horizon` (s).
pub fn catalogue(horizon: f64) -> Vec<Box<dyn Scene>> {
    vec![
        Box::new(Coning),
        Box::new(symmetric_top()),
        Box::new(RigidBody::asymmetric(horizon)),
        Box::new(RigidBody::dzhanibekov(horizon)),
        Box::new(fast_spin()),
        Box::new(spin_1e4()),
        Box::new(RateStep),
        Box::new(EarthRate),
        Box::new(RandomSmooth::new()),
        Box::new(RecordedMotion::broad()),
        Box::new(RecordedMotion::broad_low_passed()),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every scene's rate is its attitude's body rate: ω = 2 q* ⊗ q' (central differences).
    #[test]
    fn rates_are_the_attitudes_body_rates() {
        let scenes: Vec<Box<dyn Scene>> = vec![
            Box::new(Coning),
            Box::new(symmetric_top()),
            Box::new(fast_spin()),
            Box::new(spin_1e4()),
            Box::new(EarthRate),
            Box::new(RandomSmooth::new()),
        ];
        for s in &scenes {
            for &t in &[0.1, 0.77, 3.3] {
                // Difference step scaled to the rate: the central difference's truncation is (|ω|d)²/6.
                let d = 1e-6 / (s.rate(t).norm() / 100.0).max(1.0);
                let dq = (s.attitude(t + d) - s.attitude(t - d)) * (0.5 / d);
                let w = s.attitude(t).conjugate() * dq * 2.0;
                let r = s.rate(t);
                let err = (w.vector() - r).norm() / r.norm().max(1e-9);
                assert!(
                    err < 1e-6 && w.w.abs() < 1e-6 * r.norm().max(1.0),
                    "{}: {err:e}",
                    s.name()
                );
            }
        }
    }
}
