//! Work–precision on coning in f32 with one gyro sample per step: attitude error against host time per
//! step, quatprop's configurations against the peers' updates on the same samples, and the equal-cost table.

use crate::peers;
use crate::plot::{plot, Axis, Series};
use crate::Ctx;
use quatprop::scheme::{ExpMap, Rk4};
use quatprop::stabilize::FirstOrder;
use quatprop::{Propagator, Quat, SampleHistory, Vec3};
use std::fmt::Write as _;
use std::time::Instant;

/// Coning α = 0.3 rad at 1 Hz (notes/numerics.md).
fn coning_attitude(t: f64) -> Quat<f64> {
    let (s, c) = (0.15f64).sin_cos();
    let p = 2.0 * core::f64::consts::PI * t;
    Quat::new(c, s * p.cos(), s * p.sin(), 0.0)
}

fn coning_rate(t: f64) -> Vec3<f64> {
    let o = 2.0 * core::f64::consts::PI;
    let p = o * t;
    let s2 = (0.15f64).sin();
    Vec3::new(
        -o * 0.3f64.sin() * p.sin(),
        o * 0.3f64.sin() * p.cos(),
        -2.0 * o * s2 * s2,
    )
}

pub type Runner = fn(&[Vec3<f32>], f32, Quat<f32>) -> Quat<f32>;

fn quatprop_exp_linear(s: &[Vec3<f32>], dt: f32, q0: Quat<f32>) -> Quat<f32> {
    let mut p = Propagator::new(q0, ExpMap, FirstOrder).unwrap();
    for w in s.windows(2) {
        let _ = p.step_linear(w[0], w[1], dt);
    }
    p.attitude()
}
fn quatprop_rk4_linear(s: &[Vec3<f32>], dt: f32, q0: Quat<f32>) -> Quat<f32> {
    let mut p = Propagator::new(q0, Rk4, FirstOrder).unwrap();
    for w in s.windows(2) {
        let _ = p.step_linear(w[0], w[1], dt);
    }
    p.attitude()
}
fn quatprop_exp_history(s: &[Vec3<f32>], dt: f32, q0: Quat<f32>) -> Quat<f32> {
    let mut p = Propagator::new(q0, ExpMap, FirstOrder).unwrap();
    let mut h = SampleHistory::new();
    for &w in s {
        let _ = p.step_history(&mut h, w, dt);
    }
    p.attitude()
}
fn quatprop_exp_history_kahan(s: &[Vec3<f32>], dt: f32, q0: Quat<f32>) -> Quat<f32> {
    let mut p = Propagator::new_compensated(q0, ExpMap, FirstOrder).unwrap();
    let mut h = SampleHistory::new();
    for &w in s {
        let _ = p.step_history(&mut h, w, dt);
    }
    p.attitude()
}
fn quatprop_rk4_history(s: &[Vec3<f32>], dt: f32, q0: Quat<f32>) -> Quat<f32> {
    let mut p = Propagator::new(q0, Rk4, FirstOrder).unwrap();
    let mut h = SampleHistory::new();
    for &w in s {
        let _ = p.step_history(&mut h, w, dt);
    }
    p.attitude()
}
fn peer_fusion(s: &[Vec3<f32>], dt: f32, q0: Quat<f32>) -> Quat<f32> {
    // Fusion integrates the newest sample over the step (one sample per update).
    s[1..]
        .iter()
        .fold(q0, |q, &w| peers::fusion_euler(q, w, dt))
}
fn peer_ahrs(s: &[Vec3<f32>], dt: f32, q0: Quat<f32>) -> Quat<f32> {
    s[1..].iter().fold(q0, |q, &w| peers::ahrs_euler(q, w, dt))
}
fn peer_glam(s: &[Vec3<f32>], dt: f32, q0: Quat<f32>) -> Quat<f32> {
    s.windows(2)
        .fold(q0, |q, w| peers::glam_trapezoid(q, w[0], w[1], dt))
}
fn peer_rk4(s: &[Vec3<f32>], dt: f32, q0: Quat<f32>) -> Quat<f32> {
    s.windows(2)
        .fold(q0, |q, w| peers::rk4_renormalize(q, w[0], w[1], dt))
}

/// The configurations compared: (label, is quatprop, runner).
pub const CONFIGS: [(&str, bool, Runner); 9] = [
    (
        "quatprop ExpMap linear + FirstOrder",
        true,
        quatprop_exp_linear,
    ),
    (
        "quatprop Rk4 linear + FirstOrder",
        true,
        quatprop_rk4_linear,
    ),
    (
        "quatprop ExpMap history + FirstOrder",
        true,
        quatprop_exp_history,
    ),
    (
        "quatprop ExpMap history + FirstOrder, compensated",
        true,
        quatprop_exp_history_kahan,
    ),
    (
        "quatprop Rk4 history + FirstOrder",
        true,
        quatprop_rk4_history,
    ),
    ("peer: Fusion Euler + fast inverse sqrt", false, peer_fusion),
    ("peer: ahrs Euler + normalize", false, peer_ahrs),
    (
        "peer: glam/PX4 trapezoid exp map + normalize",
        false,
        peer_glam,
    ),
    ("peer: nalgebra RK4 + renormalize", false, peer_rk4),
];

struct Point {
    config: usize,
    hz: u32,
    error: f64,
    ns_per_step: f64,
}

