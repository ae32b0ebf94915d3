//! Coning drift of each rate scheme and input model: the secular rotation about the cone axis that rate
//! integration leaves on pure coning, drift ≈ c · α²Ω · λ^p with λ = Ωh (one gyro sample per step, or three
//! for `mid`). Measured in f64 at α = 10⁻³ (α² regime) as the slope of the axial error between whole-period
//! checkpoints; p from the λ dependence over λ = 0.05…0.2, c at λ = 0.05.

use crate::table::{self, Csv, Table};
use crate::report::Ctx;
use crate::study::{CsvFile, NoArgs, Study};
use quatprop::accumulate::Kahan;
use quatprop::input::{History, InputModel, Linear, TwiceRate};
use quatprop::scheme::SchemeKind;
use quatprop::stabilize::Off;
use quatprop::{Error, GyroSample, Propagator, Quat, Vec3};
use serde::{Deserialize, Serialize};

/// The coning drift coefficients (sub-command `coning-drift`).
pub struct ConingDrift;

// The `Study` impl each study spells out (its name, files and run: lab/README.md, adding a study).
impl Study for ConingDrift {
    type Args = NoArgs;
    const NAME: &'static str = "coning-drift";
    const ABOUT: &'static str = "Coning drift coefficient of every rate scheme and input model";
    const CSV: &'static [CsvFile] = &[CsvFile::data::<DriftRow>(), CsvFile::table::<FitRow>()];
    fn run(&self, ctx: &mut Ctx, _: &NoArgs) {
        // Cone periods between the drift's checkpoints: 20 cost a fraction of a second.
        let periods = ctx.scale.pick(3, 20, 20);
        ctx.section("coning drift", |c| coning_drift(c, periods));
    }
}

/// The measured drift of one scheme × input at one λ = Ωh.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct DriftRow {
    pub scheme: String,
    pub input: String,
    pub lambda: f64,
    pub drift_rad_per_s: f64,
}
impl Csv for DriftRow {
    const FILE: &'static str = "coning_drift.csv";
}

/// The fit of one scheme × input: drift = c·α²Ω·λ^p.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FitRow {
    pub scheme: String,
    pub input: String,
    /// Fitted exponent over λ = 0.05…0.2.
    pub exponent: f64,
    /// The exponent rounded (the order the coefficient is given for).
    pub exponent_rounded: f64,
    /// c at λ = 0.05.
    pub coefficient: f64,
}
impl Csv for FitRow {
    const FILE: &'static str = "coning_drift_fit.csv";
}
impl Table for FitRow {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&[
            "scheme",
            "input",
            "exponent p (fit over λ = 0.05…0.2)",
            "coefficient c at λ = 0.05 (drift = c·α²Ω·λ^p)",
        ]);
        for r in rows {
            t += &format!(
                "| {} | {} | {:.2} | {:+.3e} (p = {}) |\n",
                r.scheme, r.input, r.exponent, r.coefficient, r.exponent_rounded
            );
        }
        t
    }
}

const ALPHA: f64 = 1e-3;
const OMEGA: f64 = 2.0 * core::f64::consts::PI;

fn attitude(t: f64) -> Quat<f64> {
    let (s, c) = (ALPHA / 2.0).sin_cos();
    let p = OMEGA * t;
    Quat::new(c, s * p.cos(), s * p.sin(), 0.0)
}

fn rate(t: f64) -> Vec3<f64> {
    let p = OMEGA * t;
    let s2 = (ALPHA / 2.0).sin();
    Vec3::new(
        -OMEGA * ALPHA.sin() * p.sin(),
        OMEGA * ALPHA.sin() * p.cos(),
        -2.0 * OMEGA * s2 * s2,
    )
}

#[derive(Clone, Copy, PartialEq)]
enum Input {
    Linear,
    History,
    Mid,
}

fn push<I: InputModel<f64, Sample = GyroSample<f64>>>(
    p: &mut Propagator<f64, SchemeKind, I, Off, Kahan<f64>>,
    w: Vec3<f64>,
    dt: f64,
) -> Result<(), Error> {
    p.push(GyroSample::new(w), dt)
}

