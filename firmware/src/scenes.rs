//! The smoke scenes, shared verbatim by the firmware (`src/bin/smoke.rs`) and the host snapshot test
//! (`tests/firmware_snapshot.rs` includes this file), so both run the same f32 arithmetic.
//!
//! Everything here is plain f32 arithmetic plus quatprop; the coning rates come from a rotation recurrence,
//! not from `sin`/`cos`, so no math library takes part in generating the inputs.

use quatprop::scheme::Method;
use quatprop::stabilize::Policy;
use quatprop::{Propagator, Quat, Vec3};

/// Steps per run.
pub const STEPS: u32 = 100_000;
/// Step (s): a 1 kHz gyro.
pub const DT: f32 = 1.0e-3;

/// The scenes of the smoke run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scene {
    /// Constant rate ω = (0.36, −0.48, 0.80)·2 rad/s, `step_hold`.
    Constant,
    /// Coning α = 0.3 rad at 5 Hz, samples at both step ends, `step_linear`.
    ConingLinear,
    /// The same coning with a sample in the middle of each step (gyro at 2 kHz), `step_mid`.
    ConingMid,
}

impl Scene {
    /// All scenes.
    pub const ALL: [Scene; 3] = [Scene::Constant, Scene::ConingLinear, Scene::ConingMid];

    /// Short label.
    pub fn name(self) -> &'static str {
        match self {
            Scene::Constant => "constant",
            Scene::ConingLinear => "coning-linear",
            Scene::ConingMid => "coning-mid",
        }
    }
}

/// The stabilizers of the smoke run.
pub const POLICIES: [Policy<f32>; 5] = [
    Policy::Off,
    Policy::Normalize,
    Policy::FirstOrder,
    Policy::Every(16),
    Policy::Baumgarte { k: 0.5 },
];

/// Label of a policy.
pub fn policy_name(p: Policy<f32>) -> &'static str {
    p.name()
}

/// Coning body rate ω(t) = (−Ω sin α sin Ωt, Ω sin α cos Ωt, −2Ω sin²(α/2)), α = 0.3, Ω = 2π·5 rad/s,
/// with (cos Ωt, sin Ωt) advanced by a rotation recurrence in f32 every half step.
pub struct ConingRates {
    c: f32,
    s: f32,
}

/// Ω sin α (rad/s) for α = 0.3, Ω = 10π.
const CONE_AMPLITUDE: f32 = 9.284_041;
/// −2Ω sin²(α/2) (rad/s).
const CONE_AXIAL: f32 = -1.403_145_6;
/// cos and sin of Ω·DT/2 = 10π·0.0005 rad.
const HALF_STEP_COS: f32 = 0.999_876_6;
const HALF_STEP_SIN: f32 = 0.015_707_317;

impl ConingRates {
    /// Starts at t = 0.
    pub fn new() -> Self {
        Self { c: 1.0, s: 0.0 }
    }

    /// The rate at the current time.
    pub fn rate(&self) -> Vec3<f32> {
        Vec3::new(
            -CONE_AMPLITUDE * self.s,
            CONE_AMPLITUDE * self.c,
            CONE_AXIAL,
        )
    }

    /// Advances by half a step.
    pub fn advance_half(&mut self) {
        let c = self.c * HALF_STEP_COS - self.s * HALF_STEP_SIN;
        let s = self.s * HALF_STEP_COS + self.c * HALF_STEP_SIN;
        self.c = c;
        self.s = s;
    }
}

impl Default for ConingRates {
    fn default() -> Self {
        Self::new()
    }
}

/// What a run ends with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outcome {
    /// Final attitude.
    pub q: Quat<f32>,
    /// Steps taken.
    pub steps: u64,
    /// Corrections applied by the stabilizer.
    pub corrections: u64,
    /// Steps refused (expected zero in these scenes).
    pub refused: u32,
}

/// Runs one scene with one scheme and stabilizer for `steps` steps from the identity.
pub fn run(scene: Scene, method: Method, policy: Policy<f32>, steps: u32) -> Outcome {
    let mut p = match Propagator::new(Quat::IDENTITY, method, policy) {
        Ok(p) => p,
        Err(_) => {
            return Outcome {
                q: Quat::ZERO,
                steps: 0,
                corrections: 0,
                refused: steps,
            }
        }
    };
    let mut refused = 0;
    let constant = Vec3::new(0.72_f32, -0.96, 1.6);
    let mut cone = ConingRates::new();
    for _ in 0..steps {
        let r = match scene {
            Scene::Constant => p.step_hold(constant, DT),
            Scene::ConingLinear => {
                let w0 = cone.rate();
                cone.advance_half();
                cone.advance_half();
                p.step_linear(w0, cone.rate(), DT)
            }
            Scene::ConingMid => {
                let w0 = cone.rate();
                cone.advance_half();
                let wm = cone.rate();
                cone.advance_half();
                p.step_mid(w0, wm, cone.rate(), DT)
            }
        };
        if r.is_err() {
            refused += 1;
        }
    }
    Outcome {
        q: p.attitude(),
        steps: p.steps(),
        corrections: p.corrections(),
        refused,
    }
}

/// Canonical bit pattern of an f32 (one NaN pattern for every NaN: ARM and x86 default NaNs differ).
pub fn bits(v: f32) -> u32 {
    if v.is_nan() {
        0x7fc0_0000
    } else {
        v.to_bits()
    }
}
