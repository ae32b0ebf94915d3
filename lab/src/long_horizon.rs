//! Long horizon: attitude error and |N| against the step count at 1 kHz: every scheme in f32 on a constant
//! rate |ω| = 1 rad/s (H|ω| = 1e-3), and the exponential map with every post-step stabilizer in f32 and f64
//! (and the compensated f32 state) on the constant rate and on coning through the sample history. (Baumgarte
//! is, since quatprop 0.2, a right-hand-side option of the Runge–Kutta schemes only: no ExpMap row.)
//! Default horizon 10⁸ steps (28 h of flight at 1 kHz), `--long` 10⁹, `--quick` 10⁶.

use crate::configs::scheme_name;
use crate::plot::{plot, Axis, Series};
use crate::scenes::{Coning, Scene as _};
use crate::Ctx;
use quatprop::accumulate::{Accumulator, Kahan};
use quatprop::input::{History, Hold, InputModel};
use quatprop::scheme::{ExpMap, Scheme, SchemeKind};
use quatprop::stabilize::{Every, FirstOrder, Normalize, Off, Stabilizer};
use quatprop::{GyroSample, Propagator, Quat, Real, Vec3};
use std::fmt::Write as _;

const AXIS: Vec3<f64> = Vec3::new(0.36, -0.48, 0.80);

/// (steps, attitude error (rad), |N|) at each checkpoint.
type Curve = Vec<(u64, f64, f64)>;

/// Exact attitude after `k` steps of rate `w` (f64 from the f32 inputs), angle reduced modulo 4π.
fn exact(w: Vec3<f64>, dt: f64, k: u64) -> Quat<f64> {
    let angle = (w.norm() * dt * k as f64) % (4.0 * core::f64::consts::PI);
    Quat::from_axis_angle(w, angle).unwrap_or(Quat::IDENTITY)
}

fn checkpoints(total: u64) -> Vec<u64> {
    let mut v = Vec::new();
    let mut c = 1000f64;
    while (c as u64) < total {
        v.push(c as u64);
        c *= 10f64.sqrt();
    }
    v.push(total);
    v
}

/// The motion of a long run: a constant rate (held samples), or coning α = 0.3 rad at 1 Hz fed through the
/// fourth-order sample history (its truncation, 2.3e-11 rad/s at 1 kHz, stays below f32 round-off).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Motion {
    Constant,
    Coning,
}

/// A run from the identity with scheme `s` and stabilizer `z`: held samples ([`Hold`]) on the constant rate,
/// the sample history ([`History`]) on coning; increments added plainly or compensated ([`Kahan`]).
fn run_motion<T: Real, S: Scheme<T>, Z: Stabilizer>(
    ctx: &mut Ctx,
    s: S,
    z: Z,
    compensated: bool,
    total: u64,
    motion: Motion,
) -> Curve {
    let q0 = Quat::<T>::IDENTITY;
    match (motion, compensated) {
        (Motion::Constant, false) => {
            run(ctx, Propagator::new(q0, s, Hold, z).unwrap(), total, motion)
        }
        (Motion::Constant, true) => {
            let p = Propagator::new(q0, s, Hold, z).unwrap();
            run(ctx, p.with_accumulator(Kahan::new()), total, motion)
        }
        (Motion::Coning, false) => {
            let p = Propagator::new(q0, s, History::new(), z).unwrap();
            run(ctx, p, total, motion)
        }
        (Motion::Coning, true) => {
            let p = Propagator::new(q0, s, History::new(), z).unwrap();
            run(ctx, p.with_accumulator(Kahan::new()), total, motion)
        }
    }
}

