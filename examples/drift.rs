//! f32 against f64 drift of every scheme × stabilizer over a long constant rotation.
//!
//! Run: `cargo run --release --example drift [-- --steps N] [--out DIR]` (default 10⁶ steps). Prints the
//! Markdown table; with `--out DIR` also writes it to `DIR/drift.md`. The scene: rate
//! ω = (0.36, −0.48, 0.80) rad/s (|ω| = 1) pushed through `input::Hold`, step H = 0.2 s, so `H|ω| = 0.2` as
//! in the core issue. The reference is the exact rotation for the *same* inputs the run saw (the f32-rounded
//! ω and H widened to f64), so input quantization is not counted as drift.
//!
//! Stabilizers: the post-step ones (`Off`, `Normalize`, `FirstOrder`, `Every(100)`), and for the Runge–Kutta
//! schemes the seed's Baumgarte right-hand side (`scheme::Baumgarte::new(S, k)` with `stabilize::Off`).
//!
//! `tests/drift.rs` runs the same functions and asserts the bounds derived there.

use quatprop::input::Hold;
use quatprop::scheme::{Baumgarte, Euler, Rk2, Rk3, Rk4, Rk5, Scheme, SchemeKind};
use quatprop::stabilize::{Off, Stabilizer, StabilizerKind};
use quatprop::{Error, GyroSample, Propagator, Quat, Real, Vec3};

/// The scene's rate (rad/s).
pub const RATE: Vec3<f64> = Vec3::new(0.36, -0.48, 0.80);
/// Step (s): `H|ω| = 0.2`.
pub const STEP: f64 = 0.2;
/// Baumgarte gain used in the table (the seed's Fig. 1 value), 1/s.
pub const BAUMGARTE_K: f64 = 0.5;
/// `Every(n)` interval used in the table.
pub const EVERY_N: u32 = 100;
/// Default number of steps.
pub const DEFAULT_STEPS: u64 = 1_000_000;

/// A row's stabilization: a post-step stabilizer, or Baumgarte's right-hand side (RK schemes only).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stabilization {
    /// A post-step stabilizer with the plain scheme.
    Post(StabilizerKind),
    /// `Baumgarte::new(scheme, BAUMGARTE_K)` with `stabilize::Off`.
    Baumgarte,
}

impl Stabilization {
    /// Every stabilization of the table, in order.
    pub const ALL: [Stabilization; 5] = [
        Stabilization::Post(StabilizerKind::Off),
        Stabilization::Post(StabilizerKind::Normalize),
        Stabilization::Post(StabilizerKind::FirstOrder),
        Stabilization::Post(StabilizerKind::Every(EVERY_N)),
        Stabilization::Baumgarte,
    ];

    /// The table's label.
    pub fn label(&self) -> String {
        match self {
            Stabilization::Post(StabilizerKind::Every(n)) => format!("Every({n})"),
            Stabilization::Post(z) => z.name().to_string(),
            Stabilization::Baumgarte => format!("Baumgarte(k={BAUMGARTE_K})"),
        }
    }
}

/// One run's figures.
#[derive(Clone, Copy, Debug)]
pub struct DriftRow {
    /// Steps completed before the run ended (all, unless the step failed).
    pub steps: u64,
    /// Why the run stopped early, if it did.
    pub stopped: Option<Error>,
    /// `N = |q|² − 1` at the end (accurate evaluation of the stored quaternion).
    pub final_n: f64,
    /// `max |N|` over all steps.
    pub max_abs_n: f64,
    /// Angle (rad) between the normalized final attitude and the exact one.
    pub attitude_error: f64,
    /// Step 1's N (for the Baumgarte analysis).
    pub first_n: f64,
}

/// Runs `steps` held-rate steps of the scene in precision `T` with `scheme` and `stabilizer`;
/// `observe(step, N)` sees N after every step.
pub fn run_with<T: Real, S: Scheme<T>, Z: Stabilizer>(
    scheme: S,
    stabilizer: Z,
    steps: u64,
    mut observe: impl FnMut(u64, f64),
) -> DriftRow {
    let w = Vec3::<T>::from_f64(RATE);
    let h = T::from_f64(STEP);
    let mut p = Propagator::new(Quat::<T>::IDENTITY, scheme, Hold, stabilizer)
        .expect("valid configuration");
    let mut max_abs_n: f64 = 0.0;
    let mut first_n = 0.0;
    let mut stopped = None;
    for i in 0..steps {
        if let Err(e) = p.push(GyroSample::new(w), h) {
            stopped = Some(e);
            break;
        }
        let n = p.norm_error().to_f64();
        if i == 0 {
            first_n = n;
        }
        max_abs_n = max_abs_n.max(n.abs());
        observe(i + 1, n);
    }
    // Exact attitude for the inputs actually used: rotation by |ω| t about ω, with t = steps · h.
    let done = p.steps();
    let t = done as f64 * h.to_f64();
    let exact = exact_rotation(w.to_f64(), t);
    let attitude_error = match p.attitude().to_f64().normalized() {
        Some(u) => u.angle_to(exact),
        None => f64::NAN,
    };
    DriftRow {
        steps: done,
        stopped,
        final_n: p.norm_error().to_f64(),
        max_abs_n,
        attitude_error,
        first_n,
    }
}

