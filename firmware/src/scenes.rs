//! The smoke scenes and the quick start's sample stream, shared verbatim by the firmware (`src/bin/smoke.rs`,
//! `src/bin/isr.rs`, `src/bin/quickstart.rs`) and the host snapshot test (`tests/firmware_snapshot.rs`
//! includes this file), so both run the same f32 arithmetic.
//!
//! Everything here is plain f32 arithmetic plus quatprop; the coning rates come from a rotation recurrence,
//! not from `sin`/`cos`, so no math library takes part in generating the inputs. Samples reach the propagator
//! through the input models, one `push` per sensor sample.

use quatprop::input::{History, Hold, InputModel, Linear, TwiceRate};
use quatprop::scheme::{Baumgarte, Euler, Rk2, Rk3, Rk4, Rk5, Scheme, SchemeKind};
use quatprop::stabilize::{Off, Stabilizer, StabilizerKind};
use quatprop::{GyroSample, Propagator, Quat, Vec3};

/// Steps per run on the boards with a hardware FPU (and on the host).
pub const STEPS: u32 = 100_000;
/// Steps per run on the soft-float boards (Cortex-M3 and M0), which emulate every float operation in
/// software: the same runs, shorter, to keep CI's time (`firmware/expected/smoke-soft.txt`).
pub const STEPS_SOFT: u32 = 20_000;
/// Steps of the interrupt-driven run (`src/bin/isr.rs`).
pub const ISR_STEPS: u32 = 2_000;
/// Sample period (s): a 1 kHz gyro (TwiceRate: two samples of `DT / 2` per step).
pub const DT: f32 = 1.0e-3;
/// Baumgarte's gain k (1/s) in the smoke runs.
pub const BAUMGARTE_K: f32 = 0.5;

/// The scenes of the smoke run: the same body motion fed through different input models.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scene {
    /// Constant rate ω = (0.36, −0.48, 0.80)·2 rad/s, one `Hold` sample per step.
    Constant,
    /// Coning α = 0.3 rad at 5 Hz, `Linear`: the rate linear between consecutive 1 kHz samples.
    ConingLinear,
    /// The same coning with the gyro at 2 kHz, `TwiceRate`: start, middle, end of every step.
    ConingTwiceRate,
    /// The same coning at 1 kHz through `History` (cubic through the last four samples).
    ConingHistory,
}

impl Scene {
    /// All scenes.
    pub const ALL: [Scene; 4] = [
        Scene::Constant,
        Scene::ConingLinear,
        Scene::ConingTwiceRate,
        Scene::ConingHistory,
    ];

    /// Short label.
    pub fn name(self) -> &'static str {
        match self {
            Scene::Constant => "constant",
            Scene::ConingLinear => "coning-linear",
            Scene::ConingTwiceRate => "coning-twice-rate",
            Scene::ConingHistory => "coning-history",
        }
    }

    /// Pushes that make `steps` steps (the first sample of Linear/TwiceRate/History only starts the model).
    pub fn pushes(self, steps: u32) -> u32 {
        match self {
            Scene::Constant => steps,
            Scene::ConingLinear | Scene::ConingHistory => steps + 1,
            Scene::ConingTwiceRate => 2 * steps + 1,
        }
    }
}

/// The post-step stabilizers of the smoke run (every scheme runs with each).
pub const STABILIZERS: [StabilizerKind; 4] = [
    StabilizerKind::Off,
    StabilizerKind::Normalize,
    StabilizerKind::FirstOrder,
    StabilizerKind::Every(16),
];

/// The Runge–Kutta schemes that also run with Baumgarte's right-hand side (k = [`BAUMGARTE_K`], stabilizer Off).
pub const BAUMGARTE_SCHEMES: [SchemeKind; 5] = [
    SchemeKind::Euler,
    SchemeKind::Rk2,
    SchemeKind::Rk3,
    SchemeKind::Rk4,
    SchemeKind::Rk5,
];

/// One smoke configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Config {
    /// A scheme with a post-step stabilizer (both chosen at run time).
    Post(SchemeKind, StabilizerKind),
    /// A Runge–Kutta scheme with Baumgarte's term (k = [`BAUMGARTE_K`]), stabilizer Off.
    Baumgarte(SchemeKind),
}

impl Config {
    /// Every configuration of the smoke run, in output order: each scheme × each post-step stabilizer, then
    /// Baumgarte on each Runge–Kutta scheme.
    pub fn all() -> impl Iterator<Item = Config> {
        SchemeKind::ALL
            .into_iter()
            .flat_map(|s| STABILIZERS.into_iter().map(move |z| Config::Post(s, z)))
            .chain(BAUMGARTE_SCHEMES.into_iter().map(Config::Baumgarte))
    }

