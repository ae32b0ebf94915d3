//! f32 round-off over a long coning stream: does the attitude keep what the f32 inputs carry?
//!
//! Run: `cargo run --release --example roundoff [-- --steps N] [--out DIR]` (default 3·10⁶ steps, 50 min at
//! 1 kHz). Prints the Markdown tables; with `--out DIR` also writes them to `DIR/roundoff.md`.
//!
//! The stream is the exact per-step rotation vector of a coning motion (α = 0.3 rad at 1/√2 Hz, 1 kHz steps;
//! the frequency is incommensurate with the step so the rounding errors do not repeat period after period),
//! `φ_k = log(q(t_k)* ⊗ q(t_{k+1}))` computed in f64 and rounded to f32 — what an ideal delta-angle gyro with
//! perfect coning compensation would deliver. No truncation error is left: every difference from the exact
//! attitude is round-off. The same f32 stream feeds, one `DeltaAngle` per push into
//! `input::DeltaAngles::new(Uncorrected)`:
//! - `peer form, f32`: `q ← normalize(q ⊗ exp_q(φ))`, what Fusion-, PX4- or glam-style code does;
//! - `quatprop Plain, f32`: ExpMap + FirstOrder, increment form `q + q ⊗ (e − 1)`;
//! - `quatprop Kahan, f32`: the same with the compensated accumulator (`with_accumulator(Kahan::new())`);
//! - `f64 state`: ExpMap + FirstOrder in f64 fed the same f32 samples widened: the floor set by f32 inputs.
//!
//! `tests/roundoff.rs` runs this and asserts the compensated f32 state within 2× of the f64 state.

use quatprop::accumulate::Kahan;
use quatprop::input::coning::Uncorrected;
use quatprop::input::DeltaAngles;
use quatprop::scheme::ExpMap;
use quatprop::stabilize::FirstOrder;
use quatprop::{DeltaAngle, Propagator, Quat, Vec3};

/// Cone half-angle (rad).
pub const ALPHA: f64 = 0.3;
/// Coning frequency (rad/s): 1/√2 Hz (incommensurate with the 1 kHz step).
pub const BIG_OMEGA: f64 = 2.0 * core::f64::consts::PI * core::f64::consts::FRAC_1_SQRT_2;
/// Step (s): 1 kHz.
pub const DT: f64 = 1e-3;
/// Default number of steps.
pub const DEFAULT_STEPS: u64 = 3_000_000;
/// Body spins (rad/s about body z) of the two tables.
pub const SPINS: [f64; 2] = [0.0, 1.0];

/// Exact attitude at step k: coning with initial phase `phase0` (rad), times a steady body spin of `spin`
/// rad/s about the body z axis (0 for pure coning). Both angles are reduced modulo 4π in f64.
pub fn attitude(k: u64, phase0: f64, spin: f64) -> Quat<f64> {
    let (s, c) = (ALPHA / 2.0).sin_cos();
    let four_pi = 4.0 * core::f64::consts::PI;
    let p = (phase0 + (k as f64) * (BIG_OMEGA * DT)) % four_pi;
    let cone = Quat::new(c, s * p.cos(), s * p.sin(), 0.0);
    let a = ((k as f64) * (spin * DT)) % four_pi;
    let (sa, ca) = (0.5 * a).sin_cos();
    cone * Quat::new(ca, 0.0, 0.0, sa)
}

/// Attitude errors (rad) at the end of a run.
#[derive(Clone, Copy, Debug)]
pub struct RoundoffRow {
    /// Steps.
    pub steps: u64,
    /// `normalize(q ⊗ exp(φ))` in f32.
    pub peer_f32: f64,
    /// quatprop, plain increment form, f32.
    pub plain_f32: f64,
    /// quatprop, compensated, f32.
    pub kahan_f32: f64,
    /// f64 state fed the same f32 samples.
    pub f64_state: f64,
    /// Own round-off: angle between each f32 state and the f64 state fed the same f32 samples
    /// (peer, plain, Kahan): the input quantization cancels out.
    pub own: [f64; 3],
}