fn run<T, S, I, Z, A>(
    ctx: &mut Ctx,
    mut p: Propagator<T, S, I, Z, A>,
    total: u64,
    motion: Motion,
) -> Curve
where
    T: Real,
    S: Scheme<T>,
    I: InputModel<T, Sample = GyroSample<T>>,
    Z: Stabilizer,
    A: Accumulator<T>,
{
    let w = Vec3::<T>::from_f64(AXIS);
    let dt = T::from_f64(1e-3);
    let (w64, dt64) = (w.to_f64(), dt.to_f64());
    if motion == Motion::Coning {
        let _ = p.set_attitude(Quat::<T>::from_f64(Coning.attitude(0.0)));
        // The first sample only starts the history.
        let _ = p.push(GyroSample::new(Vec3::<T>::from_f64(Coning.rate(0.0))), dt);
    }
    let mut out = Vec::new();
    let mut k = 0u64;
    for c in checkpoints(total) {
        match motion {
            Motion::Constant => {
                while k < c {
                    let _ = p.push(GyroSample::new(w), dt);
                    k += 1;
                    if k.is_multiple_of(1_000_000) {
                        ctx.tick();
                    }
                }
            }
            Motion::Coning => {
                while k < c {
                    k += 1;
                    let wk = Vec3::<T>::from_f64(Coning.rate(k as f64 * dt64));
                    let _ = p.push(GyroSample::new(wk), dt);
                    if k.is_multiple_of(1_000_000) {
                        ctx.tick();
                    }
                }
            }
        }
        let exact = match motion {
            Motion::Constant => exact(w64, dt64, k),
            Motion::Coning => Coning.attitude(k as f64 * dt64),
        };
        let q = p.attitude().to_f64();
        let err = q.normalized().map_or(f64::NAN, |u| u.angle_to(exact));
        out.push((k, err, p.norm_error().to_f64().abs()));
    }
    out
}

/// Least-squares slope of log(err) against log(steps) over the last three decades.
fn slope(points: &[(u64, f64, f64)]) -> f64 {
    let last = points.last().map_or(1, |p| p.0) as f64;
    let sel: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| (p.0 as f64) >= last / 1000.0 && p.1 > 0.0)
        .map(|p| ((p.0 as f64).ln(), p.1.ln()))
        .collect();
    let n = sel.len() as f64;
    let (mx, my) = (
        sel.iter().map(|p| p.0).sum::<f64>() / n,
        sel.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = sel.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = sel.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    sxy / sxx
}

/// Every post-step stabilizer with the exponential map, f32 and f64, and the compensated f32 state.
fn stabilizer_rows(ctx: &mut Ctx, total: u64, motion: Motion, rows: &mut Vec<(String, Curve)>) {
    let tag = match motion {
        Motion::Constant => "constant",
        Motion::Coning => "coning",
    };
    macro_rules! both {
        ($z:expr, $zname:expr) => {{
            rows.push((
                format!("{tag}: ExpMap + {} f32", $zname),
                run_motion::<f32, _, _>(ctx, ExpMap, $z, false, total, motion),
            ));
            rows.push((
                format!("{tag}: ExpMap + {} f64", $zname),
                run_motion::<f64, _, _>(ctx, ExpMap, $z, false, total, motion),
            ));
        }};
    }
    both!(Off, "Off");
    both!(Normalize, "Normalize");
    both!(FirstOrder, "FirstOrder");
    both!(Every(16), "Every(16)");
    rows.push((
        format!("{tag}: ExpMap + FirstOrder f32 compensated"),
        run_motion::<f32, _, _>(ctx, ExpMap, FirstOrder, true, total, motion),
    ));
}