    /// Number of configurations.
    pub const COUNT: usize = SchemeKind::ALL.len() * STABILIZERS.len() + BAUMGARTE_SCHEMES.len();

    /// The scheme's label (`Rk4`, or `Rk4+Baumgarte` for the stabilized right-hand side).
    pub fn scheme_name(self) -> &'static str {
        match self {
            Config::Post(s, _) => Scheme::<f32>::information(&s).name,
            Config::Baumgarte(s) => match s {
                SchemeKind::Euler => "Euler+Baumgarte",
                SchemeKind::Rk2 => "Rk2+Baumgarte",
                SchemeKind::Rk3 => "Rk3+Baumgarte",
                SchemeKind::Rk4 => "Rk4+Baumgarte",
                SchemeKind::Rk5 => "Rk5+Baumgarte",
                _ => "?+Baumgarte",
            },
        }
    }

    /// The post-step stabilizer's label.
    pub fn stabilizer_name(self) -> &'static str {
        match self {
            Config::Post(_, z) => z.name(),
            Config::Baumgarte(_) => "Off",
        }
    }
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

    /// Advances by a whole step (two half steps, as every scene does).
    pub fn advance(&mut self) {
        self.advance_half();
        self.advance_half();
    }
}

impl Default for ConingRates {
    fn default() -> Self {
        Self::new()
    }
}

/// The sensor samples of a scene, each with the time since the previous one.
pub struct Feed {
    scene: Scene,
    cone: ConingRates,
    started: bool,
}

impl Feed {
    /// The samples of `scene` from t = 0.
    pub fn new(scene: Scene) -> Self {
        Self {
            scene,
            cone: ConingRates::new(),
            started: false,
        }
    }

    /// The next sample and its `dt` (s).
    pub fn next_sample(&mut self) -> (GyroSample<f32>, f32) {
        let first = !self.started;
        self.started = true;
        match self.scene {
            Scene::Constant => (GyroSample::new(Vec3::new(0.72_f32, -0.96, 1.6)), DT),
            Scene::ConingLinear | Scene::ConingHistory => {
                if !first {
                    self.cone.advance();
                }
                (GyroSample::new(self.cone.rate()), DT)
            }
            Scene::ConingTwiceRate => {
                if !first {
                    self.cone.advance_half();
                }
                (GyroSample::new(self.cone.rate()), 0.5 * DT)
            }
        }
    }
}

/// What a run ends with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outcome {
    /// Final attitude.
    pub q: Quat<f32>,
    /// Steps taken.
    pub steps: u64,
    /// Corrections applied by the post-step stabilizer.
    pub corrections: u64,
    /// Samples refused (expected zero in these scenes).
    pub refused: u32,
}

impl Outcome {
    fn failed(refused: u32) -> Self {
        Self {
            q: Quat::ZERO,
            steps: 0,
            corrections: 0,
            refused,
        }
    }
}