/// Drift rate (rad/s) about the cone axis with `per_period` steps per period over `periods` periods.
fn drift(m: SchemeKind, input: Input, per_period: usize, periods: usize) -> f64 {
    let h = 1.0 / per_period as f64;
    let q0 = attitude(0.0);
    match input {
        Input::Linear => {
            // The first sample (t = 0) only starts the model; each step then pushes its end sample.
            let p = Propagator::new(q0, m, Linear::new(), Off).unwrap();
            let mut p = p.with_accumulator(Kahan::new());
            if push(&mut p, rate(0.0), h).is_err() {
                return f64::NAN;
            }
            measure(p, per_period, periods, h, |p, t| push(p, rate(t + h), h))
        }
        Input::History => {
            // The history starts full: the samples at −3h … 0 (the first only starts it, the steps over
            // [−3h, 0] are discarded with that propagator).
            let mut warm = Propagator::new(q0, m, History::new(), Off).unwrap();
            for i in -3i64..=0 {
                if warm.push(GyroSample::new(rate(i as f64 * h)), h).is_err() {
                    return f64::NAN;
                }
            }
            let p = Propagator::new(q0, m, warm.input(), Off).unwrap();
            let p = p.with_accumulator(Kahan::new());
            measure(p, per_period, periods, h, |p, t| push(p, rate(t + h), h))
        }
        Input::Mid => {
            // Gyro at twice the step rate: the start sample, then (middle, end) per step, each h/2 apart.
            let p = Propagator::new(q0, m, TwiceRate::new(), Off).unwrap();
            let mut p = p.with_accumulator(Kahan::new());
            if push(&mut p, rate(0.0), 0.5 * h).is_err() {
                return f64::NAN;
            }
            measure(p, per_period, periods, h, |p, t| {
                push(p, rate(t + 0.5 * h), 0.5 * h)?;
                push(p, rate(t + h), 0.5 * h)
            })
        }
    }
}

/// Runs `per_period · periods` steps (`step(p, t)` feeds the step starting at t) and returns the slope of
/// the axial error from the end of the first period to the end.
fn measure<I: InputModel<f64, Sample = GyroSample<f64>>>(
    mut p: Propagator<f64, SchemeKind, I, Off, Kahan<f64>>,
    per_period: usize,
    periods: usize,
    h: f64,
    step: impl Fn(&mut Propagator<f64, SchemeKind, I, Off, Kahan<f64>>, f64) -> Result<(), Error>,
) -> f64 {
    let axial = |q: Quat<f64>, t: f64| (attitude(t).conjugate() * q).to_rotation_vector().z;
    let mut first = (0.0, 0.0);
    for k in 0..per_period * periods {
        if k == per_period {
            first = (axial(p.attitude(), k as f64 * h), k as f64 * h);
        }
        if step(&mut p, k as f64 * h).is_err() {
            return f64::NAN;
        }
    }
    let t = (per_period * periods) as f64 * h;
    (axial(p.attitude(), t) - first.0) / (t - first.1)
}

fn coning_drift(ctx: &mut Ctx, periods: usize) -> String {
    let lambdas = [0.05, 0.1, 0.2];
    let mut rows = Vec::new();
    let mut fits = Vec::new();
    for m in SchemeKind::ALL {
        for (input, name) in [
            (Input::Linear, "linear"),
            (Input::History, "history"),
            (Input::Mid, "mid"),
        ] {
            if m == SchemeKind::Euler && input != Input::Linear {
                continue;
            }
            ctx.tick();
            let d: Vec<f64> = lambdas
                .iter()
                .map(|&l| {
                    let per_period = (OMEGA / l).round() as usize;
                    drift(m, input, per_period, periods)
                })
                .collect();
            for (l, v) in lambdas.iter().zip(&d) {
                rows.push(DriftRow {
                    scheme: format!("{m:?}"),
                    input: name.into(),
                    lambda: *l,
                    drift_rad_per_s: *v,
                });
            }
            let p = (d[2].abs() / d[0].abs()).ln() / (lambdas[2] / lambdas[0]).ln();
            let pr = p.round();
            let c = d[0] / (ALPHA * ALPHA * OMEGA * lambdas[0].powf(pr));
            fits.push(FitRow {
                scheme: format!("{m:?}"),
                input: name.into(),
                exponent: p,
                exponent_rounded: pr,
                coefficient: c,
            });
        }
    }
    ctx.rows(&rows);
    let table = ctx.table(&fits);
    format!(
        "### Coning drift of the rate schemes\n\nPure coning, α = 10⁻³ rad, Ω = 2π rad/s, f64 with a compensated state, \
         {periods} periods; the drift is the slope of the axial error between whole-period checkpoints. With \
         rate samples the coning drift follows the input model's order: λ² for samples at the step ends, λ⁴ with \
         the sample history or three samples per step.\n\n{table}"
    )
}