/// The row of `scheme` × `stabilization`, or `None` where Baumgarte does not apply (the exponential maps).
pub fn run<T: Real>(
    scheme: SchemeKind,
    stabilization: Stabilization,
    steps: u64,
    observe: impl FnMut(u64, f64),
) -> Option<DriftRow> {
    let k = T::from_f64(BAUMGARTE_K);
    fn b<S>(e: Result<S, Error>) -> S {
        e.expect("valid gain")
    }
    match stabilization {
        Stabilization::Post(z) => Some(run_with::<T, _, _>(scheme, z, steps, observe)),
        Stabilization::Baumgarte => match scheme {
            SchemeKind::Euler => Some(run_with(b(Baumgarte::new(Euler, k)), Off, steps, observe)),
            SchemeKind::Rk2 => Some(run_with(b(Baumgarte::new(Rk2, k)), Off, steps, observe)),
            SchemeKind::Rk3 => Some(run_with(b(Baumgarte::new(Rk3, k)), Off, steps, observe)),
            SchemeKind::Rk4 => Some(run_with(b(Baumgarte::new(Rk4, k)), Off, steps, observe)),
            SchemeKind::Rk5 => Some(run_with(b(Baumgarte::new(Rk5, k)), Off, steps, observe)),
            SchemeKind::ExpMap | SchemeKind::Magnus4 | SchemeKind::Cf4 => None,
        },
    }
}

/// `exp_q(ω t)` with the angle reduced modulo 4π first (the quaternion's period), so a long horizon keeps
/// f64 accuracy: |ω| t is formed once in f64.
pub fn exact_rotation(w: Vec3<f64>, t: f64) -> Quat<f64> {
    let speed = w.norm();
    let angle = (speed * t) % (4.0 * core::f64::consts::PI);
    Quat::from_axis_angle(w, angle).unwrap_or(Quat::IDENTITY)
}

fn fmt_row(r: &DriftRow) -> String {
    if let Some(e) = r.stopped {
        let why = match e {
            Error::NonFiniteResult => "overflow".to_string(),
            other => format!("{other:?}"),
        };
        return format!("stopped: step {} refused ({why}) | – | –", r.steps + 1);
    }
    format!(
        "{:+.2e} | {:.2e} | {:.2e}",
        r.final_n, r.max_abs_n, r.attitude_error
    )
}

/// The whole table as Markdown (heading lines, conditions, rows).
pub fn table(steps: u64) -> String {
    let mut s = String::new();
    s.push_str(&format!(
        "Constant rate ω = ({}, {}, {}) rad/s (|ω| = 1 rad/s) through `input::Hold`, step H = {STEP} s \
         (H|ω| = {STEP} rad), {steps} steps from the identity; Baumgarte k = {BAUMGARTE_K} 1/s (with \
         `stabilize::Off`, Runge–Kutta schemes only), `Every({EVERY_N})`.\n\n",
        RATE.x, RATE.y, RATE.z
    ));
    s.push_str(
        "N = |q|² − 1 of the stored quaternion (dimensionless); attitude error = angle (rad) between the \
         normalized final attitude and the exact rotation for the same (f32-rounded) inputs. A run that a \
         step refused stops there; the row says which step and why.\n\n",
    );
    s.push_str("| scheme | stabilizer | f32 N final | f32 max abs N | f32 attitude err (rad) | f64 N final | f64 max abs N | f64 attitude err (rad) |\n");
    s.push_str("|---|---|---|---|---|---|---|---|\n");
    for m in SchemeKind::ALL {
        for z in Stabilization::ALL {
            let (Some(r32), Some(r64)) = (
                run::<f32>(m, z, steps, |_, _| {}),
                run::<f64>(m, z, steps, |_, _| {}),
            ) else {
                continue;
            };
            s.push_str(&format!(
                "| {} | {} | {} | {} |\n",
                m.information().name,
                z.label(),
                fmt_row(&r32),
                fmt_row(&r64)
            ));
        }
    }
    s
}

#[path = "support/page.rs"]
#[allow(dead_code)]
mod page;

#[allow(dead_code)]
fn main() {
    page::run(
        "drift",
        DEFAULT_STEPS,
        "f32 against f64 drift, every scheme × stabilizer",
        table,
    );
}
