//! f32 against f64 drift of every scheme × stabilizer over a long constant rotation.
//!
//! Run: `cargo run --release --example drift [-- --steps N]` (default 10⁶ steps). Prints the Markdown table
//! that README.md shows. The scene: rate ω = (0.36, −0.48, 0.80) rad/s (|ω| = 1) held, step H = 0.2 s, so
//! `H|ω| = 0.2` as in the core issue. The reference is the exact rotation for the *same* inputs the run saw
//! (the f32-rounded ω and H widened to f64), so input quantization is not counted as drift.
//!
//! `tests/drift.rs` runs the same function and asserts the bounds derived there.

use quatprop::scheme::{Method, Scheme};
use quatprop::stabilize::Policy;
use quatprop::{Error, Propagator, Quat, Real, Vec3};

/// The scene's rate (rad/s) and step (s).
pub const RATE: Vec3<f64> = Vec3::new(0.36, -0.48, 0.80);
/// Step (s): `H|ω| = 0.2`.
pub const STEP: f64 = 0.2;
/// Baumgarte gain used in the table (the seed's Fig. 1 value), 1/s.
pub const BAUMGARTE_K: f64 = 0.5;
/// `Every(n)` interval used in the table.
pub const EVERY_N: u32 = 100;

/// The stabilizers of the table.
pub fn policies<T: Real>() -> [Policy<T>; 5] {
    [
        Policy::Off,
        Policy::Normalize,
        Policy::FirstOrder,
        Policy::Every(EVERY_N),
        Policy::Baumgarte {
            k: T::from_f64(BAUMGARTE_K),
        },
    ]
}

/// One run's figures.
#[derive(Clone, Copy, Debug)]
pub struct DriftRow {
    /// Steps completed before the run ended (all, unless the step failed).
    pub steps: u64,
    /// Why the run stopped early, if it did.
    pub stopped: Option<Error>,
    /// `N = |q|² − 1` at the end (exact evaluation of the stored quaternion).
    pub final_n: f64,
    /// `max |N|` over all steps.
    pub max_abs_n: f64,
    /// Angle (rad) between the normalized final attitude and the exact one.
    pub attitude_error: f64,
    /// Step 1's N (for the Baumgarte analysis).
    pub first_n: f64,
}

/// Runs `steps` held-rate steps of the scene in precision `T`; `observe(step, N)` sees N after every step.
pub fn run<T: Real>(
    method: Method,
    policy: Policy<T>,
    steps: u64,
    mut observe: impl FnMut(u64, f64),
) -> DriftRow {
    let w = Vec3::<T>::from_f64(RATE);
    let h = T::from_f64(STEP);
    let q0 = Quat::<T>::IDENTITY;
    let mut p = Propagator::new(q0, method, policy).expect("valid configuration");
    let mut max_abs_n: f64 = 0.0;
    let mut first_n = 0.0;
    let mut stopped = None;
    for i in 0..steps {
        if let Err(e) = p.step_hold(w, h) {
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
    let wv = w.to_f64();
    let t = done as f64 * h.to_f64();
    let exact = exact_rotation(wv, t);
    let q = p.attitude().to_f64();
    let attitude_error = match q.normalized() {
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
        return format!("diverged at step {} ({why}) | – | –", r.steps + 1);
    }
    format!(
        "{:+.2e} | {:.2e} | {:.2e}",
        r.final_n, r.max_abs_n, r.attitude_error
    )
}

#[allow(dead_code)]
fn main() {
    let mut steps: u64 = 1_000_000;
    let args: Vec<String> = std::env::args().collect();
    let mut i = 1;
    while i < args.len() {
        match args[i].as_str() {
            "--steps" => {
                steps = args
                    .get(i + 1)
                    .and_then(|s| s.parse().ok())
                    .unwrap_or_else(|| {
                        eprintln!("--steps needs a positive integer");
                        std::process::exit(2)
                    });
                i += 2;
            }
            other => {
                eprintln!("unknown argument {other}; usage: drift [--steps N]");
                std::process::exit(2);
            }
        }
    }
    println!(
        "Constant rate |w| = 1 rad/s, H|w| = {STEP}, {steps} steps; Baumgarte k = {BAUMGARTE_K}, Every({EVERY_N}).\n\
         N = |q|^2 - 1 of the stored quaternion; attitude error = angle to the exact rotation for the same inputs.\n"
    );
    println!("| scheme | stabilizer | f32 N final | f32 max abs N | f32 attitude err (rad) | f64 N final | f64 max abs N | f64 attitude err (rad) |");
    println!("|---|---|---|---|---|---|---|---|");
    for m in Method::ALL {
        for (p32, p64) in policies::<f32>().into_iter().zip(policies::<f64>()) {
            let r32 = run::<f32>(m, p32, steps, |_, _| {});
            let r64 = run::<f64>(m, p64, steps, |_, _| {});
            let label = match p64 {
                Policy::Every(n) => format!("Every({n})"),
                Policy::Baumgarte { k } => format!("Baumgarte(k={k})"),
                other => other.name().to_string(),
            };
            println!(
                "| {} | {} | {} | {} |",
                m.name(),
                label,
                fmt_row(&r32),
                fmt_row(&r64)
            );
        }
    }
}