pub fn long_horizon(ctx: &mut Ctx, total: u64) -> String {
    let mut rows: Vec<(String, Curve)> = Vec::new();
    for m in SchemeKind::ALL {
        rows.push((
            format!("constant: {} + FirstOrder f32", scheme_name(m)),
            run_motion::<f32, _, _>(ctx, m, FirstOrder, false, total, Motion::Constant),
        ));
    }
    stabilizer_rows(ctx, total, Motion::Constant, &mut rows);
    let constant_rows = rows.len();
    stabilizer_rows(ctx, total, Motion::Coning, &mut rows);
    let mut csv = String::from("configuration,steps,attitude_error_rad,abs_N\n");
    let mut table = format!(
        "| configuration | attitude error after {total:.0e} steps (rad) | max \\|N\\| at checkpoints | growth exponent (last 3 decades) |\n|---|---|---|---|\n"
    );
    for (name, pts) in &rows {
        for (k, e, n) in pts {
            let _ = writeln!(csv, "{name},{k},{e},{n}");
        }
        let last = pts.last().copied().unwrap_or((0, f64::NAN, f64::NAN));
        let maxn = pts.iter().map(|p| p.2).fold(0.0, f64::max);
        let _ = writeln!(
            table,
            "| {name} | {:.2e} | {:.1e} | {:.2} |",
            last.1,
            maxn,
            slope(pts)
        );
    }
    ctx.csv("long_horizon.csv", &csv);
    let error_series = |sel: &[(String, Curve)]| -> Vec<Series> {
        sel.iter()
            .map(|(name, pts)| {
                Series::both(
                    name.clone(),
                    pts.iter().map(|p| (p.0 as f64, p.1.max(1e-16))).collect(),
                )
            })
            .collect()
    };
    // The drift plot: every scheme in f32, the compensated f32 state and f64 (ExpMap, FirstOrder).
    let mut drift: Vec<(String, Curve)> = rows[..SchemeKind::ALL.len()].to_vec();
    drift.extend(
        rows.iter()
            .filter(|r| {
                r.0 == "constant: ExpMap + FirstOrder f64"
                    || r.0 == "constant: ExpMap + FirstOrder f32 compensated"
            })
            .cloned(),
    );
    let steps_axis = Axis {
        label: "steps",
        log: true,
    };
    let err_axis = Axis {
        label: "attitude error (rad)",
        log: true,
    };
    let plots: [(&str, String, Vec<Series>); 4] = [
        (
            "long_horizon",
            "Constant rate 1 rad/s at 1 kHz: attitude error against step count".into(),
            error_series(&drift),
        ),
        (
            "long_horizon_stabilizers_constant",
            "Constant rate, ExpMap: every post-step stabilizer, f32 and f64".into(),
            error_series(&rows[SchemeKind::ALL.len()..constant_rows]),
        ),
        (
            "long_horizon_stabilizers_coning",
            "Coning at 1 kHz (sample history), ExpMap: every post-step stabilizer, f32 and f64"
                .into(),
            error_series(&rows[constant_rows..]),
        ),
        (
            "long_horizon_norm",
            "Coning at 1 kHz: |N| = ||q|^2 - 1| against step count".into(),
            rows[constant_rows..]
                .iter()
                .map(|(name, pts)| {
                    Series::both(
                        name.clone(),
                        pts.iter().map(|p| (p.0 as f64, p.2.max(1e-18))).collect(),
                    )
                })
                .collect(),
        ),
    ];
    for (name, title, series) in plots {
        let y = if name == "long_horizon_norm" {
            Axis {
                label: "|N|",
                log: true,
            }
        } else {
            err_axis
        };
        ctx.plot(|dir| plot(dir, name, &title, steps_axis, y, &series));
    }
    format!(
        "### Long horizon: error growth in f32 and f64\n\n![long horizon](long_horizon.png)\n\n\
         ![stabilizers, constant rate](long_horizon_stabilizers_constant.png)\n\n\
         ![stabilizers, coning](long_horizon_stabilizers_coning.png)\n\n![norm, coning](long_horizon_norm.png)\n\n\
         At 1 kHz. Constant rate: |ω| = 1 rad/s about (0.36, −0.48, 0.80) (H|ω| = 1e-3), held samples, from the \
         identity; the reference is the exact rotation for the same f32 inputs. Coning: α = 0.3 rad at 1 Hz, f32 or \
         f64 samples of the exact rate through the fourth-order sample history; the reference is the exact \
         motion. Every post-step stabilizer; no Baumgarte row, which since quatprop 0.2 exists for the Runge–Kutta \
         schemes only (a right-hand-side option of their engine, not a stabilizer). A growth exponent near 1 is a linear (biased) drift, near ½ a random walk; a truncation-dominated \
         scheme grows linearly too (its per-step error is the same every step).\n\n{table}"
    )
}