pub fn work_precision(ctx: &mut Ctx, quick: bool) -> String {
    // Not a whole number of coning periods: over whole periods first-order errors cancel and flatter Euler.
    let horizon = if quick { 5.37 } else { 60.37 };
    let rates: &[u32] = if quick {
        &[100, 1000]
    } else {
        &[100, 200, 500, 1000, 2000, 4000]
    };
    let repeats = if quick { 1 } else { 5 };
    let mut points = Vec::new();
    let mut csv = String::from("config,rate_hz,steps,error_rad,ns_per_step\n");
    for &hz in rates {
        let steps = (horizon * hz as f64).round() as usize;
        let dt = 1.0 / hz as f64;
        // The same f32 samples for everyone: ω(t_k), k = 0..=steps.
        let samples: Vec<Vec3<f32>> = (0..=steps)
            .map(|k| Vec3::<f32>::from_f64(coning_rate(k as f64 * dt)))
            .collect();
        let q0 = Quat::<f32>::from_f64(coning_attitude(0.0));
        let exact = coning_attitude(steps as f64 * dt);
        for (ci, (name, _, run)) in CONFIGS.iter().enumerate() {
            ctx.tick();
            let mut times = Vec::new();
            let mut q = q0;
            for _ in 0..repeats.max(1) + 1 {
                let t0 = Instant::now();
                q = std::hint::black_box(run(std::hint::black_box(&samples), dt as f32, q0));
                times.push(t0.elapsed().as_nanos() as f64 / steps as f64);
            }
            times.remove(0); // warm-up
            times.sort_by(|a, b| a.total_cmp(b));
            let ns = times[times.len() / 2];
            let error = q
                .to_f64()
                .normalized()
                .map_or(f64::NAN, |u| u.angle_to(exact));
            let _ = writeln!(csv, "{name},{hz},{steps},{error},{ns}");
            points.push(Point {
                config: ci,
                hz,
                error,
                ns_per_step: ns,
            });
        }
    }
    ctx.csv("work_precision_coning_f32.csv", &csv);
    // Pareto front over all (cost, error) points.
    let mut sorted: Vec<&Point> = points.iter().filter(|p| p.error.is_finite()).collect();
    sorted.sort_by(|a, b| a.ns_per_step.total_cmp(&b.ns_per_step));
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for p in &sorted {
        if p.error < best {
            best = p.error;
            front.push((p.ns_per_step, p.error));
        }
    }
    let mut series: Vec<Series> = CONFIGS
        .iter()
        .enumerate()
        .map(|(ci, (name, _, _))| {
            Series::both(
                *name,
                points
                    .iter()
                    .filter(|p| p.config == ci)
                    .map(|p| (p.ns_per_step, p.error))
                    .collect(),
            )
        })
        .collect();
    series.push(Series::line("Pareto front", front).dashed());
    ctx.plot(|dir| {
        plot(
            dir,
            "work_precision_coning_f32",
            "Coning, f32, one sample per step: error against host time per step",
            Axis {
                label: "host time per step (ns, median)",
                log: true,
            },
            Axis {
                label: "attitude error after the horizon (rad)",
                log: true,
            },
            &series,
        )
    });
    // Equal-cost table at 1 kHz.
    let at = |hz: u32| points.iter().filter(move |p| p.hz == hz);
    let mut table = String::from(
        "| configuration | error at 1 kHz (rad) | host ns/step | host µs per simulated second |\n|---|---|---|---|\n",
    );
    for p in at(1000) {
        let _ = writeln!(
            table,
            "| {} | {:.2e} | {:.1} | {:.1} |",
            CONFIGS[p.config].0,
            p.error,
            p.ns_per_step,
            p.ns_per_step * 1000.0 / 1000.0
        );
    }
    let best_peer = at(1000)
        .filter(|p| !CONFIGS[p.config].1)
        .min_by(|a, b| a.error.total_cmp(&b.error));
    let headline = best_peer.and_then(|bp| {
        // quatprop's best configuration at no more host time per simulated second than the best peer
        // (any rate: a cheaper scheme may run at a higher rate for the same host time).
        let budget = bp.ns_per_step * bp.hz as f64;
        points
            .iter()
            .filter(|p| {
                CONFIGS[p.config].1 && p.ns_per_step * p.hz as f64 <= budget && p.hz == 1000
            })
            .min_by(|a, b| a.error.total_cmp(&b.error))
            .map(|q| (bp, q))
    });
    let best_overall = at(1000)
        .filter(|p| CONFIGS[p.config].1)
        .min_by(|a, b| a.error.total_cmp(&b.error));
    let mut summary = match headline {
        Some((bp, q)) => format!(
            "At 1 kHz on the same f32 samples the best peer is **{}** ({:.2e} rad, {:.1} ns/step). Within that host \
             time, quatprop's best configuration is **{}** ({:.2e} rad, {:.1} ns/step): **{:.1}× lower error**.",
            CONFIGS[bp.config].0,
            bp.error,
            bp.ns_per_step,
            CONFIGS[q.config].0,
            q.error,
            q.ns_per_step,
            bp.error / q.error
        ),
        None => "No quatprop configuration ran within the best peer's host time at 1 kHz.".into(),
    };
    if let (Some(bp), Some(q)) = (best_peer, best_overall) {
        let _ = write!(
            summary,
            " quatprop's most accurate configuration, **{}**, reaches {:.2e} rad: **{:.0}× lower error** than the \
             best peer at {:.1}× its host time per step.",
            CONFIGS[q.config].0,
            q.error,
            bp.error / q.error,
            q.ns_per_step / bp.ns_per_step
        );
    }
    format!(
        "### Work–precision: coning in f32, one gyro sample per step\n\n![work-precision](work_precision_coning_f32.png)\n\n\
         Coning α = 0.3 rad at 1 Hz, horizon {horizon} s, gyro rates {rates:?} Hz, every configuration fed the same f32 \
         samples ω(t_k). Host time: median of {repeats} timed runs after a warm-up, this machine (noisy, 2 cores). Peers \
         are implemented in the lab from their published formulas (`lab/src/peers.rs`).\n\n{table}\n{summary}\n"
    )
}