/// Pushes the scene's samples into `p`.
fn drive<S, I, Z>(mut p: Propagator<f32, S, I, Z>, scene: Scene, steps: u32) -> Outcome
where
    S: Scheme<f32>,
    I: InputModel<f32, Sample = GyroSample<f32>>,
    Z: Stabilizer,
{
    let mut feed = Feed::new(scene);
    let mut refused = 0;
    for _ in 0..scene.pushes(steps) {
        let (sample, dt) = feed.next_sample();
        if p.push(sample, dt).is_err() {
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

/// Runs `scheme` + `stabilizer` on `scene` with the scene's input model for `steps` steps from the identity.
pub fn run_with<S: Scheme<f32>, Z: Stabilizer>(
    scene: Scene,
    scheme: S,
    stabilizer: Z,
    steps: u32,
) -> Outcome {
    let q0 = Quat::IDENTITY;
    let built =
        match scene {
            Scene::Constant => {
                Propagator::new(q0, scheme, Hold, stabilizer).map(|p| drive(p, scene, steps))
            }
            Scene::ConingLinear => Propagator::new(q0, scheme, Linear::new(), stabilizer)
                .map(|p| drive(p, scene, steps)),
            Scene::ConingTwiceRate => Propagator::new(q0, scheme, TwiceRate::new(), stabilizer)
                .map(|p| drive(p, scene, steps)),
            Scene::ConingHistory => Propagator::new(q0, scheme, History::new(), stabilizer)
                .map(|p| drive(p, scene, steps)),
        };
    built.unwrap_or(Outcome::failed(scene.pushes(steps)))
}

/// The fixed-point propagator's run: the scene's 1 kHz rates (constant, or the coning of the Linear and
/// History scenes) as a ±2000 °/s gyro's counts (f32, truncated toward zero), `steps` steps from the
/// identity. Returns the Q30 attitude and the steps taken (`None` if a sample was refused).
pub fn run_fixed(scene: Scene, steps: u32) -> Option<([i32; 4], u64)> {
    let rad_per_count = 2000.0_f32 / 32768.0 * (core::f32::consts::PI / 180.0);
    let mut p = quatprop::fixed::Q30Propagator::new(Quat::IDENTITY, rad_per_count, DT).ok()?;
    let scene = match scene {
        Scene::ConingTwiceRate => Scene::ConingHistory,
        s => s,
    };
    let mut feed = Feed::new(scene);
    for _ in 0..=steps {
        let (s, _) = feed.next_sample();
        let w = s.rate * (1.0 / rad_per_count);
        p.push([w.x as i16, w.y as i16, w.z as i16]).ok()?;
    }
    Some((p.attitude_q30(), p.steps()))
}

/// Runs one smoke configuration on one scene for `steps` steps from the identity.
pub fn run(scene: Scene, config: Config, steps: u32) -> Outcome {
    fn baumgarte<S: Scheme<f32> + quatprop::scheme::RungeKutta>(
        scene: Scene,
        s: S,
        steps: u32,
    ) -> Outcome {
        match Baumgarte::new(s, BAUMGARTE_K) {
            Ok(b) => run_with(scene, b, Off, steps),
            Err(_) => Outcome::failed(scene.pushes(steps)),
        }
    }
    match config {
        Config::Post(s, z) => run_with(scene, s, z, steps),
        Config::Baumgarte(s) => match s {
            SchemeKind::Euler => baumgarte(scene, Euler, steps),
            SchemeKind::Rk2 => baumgarte(scene, Rk2, steps),
            SchemeKind::Rk3 => baumgarte(scene, Rk3, steps),
            SchemeKind::Rk4 => baumgarte(scene, Rk4, steps),
            SchemeKind::Rk5 => baumgarte(scene, Rk5, steps),
            _ => Outcome::failed(scene.pushes(steps)),
        },
    }
}

/// FIFO bursts in the quick start's stream, and samples per burst (1 kHz).
pub const QUICKSTART_BURSTS: u32 = 400;
/// Samples per FIFO burst.
pub const QUICKSTART_BURST: usize = 25;
/// Bursts at the start during which the sensor is still (bias only).
pub const QUICKSTART_STILL_BURSTS: u32 = 80;

/// The quick start's input: [`QUICKSTART_BURSTS`] bursts of raw 16-bit counts from a ±2000 °/s gyro at
/// 1 kHz: 2 s still with a bias of (12, −3, 7) counts, then coning (the rotation recurrence above) in
/// sensor axes, truncated to counts in f32 arithmetic.
pub fn quickstart_fifo() -> impl Iterator<Item = [[i16; 3]; QUICKSTART_BURST]> {
    // Counts per rad/s at ±2000 °/s: 32768 / (2000 π / 180).
    const COUNTS_PER_RAD_S: f32 = 938.734_6;
    const BIAS: [i16; 3] = [12, -3, 7];
    let mut cone = ConingRates::new();
    (0..QUICKSTART_BURSTS).map(move |k| {
        let mut burst = [BIAS; QUICKSTART_BURST];
        if k >= QUICKSTART_STILL_BURSTS {
            for slot in burst.iter_mut() {
                cone.advance();
                let w = cone.rate();
                // Body x = sensor y, body y = −sensor x (AxisRemap::PyNxPz): sensor = (−body y, body x, z).
                let sensor = [-w.y, w.x, w.z];
                for (c, (&r, b)) in slot.iter_mut().zip(sensor.iter().zip(BIAS)) {
                    *c = (r * COUNTS_PER_RAD_S) as i16 + b;
                }
            }
        }
        burst
    })
}

/// Canonical bit pattern of an f32 (one NaN pattern for every NaN: ARM and x86 default NaNs differ).
pub fn bits(v: f32) -> u32 {
    if v.is_nan() {
        0x7fc0_0000
    } else {
        v.to_bits()
    }
}