/// Runs the stream for `steps` steps from initial phase `phase0`; `checkpoint(row)` is called at step counts
/// spaced by √10.
pub fn run(
    steps: u64,
    phase0: f64,
    spin: f64,
    mut checkpoint: impl FnMut(&RoundoffRow),
) -> RoundoffRow {
    let attitude = |k| attitude(k, phase0, spin);
    let q0 = attitude(0);
    let mut peer = Quat::<f32>::from_f64(q0);
    let input = DeltaAngles::new(Uncorrected);
    let mut plain = Propagator::new(Quat::<f32>::from_f64(q0), ExpMap, input, FirstOrder).unwrap();
    let mut kahan = plain.with_accumulator(Kahan::new());
    let mut wide = Propagator::new(q0, ExpMap, DeltaAngles::new(Uncorrected), FirstOrder).unwrap();
    let mut prev = q0;
    let mut next_checkpoint = 1000u64;
    let row = |k: u64, peer: Quat<f32>, p: &Quat<f32>, kq: &Quat<f32>, w: &Quat<f64>| {
        let exact = attitude(k);
        let err = |q: Quat<f64>| q.normalized().map_or(f64::NAN, |u| u.angle_to(exact));
        let wn = w.normalized().unwrap_or(*w);
        let own = |q: Quat<f64>| q.normalized().map_or(f64::NAN, |u| u.angle_to(wn));
        RoundoffRow {
            steps: k,
            peer_f32: err(peer.to_f64()),
            plain_f32: err(p.to_f64()),
            kahan_f32: err(kq.to_f64()),
            f64_state: err(*w),
            own: [own(peer.to_f64()), own(p.to_f64()), own(kq.to_f64())],
        }
    };
    for k in 0..steps {
        let next = attitude(k + 1);
        let phi64 = (prev.conjugate() * next).to_rotation_vector();
        prev = next;
        let phi = Vec3::<f32>::from_f64(phi64);
        let dt = DT as f32;
        peer = (peer * Quat::from_rotation_vector(phi))
            .normalized()
            .unwrap_or(peer);
        plain.push(DeltaAngle::new(phi), dt).unwrap();
        kahan.push(DeltaAngle::new(phi), dt).unwrap();
        wide.push(DeltaAngle::new(phi.to_f64()), DT).unwrap();
        if k + 1 == next_checkpoint {
            checkpoint(&row(
                k + 1,
                peer,
                &plain.attitude(),
                &kahan.attitude(),
                &wide.attitude(),
            ));
            next_checkpoint = (next_checkpoint as f64 * 10f64.powf(0.5)).round() as u64;
        }
    }
    row(
        steps,
        peer,
        &plain.attitude(),
        &kahan.attitude(),
        &wide.attitude(),
    )
}

/// The tables as Markdown: conditions, then one table per body spin with a row per checkpoint.
pub fn tables(steps: u64) -> String {
    let mut s = String::new();
    s.push_str(&format!(
        "Coning α = {ALPHA} rad at 1/√2 Hz (Ω = {BIG_OMEGA:.6} rad/s), steps of {DT} s (1 kHz), {steps} steps. \
         Input: the exact per-step rotation vector φ_k = log(q(t_k)* ⊗ q(t_k+1)), computed in f64 and rounded \
         to f32, one `DeltaAngle` per push into `input::DeltaAngles::new(Uncorrected)` with `scheme::ExpMap` and \
         `stabilize::FirstOrder`. No truncation error is left: every difference from the exact attitude is \
         round-off.\n\n"
    ));
    s.push_str(
        "Columns: error (rad) against the exact attitude, and in brackets each f32 state's own round-off: its \
         angle (rad) to the f64 state fed the same f32 inputs. `peer` is `q ← normalize(q ⊗ exp_q(φ))` in f32; \
         `Plain` and `Kahan` are quatprop's f32 propagator with plain and compensated (`accumulate::Kahan`) \
         addition; `f64 state` is quatprop in f64 fed the same f32 samples widened (the floor the f32 inputs \
         set). Rows: step counts spaced by √10, then the last step.\n",
    );
    for spin in SPINS {
        s.push_str(&format!("\n## Spin {spin} rad/s about body z\n\n"));
        s.push_str("| steps | peer normalize(q⊗exp φ), f32 | quatprop Plain, f32 | quatprop Kahan, f32 | f64 state, same f32 inputs |\n");
        s.push_str("|---|---|---|---|---|\n");
        let mut rows = Vec::new();
        let last = run(steps, 0.0, spin, |r| rows.push(*r));
        if rows.last().map(|r| r.steps) != Some(last.steps) {
            rows.push(last);
        }
        for r in rows {
            s.push_str(&format!(
                "| {} | {:.2e} ({:.1e}) | {:.2e} ({:.1e}) | {:.2e} ({:.1e}) | {:.2e} |\n",
                r.steps,
                r.peer_f32,
                r.own[0],
                r.plain_f32,
                r.own[1],
                r.kahan_f32,
                r.own[2],
                r.f64_state
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
        "roundoff",
        DEFAULT_STEPS,
        "f32 round-off: plain, compensated and f64 states on the same samples",
        tables,
    );
}
