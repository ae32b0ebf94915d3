//! The f32 covariance study: three ways of keeping an error-state covariance in `f32` over 10⁸ attitude
//! steps, each against an `f64` reference.
//!
//! An attitude runs at 1 kHz through `Propagator::recommended` (ExpMap + History + FirstOrder) on a smooth
//! tumble (body rates a sum of sines at incommensurate frequencies, up to 1 rad/s per axis). Every 10
//! attitude steps (10 ms) the covariance of `x = (δθ, δb)` is propagated with `error_state::Step::between`
//! (Φ over the 10 steps, Q from a MEMS datasheet) and the inclination is observed: two scalar updates with
//! the rows `hᵢ = (tᵢᵀ[g×], 0)`, `g` the predicted gravity direction in body axes, `t₁, t₂ ⟂ g`. Heading
//! is never observed, so the variance about the vertical only grows and the eigenvalues spread.
//!
//! The forms: naive (`ΦPΦᵀ + Q`, `(I − KH)P`), symmetrized Joseph (`(P + Pᵀ)/2` after each operation,
//! `(I − KH)P(I − KH)ᵀ + K r Kᵀ`) and the core's `covariance::Ud` (Thornton, Bierman). The reference is the
//! symmetrized Joseph form in `f64`, cross-checked against an `f64` `Ud`. The `f32` forms get `f32` Φ, Q
//! and H computed in `f32` from an `f32` propagator; the reference gets `f64` ones from an `f64`
//! propagator fed the same `f32` samples and `dt`s (what a firmware and its desktop model would each
//! compute). A fourth form, `Ud` predicted with `predict_compensated` (D carried to twice the precision),
//! asks whether keeping the variances' sub-ulp increments brings `f32` to `f64`. Diagnostics: both `Ud`
//! lines fed the reference's Φ, Q and H rounded to `f32`, and the reference's own `f64` arithmetic on
//! those rounded inputs (what rounding the inputs costs alone).

// Matrix algorithms read clearest with the indices of their formulas.
#![allow(clippy::needless_range_loop)]

use crate::plot::{plot, png, Axis, Series};
use crate::report::Ctx;
use crate::study::{CsvFile, Study};
use crate::table::{self, sci, Csv, Table};
use nalgebra::{Matrix6, SymmetricEigen};
use quatprop::covariance::Ud;
use quatprop::error_state::{GyroNoise, Step};
use quatprop::{GyroSample, Propagator, Quat, Real, Recommended, Vec3};
use serde::{Deserialize, Serialize};
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

/// The study (sub-command `covariance`).
pub struct Covariance;

/// Its arguments.
#[derive(clap::Args, Debug, Clone)]
pub struct Args {
    /// Attitude steps at 1 kHz (from 1e3; `1e8` and `100000000` both work; rounded to a multiple of 10).
    /// Default 1e8 (1e5 with --quick; 1e7 in `report`, 1e8 in `report --full`).
    #[arg(long, value_parser = parse_steps)]
    pub steps: Option<u64>,
    /// Run alone, the study writes its own page (`DIR/covariance.md`, no CSV); in `report`, a section.
    #[arg(skip = true)]
    pub page: bool,
}

fn parse_steps(s: &str) -> Result<u64, String> {
    let n: f64 = s.parse().map_err(|e| format!("{e}"))?;
    if (1e3..=1e12).contains(&n) {
        Ok(((n / 10.0).round() as u64) * 10)
    } else {
        Err("a step count from 1e3 to 1e12".into())
    }
}

impl Study for Covariance {
    type Args = Args;
    const NAME: &'static str = "covariance";
    const ABOUT: &'static str =
        "f32 covariance to 1e8 steps: naive, symmetrized Joseph, U-D factored (plain and compensated) against f64";
    const CSV: &'static [CsvFile] = &[CsvFile::data::<PointRow>(), CsvFile::table::<SummaryRow>()];
    fn figures(&self) -> Vec<String> {
        vec!["covariance".into()]
    }
    fn report_args(&self, _report: &crate::args::ReportArgs) -> Args {
        Args {
            steps: None,
            page: false,
        }
    }
    fn run(&self, ctx: &mut Ctx, args: &Args) {
        let steps = args.steps.unwrap_or(if args.page {
            ctx.scale.pick(100_000, 100_000_000, 100_000_000)
        } else {
            ctx.scale.pick(100_000, 10_000_000, 100_000_000)
        });
        if args.page {
            ctx.page("covariance.md");
        }
        let page = args.page;
        ctx.section("covariance", |c| study(c, steps, page));
    }
}

// ---------------------------------------------------------------------------------------------------------
// The scenario.

// The scenario's parameters: one named constant a line, alike in form only (values, not repeated logic).

/// Attitude steps per covariance step (and per inclination epoch): 10 ms at 1 kHz.
const PER_EPOCH: u64 = 10;
/// Angle random walk (°/√h) and bias random walk (°/h/√h): a MEMS-class gyro.
const ARW_DEG_SQRT_H: f64 = 0.3;
const RRW_DEG_H_SQRT_H: f64 = 10.0;
/// Inclination noise, per component (rad).
const INCLINATION_SIGMA_DEG: f64 = 0.5;
/// Initial standard deviations: attitude 5° per axis, bias 0.5 °/s per axis.
const SIGMA0_ATTITUDE_DEG: f64 = 5.0;
const SIGMA0_BIAS_DEG_S: f64 = 0.5;

/// (amplitude rad/s, frequency Hz, phase rad) of the three sines of each body axis; frequencies
/// multiples of √2, √3, √5, √7, √11: incommensurate with each other and with 1 kHz.
const SINES: [[(f64, f64, f64); 3]; 3] = {
    const R2: f64 = core::f64::consts::SQRT_2;
    const R3: f64 = 1.732_050_807_568_877_2;
    const R5: f64 = 2.236_067_977_499_79;
    const R7: f64 = 2.645_751_311_064_590_7;
    const R11: f64 = 3.316_624_790_355_4;
    [
        [
            (0.5, 0.1 * R2, 0.0),
            (0.3, 0.7 * R3, 1.0),
            (0.2, 2.3 * R5, 2.0),
        ],
        [
            (0.5, 0.13 * R3, 0.5),
            (0.3, 0.9 * R2, 0.0),
            (0.2, 1.7 * R7, 1.5),
        ],
        [
            (0.6, 0.07 * R5, 2.5),
            (0.3, 0.5 * R11, 0.0),
            (0.1, 3.1 * R2, 0.7),
        ],
    ]
};

/// The body rate (rad/s) at time `t` (s).
fn rate(t: f64) -> Vec3<f64> {
    let axis = |a: &[(f64, f64, f64); 3]| {
        a.iter()
            .map(|&(amp, f, ph)| amp * (2.0 * core::f64::consts::PI * f * t + ph).sin())
            .sum::<f64>()
    };
    Vec3::new(axis(&SINES[0]), axis(&SINES[1]), axis(&SINES[2]))
}

type M6<T> = [[T; 6]; 6];
type M64 = M6<f64>;

/// One epoch's Φ, Q and the two measurement rows.
#[derive(Clone, Copy)]
struct Inputs<T> {
    phi: M6<T>,
    q: M6<T>,
    h: [[T; 6]; 2],
}

fn cross<T: Real>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit3<T: Real>(a: [T; 3]) -> [T; 3] {
    let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

/// Φ and Q of the interval from `start` to `end`, and the inclination rows at `end`, all in `T`.
///
/// The reference's vertical is z; `g = R(q̂)ᵀ e_z` is the predicted gravity direction in body axes. With
/// `q = q̂ ⊗ exp_q(δθ)`, the true one is `R(δθ)ᵀ g ≈ g + [g×] δθ`: H_θ = [g×], of which the two rows along
/// unit vectors `t₁, t₂ ⟂ g` are measured (`tᵢᵀ[g×] = (tᵢ × g)ᵀ`), none on the bias. The component of δθ
/// along g (heading) is in no row.
fn inputs<T: Real>(start: Quat<T>, end: Quat<T>, dt: T, noise: &GyroNoise<T>) -> Inputs<T> {
    let step = Step::between(start, end, dt, noise).expect("finite attitudes and dt");
    let (phi, q) = step.matrices();
    let e = end.normalized().expect("a unit attitude");
    let gv = e
        .conjugate()
        .rotate(Vec3::new(T::ZERO, T::ZERO, T::ONE));
    let g = unit3([gv.x, gv.y, gv.z]);
    let a = if g[0].abs() < T::from_f64(0.9) {
        [T::ONE, T::ZERO, T::ZERO]
    } else {
        [T::ZERO, T::ONE, T::ZERO]
    };
    let t1 = unit3(cross(a, g));
    let t2 = cross(g, t1);
    let mut h = [[T::ZERO; 6]; 2];
    for (row, t) in h.iter_mut().zip([t1, t2]) {
        let v = cross(t, g);
        row[..3].copy_from_slice(&v);
    }
    Inputs { phi, q, h }
}

fn widen_inputs(i: &Inputs<f32>) -> Inputs<f64> {
    let m = |a: &M6<f32>| a.map(|r| r.map(f64::from));
    Inputs {
        phi: m(&i.phi),
        q: m(&i.q),
        h: i.h.map(|r| r.map(f64::from)),
    }
}

fn round_inputs(i: &Inputs<f64>) -> Inputs<f32> {
    let m = |a: &M64| a.map(|r| r.map(|v| v as f32));
    Inputs {
        phi: m(&i.phi),
        q: m(&i.q),
        h: i.h.map(|r| r.map(|v| v as f32)),
    }
}

// ---------------------------------------------------------------------------------------------------------
// The forms.

/// `P` kept as a matrix: the naive form, or the symmetrized Joseph form.
#[derive(Clone, Copy)]
struct Dense<T> {
    p: M6<T>,
    joseph: bool,
}

/// `A B`, each element summed in index order.
fn product<T: Real>(a: &M6<T>, b: &M6<T>) -> M6<T> {
    product_by(a, |k, j| b[k][j])
}

/// `A Bᵀ`, each element summed in index order.
fn product_transposed<T: Real>(a: &M6<T>, b: &M6<T>) -> M6<T> {
    product_by(a, |k, j| b[j][k])
}

/// `A B` with `B`'s element (k, j) given by `b(k, j)`, each element summed in index order.
#[inline(always)]
fn product_by<T: Real>(a: &M6<T>, b: impl Fn(usize, usize) -> T) -> M6<T> {
    let mut c = [[T::ZERO; 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            let mut s = T::ZERO;
            for k in 0..6 {
                s += a[i][k] * b(k, j);
            }
            c[i][j] = s;
        }
    }
    c
}

fn symmetrize<T: Real>(p: &mut M6<T>) {
    for i in 0..6 {
        for j in i + 1..6 {
            let m = (p[i][j] + p[j][i]) * T::HALF;
            p[i][j] = m;
            p[j][i] = m;
        }
    }
}

impl<T: Real> Dense<T> {
    fn new(diag: [T; 6], joseph: bool) -> Self {
        let mut p = [[T::ZERO; 6]; 6];
        for i in 0..6 {
            p[i][i] = diag[i];
        }
        Self { p, joseph }
    }

    /// `P ← Φ P Φᵀ + Q` (then symmetrized for the Joseph form).
    fn predict(&mut self, phi: &M6<T>, q: &M6<T>) {
        let a = product(phi, &self.p);
        let mut p = product_transposed(&a, phi);
        for i in 0..6 {
            for j in 0..6 {
                p[i][j] += q[i][j];
            }
        }
        if self.joseph {
            symmetrize(&mut p);
        }
        self.p = p;
    }

    /// One scalar measurement `h·x` of variance `r`, `K = P hᵀ / (h P hᵀ + r)`: `P ← (I − K h) P`
    /// (naive) or `(I − K h) P (I − K h)ᵀ + K r Kᵀ`, symmetrized (Joseph).
    fn update(&mut self, h: &[T; 6], r: T) {
        let p = &self.p;
        let mut ph = [T::ZERO; 6];
        for i in 0..6 {
            let mut s = T::ZERO;
            for j in 0..6 {
                s += p[i][j] * h[j];
            }
            ph[i] = s;
        }
        let mut s = r;
        for i in 0..6 {
            s += h[i] * ph[i];
        }
        let k = ph.map(|v| v / s);
        if !self.joseph {
            let mut hp = [T::ZERO; 6];
            for j in 0..6 {
                let mut s = T::ZERO;
                for m in 0..6 {
                    s += h[m] * p[m][j];
                }
                hp[j] = s;
            }
            for i in 0..6 {
                for j in 0..6 {
                    self.p[i][j] -= k[i] * hp[j];
                }
            }
        } else {
            // A = I − k h; P ← A P Aᵀ + r k kᵀ.
            let mut a = [[T::ZERO; 6]; 6];
            for i in 0..6 {
                for j in 0..6 {
                    let id = if i == j { T::ONE } else { T::ZERO };
                    a[i][j] = id - k[i] * h[j];
                }
            }
            let ap = product(&a, p);
            let mut out = product_transposed(&ap, &a);
            for i in 0..6 {
                for j in 0..6 {
                    out[i][j] += r * k[i] * k[j];
                }
            }
            symmetrize(&mut out);
            self.p = out;
        }
    }

    fn matrix64(&self) -> M64 {
        self.p.map(|r| r.map(Real::to_f64))
    }
}

/// Every form's covariance in f64, in the order of [`FORMS`]: the two dense forms, then the four `Ud`s.
fn matrices64(naive: &Dense<f32>, joseph: &Dense<f32>, uds: [&Ud<f32, 6>; 4]) -> [M64; 6] {
    let [ud, ud_comp, ud_rounded, ud_comp_rounded] = uds.map(ud_matrix64);
    [naive.matrix64(), joseph.matrix64(), ud, ud_comp, ud_rounded, ud_comp_rounded]
}

/// The covariance a `Ud` holds, `U D Uᵀ` formed in f64 from its factors (exactly what the factors
/// represent: positive semi-definite by construction).
fn ud_matrix64<T: Real>(ud: &Ud<T, 6>) -> M64 {
    let (u, d) = (ud.u(), ud.d());
    let mut p = [[0.0; 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            let mut s = 0.0;
            for k in i.max(j)..6 {
                s += u[i][k].to_f64() * d[k].to_f64() * u[j][k].to_f64();
            }
            p[i][j] = s;
        }
    }
    p
}

// ---------------------------------------------------------------------------------------------------------
// Metrics.

/// max |P_ij − R_ij| / sqrt(R_ii R_jj) (NaN if P has a NaN).
fn rel_error(p: &M64, r: &M64) -> f64 {
    worst_element(p, r).0
}

/// The state names, for the element with the largest error.
const STATES: [&str; 6] = ["θx", "θy", "θz", "bx", "by", "bz"];

/// max |P_ij − R_ij| / sqrt(R_ii R_jj) and its (i, j), i ≤ j.
fn worst_element(p: &M64, r: &M64) -> (f64, usize, usize) {
    let mut m = (0.0, 0, 0);
    for i in 0..6 {
        for j in 0..6 {
            let e = (p[i][j] - r[i][j]).abs() / (r[i][i] * r[j][j]).sqrt();
            if e.is_nan() {
                return (f64::NAN, i, j);
            }
            if e > m.0 {
                m = (e, i.min(j), i.max(j));
            }
        }
    }
    m
}

fn sym_part(p: &M64) -> Matrix6<f64> {
    Matrix6::from_fn(|i, j| 0.5 * (p[i][j] + p[j][i]))
}

/// The eigenvalues of the symmetric part, ascending (NaN if any entry is not finite).
fn eigenvalues(p: &M64) -> [f64; 6] {
    if !p.iter().flatten().all(|v| v.is_finite()) {
        return [f64::NAN; 6];
    }
    let e = SymmetricEigen::new(sym_part(p)).eigenvalues;
    let mut v = [0.0; 6];
    for (o, x) in v.iter_mut().zip(e.iter()) {
        *o = *x;
    }
    v.sort_by(f64::total_cmp);
    v
}

/// max |P − Pᵀ| / max |P|.
fn asymmetry(p: &M64) -> f64 {
    let (mut a, mut m): (f64, f64) = (0.0, 0.0);
    for i in 0..6 {
        for j in 0..6 {
            a = a.max((p[i][j] - p[j][i]).abs());
            m = m.max(p[i][j].abs());
        }
    }
    a / m
}

/// Why a covariance stopped being valid, if it has: a NaN, a negative diagonal entry, a negative
/// eigenvalue (an LDLᵀ pivot of the symmetric part below zero by more than 64 ε₆₄ of its diagonal entry,
/// so that f64's own rounding of a semi-definite matrix is not counted), or an error above 1.
fn invalid(p: &M64, r: &M64) -> Option<&'static str> {
    if !p.iter().flatten().all(|v| v.is_finite()) {
        return Some("NaN or infinite entry");
    }
    if (0..6).any(|i| p[i][i] < 0.0) {
        return Some("negative variance");
    }
    // LDLᵀ of the symmetric part.
    let s = sym_part(p);
    let mut l = [[0.0f64; 6]; 6];
    let mut d = [0.0f64; 6];
    for j in 0..6 {
        let mut dj = s[(j, j)];
        for k in 0..j {
            dj -= l[j][k] * l[j][k] * d[k];
        }
        if dj < -64.0 * f64::EPSILON * s[(j, j)].abs() {
            return Some("negative eigenvalue");
        }
        d[j] = dj;
        for i in j + 1..6 {
            let mut v = s[(i, j)];
            for k in 0..j {
                v -= l[i][k] * l[j][k] * d[k];
            }
            l[i][j] = if dj > 0.0 { v / dj } else { 0.0 };
        }
    }
    if rel_error(p, r) > 1.0 {
        return Some("error above 1");
    }
    None
}

// ---------------------------------------------------------------------------------------------------------
// The run.

/// The f32 forms, in the order of the table and the plot.
const FORMS: [&str; 6] = [
    "naive f32",
    "f32 Joseph, symmetrized",
    "f32 U-D (covariance::Ud)",
    "f32 U-D, compensated",
    "f32 U-D, f64 inputs rounded",
    "f32 U-D compensated, f64 inputs rounded",
];
/// Indices into [`FORMS`] (one named constant a line, like the scenario's parameters).
const NAIVE: usize = 0;
const JOSEPH: usize = 1;
const UD: usize = 2;
const UD_COMP: usize = 3;
const UD_ROUNDED: usize = 4;
const UD_COMP_ROUNDED: usize = 5;

/// One checkpoint of one form.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PointRow {
    pub form: String,
    pub steps: u64,
    /// max_ij |P_ij − R_ij| / sqrt(R_ii R_jj), R the f64 reference.
    pub max_rel_error: f64,
    /// The element with that error (`θx/bz`).
    pub worst_element: String,
    /// Smallest eigenvalue of the symmetric part (mixed units: rad² and (rad/s)²).
    pub min_eigenvalue: f64,
    /// The same over the reference's smallest eigenvalue.
    pub min_eigenvalue_ratio: f64,
    /// max |P − Pᵀ| / max |P|.
    pub asymmetry: f64,
}
impl Csv for PointRow {
    const FILE: &'static str = "covariance.csv";
}

/// One form's summary.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SummaryRow {
    pub form: String,
    pub error_1e4: f64,
    pub error_1e6: f64,
    pub error_end: f64,
    pub worst_element_end: String,
    pub min_eigenvalue_ratio_end: f64,
    pub max_asymmetry: f64,
    /// The first attitude step at which it is no longer valid (0: valid throughout).
    pub invalid_at: u64,
    pub why: String,
    pub steps_end: u64,
    pub ns_predict: f64,
    pub ns_update: f64,
}
impl Csv for SummaryRow {
    const FILE: &'static str = "covariance_summary.csv";
}
// Each table spells out its own line: its columns and their number formats are its own.
impl Table for SummaryRow {
    fn render(rows: &[Self]) -> String {
        let n = rows.first().map_or(0, |r| r.steps_end) as f64;
        let end = format!("{n:.0e}");
        let mut t = table::header(&[
            "form",
            "error vs f64, 1e4 steps",
            "1e6",
            &end,
            "worst element",
            &format!("λ_min / λ_min(f64), {end}"),
            "max asymmetry",
            "valid until",
            "ns per predict",
            "ns per scalar update",
        ]);
        for r in rows {
            let valid = if r.invalid_at == 0 {
                format!("{end} (the end)")
            } else {
                format!("step {} ({})", r.invalid_at, r.why)
            };
            t += &format!(
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                r.form,
                sci(r.error_1e4, 2),
                sci(r.error_1e6, 2),
                sci(r.error_end, 2),
                r.worst_element_end,
                sci(r.min_eigenvalue_ratio_end, 2),
                if r.max_asymmetry == 0.0 {
                    "0".to_string()
                } else {
                    sci(r.max_asymmetry, 1)
                },
                valid,
                ns(r.ns_predict),
                ns(r.ns_update),
            );
        }
        t
    }
}

/// A host time in ns, or "not timed" (NaN: the diagnostic lines, whose arithmetic is a timed line's).
fn ns(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.0}")
    } else {
        "not timed".into()
    }
}

/// Reference-side quantities at a checkpoint.
#[derive(Clone, Debug)]
struct RefPoint {
    steps: u64,
    eig: [f64; 6],
    /// Agreement of the f64 Ud with the f64 Joseph reference (max relative error).
    ud64_error: f64,
    /// Angle between the f32 and the f64 attitude (rad).
    attitude_gap: f64,
    /// Standard deviations of δθ along the vertical (heading) and of the bias, from the reference (rad,
    /// rad/s).
    heading_sigma: f64,
    bias_sigma: f64,
    /// Each form's heading variance (along the f64 attitude's vertical) over the reference's, minus 1
    /// (in the order of [`FORMS`]).
    heading_error: [f64; 6],
    /// The reference's own arithmetic (f64 symmetrized Joseph) fed the f64 inputs rounded to f32: its
    /// max relative error and heading-variance error against the reference (the inputs' rounding alone).
    rounded_f64_error: f64,
    rounded_f64_heading_error: f64,
    /// Smallest eigenvalue of the reference's correlation matrix (P scaled to a unit diagonal).
    corr_min_eig: f64,
}

/// Checkpoints: ten per decade from 10³ to `total`, multiples of 10.
fn checkpoints(total: u64) -> Vec<u64> {
    let mut v: Vec<u64> = (0..)
        .map(|i| ((10f64.powf(3.0 + f64::from(i) / 10.0) / 10.0).round() as u64) * 10)
        .take_while(|&c| c < total)
        .collect();
    v.dedup();
    v.push(total);
    v
}

struct Outcome {
    points: Vec<PointRow>,
    refs: Vec<RefPoint>,
    invalid: [Option<(u64, &'static str)>; 6],
    wall_s: f64,
}

fn initial<T: Real>() -> [T; 6] {
    let a = SIGMA0_ATTITUDE_DEG.to_radians().powi(2);
    let b = SIGMA0_BIAS_DEG_S.to_radians().powi(2);
    [a, a, a, b, b, b].map(T::from_f64)
}

fn run(total: u64, bar: &indicatif::ProgressBar) -> Outcome {
    let started = Instant::now();
    let noise32 = GyroNoise::<f32>::from_datasheet(ARW_DEG_SQRT_H, RRW_DEG_H_SQRT_H).expect("noise");
    let noise64 = GyroNoise::<f64>::from_datasheet(ARW_DEG_SQRT_H, RRW_DEG_H_SQRT_H).expect("noise");
    let r64 = INCLINATION_SIGMA_DEG.to_radians().powi(2);
    let r32 = r64 as f32;
    let mut p32: Recommended<f32> = Propagator::recommended(Quat::IDENTITY).expect("identity");
    let mut p64: Recommended<f64> = Propagator::recommended(Quat::IDENTITY).expect("identity");
    let dt32: f32 = 1.0e-3;
    let dt = f64::from(dt32);
    let sample = |k: u64| {
        let w = rate(k as f64 * dt);
        Vec3::new(w.x as f32, w.y as f32, w.z as f32)
    };
    let w0 = sample(0);
    p32.start(GyroSample::new(w0)).expect("finite");
    p64.start(GyroSample::new(w0.to_f64())).expect("finite");
    let mut naive = Dense::new(initial::<f32>(), false);
    let mut joseph = Dense::new(initial::<f32>(), true);
    let mut ud = Ud::<f32, 6>::from_diagonal(initial()).expect("valid");
    let mut ud_comp = ud;
    let mut ud_rounded = ud;
    let mut ud_comp_rounded = ud;
    // The reference's arithmetic on the f32-rounded inputs: what rounding Φ, Q and h alone costs.
    let mut reference_rounded = Dense::new(initial::<f64>(), true);
    let mut reference = Dense::new(initial::<f64>(), true);
    let mut ud64 = Ud::<f64, 6>::from_diagonal(initial()).expect("valid");
    let (mut start32, mut start64) = (p32.attitude(), p64.attitude());
    let epoch_dt32 = dt32 * PER_EPOCH as f32;
    let epoch_dt = dt * PER_EPOCH as f64;
    let mut broken: [Option<(u64, &'static str)>; 6] = [None; 6];
    let mut points = Vec::new();
    let mut refs = Vec::new();
    let mut k = 0u64;
    for c in checkpoints(total) {
        while k < c {
            for _ in 0..PER_EPOCH {
                k += 1;
                let w = sample(k);
                let _ = p32.push(GyroSample::new(w), dt32);
                let _ = p64.push(GyroSample::new(w.to_f64()), dt);
            }
            let (end32, end64) = (p32.attitude(), p64.attitude());
            let i32_ = inputs(start32, end32, epoch_dt32, &noise32);
            let i64_ = inputs(start64, end64, epoch_dt, &noise64);
            let ir = round_inputs(&i64_);
            (start32, start64) = (end32, end64);
            naive.predict(&i32_.phi, &i32_.q);
            joseph.predict(&i32_.phi, &i32_.q);
            let _ = ud.predict(&i32_.phi, &i32_.q);
            let _ = ud_comp.predict_compensated(&i32_.phi, &i32_.q);
            let _ = ud_rounded.predict(&ir.phi, &ir.q);
            let _ = ud_comp_rounded.predict_compensated(&ir.phi, &ir.q);
            let iw = widen_inputs(&ir);
            reference_rounded.predict(&iw.phi, &iw.q);
            reference.predict(&i64_.phi, &i64_.q);
            let _ = ud64.predict(&i64_.phi, &i64_.q);
            for m in 0..2 {
                naive.update(&i32_.h[m], r32);
                joseph.update(&i32_.h[m], r32);
                let _ = ud.update(&i32_.h[m], r32);
                let _ = ud_comp.update(&i32_.h[m], r32);
                let _ = ud_rounded.update(&ir.h[m], r32);
                let _ = ud_comp_rounded.update(&ir.h[m], r32);
                reference_rounded.update(&iw.h[m], f64::from(r32));
                reference.update(&i64_.h[m], r64);
                let _ = ud64.update(&i64_.h[m], r64);
            }
            let r = reference.p;
            let forms = matrices64(&naive, &joseph, [&ud, &ud_comp, &ud_rounded, &ud_comp_rounded]);
            for (slot, p) in broken.iter_mut().zip(&forms) {
                if slot.is_none() {
                    if let Some(why) = invalid(p, &r) {
                        *slot = Some((k, why));
                    }
                }
            }
            if k.is_multiple_of(1_000_000) {
                bar.inc(1);
            }
        }
        let r = reference.p;
        let er = eigenvalues(&r);
        let forms = matrices64(&naive, &joseph, [&ud, &ud_comp, &ud_rounded, &ud_comp_rounded]);
        for (name, p) in FORMS.iter().zip(&forms) {
            let e = eigenvalues(p);
            let (err, i, j) = worst_element(p, &r);
            points.push(PointRow {
                form: (*name).into(),
                steps: k,
                max_rel_error: err,
                worst_element: format!("{}/{}", STATES[i], STATES[j]),
                min_eigenvalue: e[0],
                min_eigenvalue_ratio: e[0] / er[0],
                asymmetry: asymmetry(p),
            });
        }
        // Heading: δθ along the body's vertical g.
        let e64 = p64.attitude().normalized().expect("unit");
        let g = e64.conjugate().rotate(Vec3::new(0.0, 0.0, 1.0));
        let g = [g.x, g.y, g.z];
        let along = |p: &M64| {
            let mut v = 0.0;
            for i in 0..3 {
                for j in 0..3 {
                    v += g[i] * p[i][j] * g[j];
                }
            }
            v
        };
        let heading = along(&r);
        let corr: M64 = core::array::from_fn(|i| {
            core::array::from_fn(|j| r[i][j] / (r[i][i] * r[j][j]).sqrt())
        });
        let heading_error = forms.map(|p| along(&p) / heading - 1.0);
        refs.push(RefPoint {
            steps: k,
            eig: er,
            ud64_error: rel_error(&ud_matrix64(&ud64), &r),
            attitude_gap: p32.attitude().to_f64().angle_to(p64.attitude()),
            heading_sigma: heading.sqrt(),
            bias_sigma: ((r[3][3] + r[4][4] + r[5][5]) / 3.0).sqrt(),
            heading_error,
            rounded_f64_error: rel_error(&reference_rounded.p, &r),
            rounded_f64_heading_error: along(&reference_rounded.p) / heading - 1.0,
            corr_min_eig: eigenvalues(&corr).first().copied().unwrap_or(f64::NAN),
        });
    }
    Outcome {
        points,
        refs,
        invalid: broken,
        wall_s: started.elapsed().as_secs_f64(),
    }
}

// ---------------------------------------------------------------------------------------------------------
// Host timing.

/// ns per predict and per scalar update of each form (f32 forms, then the f64 Joseph and f64 Ud), on
/// recorded inputs: the best of 15 rounds of 1000 epochs each.
fn timing() -> Vec<(&'static str, f64, f64)> {
    let noise32 = GyroNoise::<f32>::from_datasheet(ARW_DEG_SQRT_H, RRW_DEG_H_SQRT_H).expect("noise");
    let noise64 = GyroNoise::<f64>::from_datasheet(ARW_DEG_SQRT_H, RRW_DEG_H_SQRT_H).expect("noise");
    let mut p32: Recommended<f32> = Propagator::recommended(Quat::IDENTITY).expect("identity");
    let mut p64: Recommended<f64> = Propagator::recommended(Quat::IDENTITY).expect("identity");
    let n = 1000;
    let mut in32 = Vec::with_capacity(n);
    let mut in64 = Vec::with_capacity(n);
    let (mut s32, mut s64) = (p32.attitude(), p64.attitude());
    for e in 0..n as u64 {
        for i in 0..PER_EPOCH {
            let w = rate((e * PER_EPOCH + i) as f64 * 1e-3);
            let _ = p32.push(
                GyroSample::new(Vec3::new(w.x as f32, w.y as f32, w.z as f32)),
                1e-3,
            );
            let _ = p64.push(GyroSample::new(w), 1e-3);
        }
        in32.push(inputs(s32, p32.attitude(), 1e-2, &noise32));
        in64.push(inputs(s64, p64.attitude(), 1e-2, &noise64));
        (s32, s64) = (p32.attitude(), p64.attitude());
    }
    let r = INCLINATION_SIGMA_DEG.to_radians().powi(2);
    let best = |f: &mut dyn FnMut() -> f64| (0..15).map(|_| f()).fold(f64::INFINITY, f64::min);
    macro_rules! time_form {
        ($state:expr, $ins:expr, $r:expr, $predict:expr, $update:expr) => {{
            let mut s = $state;
            let p = best(&mut || {
                let mut x = s;
                let t = Instant::now();
                for i in $ins.iter() {
                    $predict(&mut x, black_box(i));
                }
                black_box(&x);
                t.elapsed().as_secs_f64() * 1e9 / n as f64
            });
            // Updates on a predicted state (the state after the predicts, as a run has it).
            for i in $ins.iter() {
                $predict(&mut s, i);
            }
            let u = best(&mut || {
                let mut x = s;
                let t = Instant::now();
                for i in $ins.iter() {
                    $update(&mut x, black_box(&i.h[0]), $r);
                    $update(&mut x, black_box(&i.h[1]), $r);
                }
                black_box(&x);
                t.elapsed().as_secs_f64() * 1e9 / (2 * n) as f64
            });
            (p, u)
        }};
    }
    let dense_p = |x: &mut Dense<f32>, i: &Inputs<f32>| x.predict(&i.phi, &i.q);
    let dense_u = |x: &mut Dense<f32>, h: &[f32; 6], r: f32| x.update(h, r);
    let ud_p = |x: &mut Ud<f32, 6>, i: &Inputs<f32>| {
        let _ = x.predict(&i.phi, &i.q);
    };
    let ud_u = |x: &mut Ud<f32, 6>, h: &[f32; 6], r: f32| {
        let _ = x.update(h, r);
    };
    let ud_comp_p = |x: &mut Ud<f32, 6>, i: &Inputs<f32>| {
        let _ = x.predict_compensated(&i.phi, &i.q);
    };
    let dense64_p = |x: &mut Dense<f64>, i: &Inputs<f64>| x.predict(&i.phi, &i.q);
    let dense64_u = |x: &mut Dense<f64>, h: &[f64; 6], r: f64| x.update(h, r);
    let ud64_p = |x: &mut Ud<f64, 6>, i: &Inputs<f64>| {
        let _ = x.predict(&i.phi, &i.q);
    };
    let ud64_u = |x: &mut Ud<f64, 6>, h: &[f64; 6], r: f64| {
        let _ = x.update(h, r);
    };
    let r32 = r as f32;
    let ud0 = Ud::<f32, 6>::from_diagonal(initial()).expect("valid");
    let ud64 = Ud::<f64, 6>::from_diagonal(initial()).expect("valid");
    let a = time_form!(Dense::new(initial::<f32>(), false), in32, r32, dense_p, dense_u);
    let b = time_form!(Dense::new(initial::<f32>(), true), in32, r32, dense_p, dense_u);
    let c = time_form!(ud0, in32, r32, ud_p, ud_u);
    let cc = time_form!(ud0, in32, r32, ud_comp_p, ud_u);
    let d = time_form!(Dense::new(initial::<f64>(), true), in64, r, dense64_p, dense64_u);
    let e = time_form!(ud64, in64, r, ud64_p, ud64_u);
    vec![
        (FORMS[NAIVE], a.0, a.1),
        (FORMS[JOSEPH], b.0, b.1),
        (FORMS[UD], c.0, c.1),
        (FORMS[UD_COMP], cc.0, cc.1),
        ("f64 Joseph, symmetrized (the reference)", d.0, d.1),
        ("f64 U-D (covariance::Ud)", e.0, e.1),
    ]
}

// ---------------------------------------------------------------------------------------------------------
// The figure: a log-log panel per metric, composed into one image.

fn figure(dir: &Path, panels: &[(&str, Axis, Vec<Series>)], x: Axis) -> std::io::Result<()> {
    let tmp = std::env::temp_dir().join(format!("quatprop-lab-covariance-{}", std::process::id()));
    std::fs::create_dir_all(&tmp)?;
    let mut svgs = Vec::new();
    for (i, (title, y, s)) in panels.iter().enumerate() {
        let name = format!("panel{i}");
        plot(&tmp, &name, title, x, *y, s)?;
        svgs.push(std::fs::read_to_string(tmp.join(format!("{name}.svg")))?);
    }
    let _ = std::fs::remove_dir_all(&tmp);
    let size = |s: &str, attr: &str| -> f64 {
        s.split(&format!(" {attr}=\""))
            .nth(1)
            .and_then(|r| r.split('"').next())
            .and_then(|v| v.parse().ok())
            .unwrap_or(0.0)
    };
    let w = svgs.iter().map(|s| size(s, "width")).fold(0.0, f64::max);
    let h = svgs.iter().map(|s| size(s, "height")).fold(0.0, f64::max);
    let (cols, rows) = (2.0, (svgs.len() as f64 / 2.0).ceil());
    let (tw, th) = (w * cols, h * rows);
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{tw}\" height=\"{th}\" viewBox=\"0 0 {tw} {th}\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    for (i, s) in svgs.iter().enumerate() {
        let (cx, cy) = ((i % 2) as f64 * w, (i / 2) as f64 * h);
        out += &s.replacen("<svg ", &format!("<svg x=\"{cx}\" y=\"{cy}\" "), 1);
    }
    out += "</svg>\n";
    std::fs::write(dir.join("covariance.svg"), &out)?;
    png(&out, &dir.join("covariance.png"))
}

// ---------------------------------------------------------------------------------------------------------
// The study.

fn study(ctx: &mut Ctx, total: u64, page: bool) -> String {
    let bar = ctx.progress();
    let o = run(total, &bar);
    let times = timing();
    let at = |form: &str, k: u64, f: fn(&PointRow) -> f64| {
        o.points
            .iter()
            .find(|p| p.form == form && p.steps == k)
            .map_or(f64::NAN, f)
    };
    let summaries: Vec<SummaryRow> = FORMS
        .iter()
        .enumerate()
        .map(|(i, &form)| {
            let (invalid_at, why) = o.invalid[i].map_or((0, String::new()), |(k, w)| (k, w.into()));
            let t = times.iter().find(|t| t.0 == form);
            SummaryRow {
                form: form.into(),
                error_1e4: at(form, 10_000, |p| p.max_rel_error),
                error_1e6: at(form, 1_000_000, |p| p.max_rel_error),
                error_end: at(form, total, |p| p.max_rel_error),
                worst_element_end: o
                    .points
                    .iter()
                    .find(|p| p.form == form && p.steps == total)
                    .map_or(String::new(), |p| p.worst_element.clone()),
                min_eigenvalue_ratio_end: at(form, total, |p| p.min_eigenvalue_ratio),
                max_asymmetry: o
                    .points
                    .iter()
                    .filter(|p| p.form == form)
                    .map(|p| p.asymmetry)
                    .fold(0.0, f64::max),
                invalid_at,
                why,
                steps_end: total,
                ns_predict: t.map_or(f64::NAN, |t| t.1),
                ns_update: t.map_or(f64::NAN, |t| t.2),
            }
        })
        .collect();
    let table = if page {
        SummaryRow::render(&summaries)
    } else {
        ctx.rows(&o.points);
        ctx.table(&summaries)
    };
    // The figure.
    let series = |f: fn(&PointRow) -> f64| {
        FORMS
            .iter()
            .map(|&form| {
                let pts: Vec<(f64, f64)> = o
                    .points
                    .iter()
                    .filter(|p| p.form == form)
                    .map(|p| (p.steps as f64, f(p)))
                    .filter(|p| p.1 > 0.0 && p.1.is_finite())
                    .collect();
                Series::both(form, pts)
            })
            .filter(|s| !s.points.is_empty())
            .collect::<Vec<_>>()
    };
    let mut eig = series(|p| p.min_eigenvalue_ratio);
    for &form in &FORMS {
        let neg: Vec<(f64, f64)> = o
            .points
            .iter()
            .filter(|p| p.form == form && p.min_eigenvalue_ratio < 0.0)
            .map(|p| (p.steps as f64, -p.min_eigenvalue_ratio))
            .collect();
        if !neg.is_empty() {
            eig.push(Series {
                name: format!("{form}: negative, −λ_min / λ_min(f64)"),
                points: neg,
                line: false,
                marker: true,
                dashed: false,
                colour: None,
            });
        }
    }
    let mut spread = vec![
        Series::line(
            "reference λ_max (rad²)",
            o.refs.iter().map(|r| (r.steps as f64, r.eig[5])).collect(),
        ),
        Series::line(
            "reference λ_min (mixed units)",
            o.refs.iter().map(|r| (r.steps as f64, r.eig[0])).collect(),
        ),
    ];
    spread.push(
        Series::line(
            "heading variance (rad²)",
            o.refs
                .iter()
                .map(|r| (r.steps as f64, r.heading_sigma.powi(2)))
                .collect(),
        )
        .dashed(),
    );
    spread.push(
        Series::line(
            "bias variance ((rad/s)², mean of 3)",
            o.refs
                .iter()
                .map(|r| (r.steps as f64, r.bias_sigma.powi(2)))
                .collect(),
        )
        .dashed(),
    );
    let x = Axis {
        label: "attitude steps (1 kHz; covariance every 10)",
        log: true,
    };
    let panels = [
        (
            "max relative error against f64, |ΔP_ij| / sqrt(P_ii P_jj)",
            Axis {
                label: "max relative error",
                log: true,
            },
            {
                let mut e = series(|p| p.max_rel_error);
                e.push(
                    Series::line(
                        "f64 Joseph on the f32-rounded inputs (diagnostic)",
                        o.refs
                            .iter()
                            .map(|r| (r.steps as f64, r.rounded_f64_error))
                            .filter(|p| p.1 > 0.0 && p.1.is_finite())
                            .collect(),
                    )
                    .dashed(),
                );
                e
            },
        ),
        (
            "smallest eigenvalue of (P + Pᵀ)/2 over the f64 reference's",
            Axis {
                label: "λ_min / λ_min(f64)",
                log: true,
            },
            eig,
        ),
        (
            "asymmetry max|P − Pᵀ| / max|P| (exact zeros not drawn)",
            Axis {
                label: "asymmetry",
                log: true,
            },
            series(|p| p.asymmetry),
        ),
        (
            "the f64 reference: eigenvalue spread",
            Axis {
                label: "eigenvalue, variance",
                log: true,
            },
            spread,
        ),
    ];
    ctx.plot(|dir| figure(dir, &panels, x));
    markdown(&o, &summaries, &times, &table, total, page)
}

fn markdown(
    o: &Outcome,
    s: &[SummaryRow],
    times: &[(&str, f64, f64)],
    table: &str,
    total: u64,
    page: bool,
) -> String {
    let h1 = if page { "#" } else { "###" };
    let h2 = if page { "##" } else { "####" };
    let last = o.refs.last().expect("a checkpoint");
    let first = o.refs.first().expect("a checkpoint");
    let ud64_worst = o.refs.iter().map(|r| r.ud64_error).fold(0.0, f64::max);
    let ud64_at = |k: u64| {
        o.refs
            .iter()
            .find(|r| r.steps == k)
            .map_or(f64::NAN, |r| r.ud64_error)
    };
    let gap_max = o.refs.iter().map(|r| r.attitude_gap).fold(0.0, f64::max);
    let lowest = |form: &str| {
        o.points
            .iter()
            .filter(|p| p.form == form)
            .map(|p| p.min_eigenvalue_ratio)
            .fold(f64::INFINITY, f64::min)
    };
    let corr_min = o.refs.iter().map(|r| r.corr_min_eig).fold(f64::INFINITY, f64::min);
    let sigma_g = (ARW_DEG_SQRT_H.to_radians() / 60.0).powi(2);
    let q_epoch = sigma_g * PER_EPOCH as f64 * 1e-3;
    let v0 = first.heading_sigma.powi(2);
    let v1 = last.heading_sigma.powi(2);
    let plain = &s[UD];
    let comp = &s[UD_COMP];
    let he = last.heading_error;
    let t_of = |form: &str| times.iter().find(|t| t.0 == form).map_or((f64::NAN, f64::NAN), |t| (t.1, t.2));
    let (tp, tu) = t_of(FORMS[UD]);
    let (cp, cu) = t_of(FORMS[UD_COMP]);
    let comp_tracks = comp.invalid_at == 0
        && comp.error_end < 1e-2
        && comp.error_end < 0.2 * plain.error_end;
    // The f64 reference's own arithmetic on the f32-rounded inputs: the inputs' rounding alone.
    let inputs_err = last.rounded_f64_error;
    let inputs_explain = inputs_err >= 0.5 * plain.error_end;
    let cause = if comp_tracks {
        String::new()
    } else if inputs_explain {
        format!(
            "The f64 reference's own arithmetic fed the same inputs rounded to f32 (Φ, Q, h; nothing else \
             in f32) ends {inputs_err:.2e} off in the worst element and {:+.1}% in the heading variance: \
             rounding Φ to f32 alone accounts for the error. The rotation changes slowly, so consecutive \
             Φ are rounded nearly alike and their rounding does not average out over the 10⁸ steps; no \
             compensation of D can fix what is already in Φ.",
            100.0 * last.rounded_f64_heading_error
        )
    } else {
        format!(
            "The f64 reference's own arithmetic fed the same inputs rounded to f32 ends only {inputs_err:.2e} \
             off ({:+.1}% in the heading variance), so it is not the rounding of Φ, Q and h: it is the f32 \
             arithmetic outside D (ΦU and the reduced rows, U rounded at every step), which the compensated \
             predict leaves in f32.",
            100.0 * last.rounded_f64_heading_error
        )
    };
    let shipped = if comp_tracks {
        format!(
            "- **What the project ships.** `covariance::Ud` (Thornton predict, Bierman update) for the f32 \
             covariance, and `Ud::predict_compensated` for long unobserved horizons in f32: it stays valid to \
             the end (λ_min ratio {:.3} at the end, asymmetry 0) and tracks f64, error {:.1e} at 10⁴ steps, \
             {:.1e} at 10⁶, {:.1e} at {total:.0e} (plain `predict`: {:.1e}, {:.1e}, {:.1e}); heading variance \
             {:+.2}% from f64 at the end (plain {:+.1}%). It costs {cp:.0} ns per predict on this host against \
             {tp:.0} ns for `predict` ({:.1}×); the update is the same, {cu:.0} ns per scalar measurement \
             ({tu:.0} ns without the carried part). Where every state is observed, or the horizon is short, \
             `predict` is enough.\n",
            comp.min_eigenvalue_ratio_end,
            comp.error_1e4,
            comp.error_1e6,
            comp.error_end,
            plain.error_1e4,
            plain.error_1e6,
            plain.error_end,
            100.0 * he[UD_COMP],
            100.0 * he[UD],
            cp / tp,
        )
    } else {
        format!(
            "- **What the project ships.** `covariance::Ud` with the plain `predict` (Thornton) and \
             Bierman's `update` as the f32 covariance: with the compensated line, the only f32 forms valid \
             to the end with zero asymmetry (λ_min ratio {:.3} at the end), and the smallest full-f32 error \
             at 10⁶ steps ({:.1e}; naive {:.1e}, Joseph {:.1e}). `predict_compensated` does not track f64 \
             here: error {:.1e} at 10⁴ steps, {:.1e} at 10⁶, {:.1e} at {total:.0e} (plain `predict`: {:.1e}, \
             {:.1e}, {:.1e}); heading variance {:+.1}% from f64 at the end (plain {:+.1}%; fed the f64 inputs \
             rounded, compensated {:+.1}%, plain {:+.1}%). {cause} At {cp:.0} ns per predict against {tp:.0} ns \
             ({:.1}× on this host; the update is the same, {cu:.0} ns against {tu:.0} ns) it is not worth \
             its cost in this scenario; it remains the remedy where a variance sits still under increments \
             below its ulp (Φ near the identity on that state, as in the core's unit test), which this \
             tumbling run does not have. For a long unobserved horizon in f32 the way out is to observe the \
             heading (magnetometer, GNSS course) or {}.\n",
            plain.min_eigenvalue_ratio_end,
            plain.error_1e6,
            s[NAIVE].error_1e6,
            s[JOSEPH].error_1e6,
            comp.error_1e4,
            comp.error_1e6,
            comp.error_end,
            plain.error_1e4,
            plain.error_1e6,
            plain.error_end,
            100.0 * he[UD_COMP],
            100.0 * he[UD],
            100.0 * he[UD_COMP_ROUNDED],
            100.0 * he[UD_ROUNDED],
            cp / tp,
            if inputs_explain {
                "to form and apply Φ in f64"
            } else {
                "to keep the covariance in f64"
            },
        )
    };
    let joseph = if s[JOSEPH].invalid_at == 0 {
        "valid to the end here".to_string()
    } else {
        format!(
            "invalid first at step {} ({:.1} h: {})",
            s[JOSEPH].invalid_at,
            s[JOSEPH].invalid_at as f64 * 1e-3 / 3600.0,
            s[JOSEPH].why
        )
    };
    let findings = format!(
        "{h2} What the numbers say\n\n\
         {shipped}\
         - **Where the f32 forms' error at {total:.0e} comes from.** In f64 the heading variance goes from \
         {v0:.2e} to {v1:.2e} rad² ({:+.1}% over the run, angle random walk and bias walk together). At the \
         end it is off f64 by {:+.1}% in the f32 U-D, {:+.1}% compensated; fed the f64 inputs rounded to \
         f32, {:+.1}% and {:+.1}%; the f64 reference's arithmetic on those rounded inputs, {:+.1}% (max \
         element error {inputs_err:.2e}, the dashed line in the first panel). The angle random walk adds \
         Q_θθ = σ_g² Δt = {q_epoch:.1e} rad² per covariance step, {:.1e} of the heading variance, below half \
         an f32 ulp (6.0e-8 relative): a plain f32 sum would drop it if the variance stayed put, as the \
         core's unit test (Φ = I) shows. Here Φ turns the heading direction through the body axes at every \
         step, so D is recomputed, not incremented, and {}\n\
         - **The naive form does not fail here**, and that is not tuned away: its smallest eigenvalue over \
         the reference's is at least {:.3} at every checkpoint, and its asymmetry at most {:.1e}. The \
         eigenvalue spread ({:.1e} at the end, beyond 1/ε of f32) is mostly units: rad² against (rad/s)², a \
         diagonal scaling that floating point does not see. Scaled to a unit diagonal (the correlation \
         matrix), the reference's smallest eigenvalue is {corr_min:.1e} at its lowest, far above ε = \
         1.2e-7: the states are not correlated closely enough for f32 rounding of ΦPΦᵀ and (I − Kh)P to \
         cross zero. A scenario with a near-singular correlation (e.g. much smaller measurement noise, or \
         states that are nearly the same) would be needed to break it.\n\
         - **The symmetrized Joseph form in f32**: {joseph}; lowest λ_min ratio at the checkpoints {:.2}, \
         error {:.1e} at 10⁶ steps (naive {:.1e}, U-D {:.1e}). Evaluated as written, (I − Kh)P(I − Kh)ᵀ \
         recomputes every entry from products with the large heading-sized entries, where the naive update \
         subtracts one rank-one term; the rounding lands on the small bias entries, whose direction is the \
         smallest eigenvalue's (our reading of the measurement, not a proof). Symmetrizing removes the \
         asymmetry, not that error. The U-D forms' lowest λ_min ratio is {:.3} (plain) and {:.3} \
         (compensated).\n",
        100.0 * (v1 - v0) / v0,
        100.0 * he[UD],
        100.0 * he[UD_COMP],
        100.0 * he[UD_ROUNDED],
        100.0 * he[UD_COMP_ROUNDED],
        100.0 * last.rounded_f64_heading_error,
        q_epoch / v0,
        if comp_tracks {
            "keeping D's increments (the compensated line) is what brings the f32 U-D to f64.".to_string()
        } else if inputs_explain {
            "keeping D's increments (the compensated line) does not bring the f32 U-D to f64: the error is \
             the rounded Φ's, which the f64 arithmetic on the rounded inputs reproduces."
                .to_string()
        } else {
            "keeping D's increments (the compensated line) does not bring the f32 U-D to f64, though the \
             rounded inputs alone would allow it: the rest of the f32 arithmetic does not."
                .to_string()
        },
        lowest(FORMS[NAIVE]),
        s[NAIVE].max_asymmetry,
        last.eig[5] / last.eig[0],
        lowest(FORMS[JOSEPH]),
        s[JOSEPH].error_1e6,
        s[NAIVE].error_1e6,
        s[UD].error_1e6,
        lowest(FORMS[UD]),
        lowest(FORMS[UD_COMP]),
    );
    // A table on the page of its own; in the report, where every table is rendered from a CSV (and
    // checked against it), a list.
    let mut timing = if page {
        table::header(&["form", "ns per predict", "ns per scalar update"])
    } else {
        String::new()
    };
    for (name, p, u) in times {
        timing += &if page {
            format!("| {name} | {p:.0} | {u:.0} |\n")
        } else {
            format!("- {name}: {p:.0} ns per predict, {u:.0} ns per scalar update\n")
        };
    }
    let hours = total as f64 * 1e-3 / 3600.0;
    let valid: Vec<String> = s
        .iter()
        .map(|r| {
            if r.invalid_at == 0 {
                format!("{}: valid to the end", r.form)
            } else {
                format!(
                    "{}: invalid from step {} ({:.1} h: {})",
                    r.form,
                    r.invalid_at,
                    r.invalid_at as f64 * 1e-3 / 3600.0,
                    r.why
                )
            }
        })
        .collect();
    format!(
        "{h1} f32 covariance over {total:.0e} steps: naive, symmetrized Joseph, U-D and compensated U-D \
         against f64\n\n\
         ![covariance](covariance.png)\n\n\
         {h2} The run\n\n\
         {total:.0e} attitude steps at 1 kHz ({hours:.1} h of simulated time), {:.0} s on this machine, one \
         thread. The body rates are sums of three sines per axis at incommensurate frequencies (multiples of \
         √2, √3, √5, √7, √11 between 0.14 and 7 Hz), up to 1 rad/s per axis; `Propagator::recommended` \
         (ExpMap + History + FirstOrder) integrates them in f32 and in f64 from the same f32 samples and the \
         same f32 dt. The error state is `(δθ, δb)` with `q = q̂ ⊗ exp_q(δθ)`; gyro: ARW \
         {ARW_DEG_SQRT_H} °/√h, bias random walk {RRW_DEG_H_SQRT_H} °/h/√h \
         (`GyroNoise::from_datasheet`); initial σ {SIGMA0_ATTITUDE_DEG}° per attitude axis and \
         {SIGMA0_BIAS_DEG_S} °/s per bias axis, uncorrelated. Every 10 attitude steps the covariance is \
         propagated with `Step::between` (Φ of the 10 steps' rotation) and the inclination is observed: \
         the gravity direction in body axes, predicted `g = R(q̂)ᵀ e_z`, true `≈ g + [g×] δθ`, so the two \
         scalar measurements are the rows `hᵢ = (tᵢᵀ[g×], 0, 0, 0)` for unit `t₁, t₂ ⟂ g`, each of variance \
         ({INCLINATION_SIGMA_DEG}°)². Heading is never observed. No residual is applied (the study is the \
         covariance's arithmetic): every form sees the same sequence of Φ, Q, h, r.\n\n\
         **Inputs.** The f32 forms get Φ, Q and h computed in f32 (`Step::<f32>::between` on the f32 \
         propagator's attitudes), as a firmware would; the reference gets f64 ones from the f64 propagator. \
         So the f32 forms' error also holds the f32 inputs' (Φ, Q, h rounded, and the f32 attitude, which is \
         up to {gap_max:.1e} rad from the f64 one over the run). Two diagnostic lines, `f32 U-D, f64 inputs \
         rounded` and `f32 U-D compensated, f64 inputs rounded`, feed a `Ud<f32, 6>` the reference's own Φ, \
         Q and h rounded to f32: the difference from the lines above them is what computing the inputs in \
         f32 costs. A third diagnostic, drawn dashed in the first panel, runs the reference's own f64 \
         arithmetic on those rounded inputs: its error is what rounding Φ, Q and h to f32 costs alone, with \
         no f32 arithmetic at all.\n\n\
         **Reference.** The symmetrized Joseph form in f64. Its agreement with `Ud<f64, 6>` fed the same \
         inputs (max relative element difference): {:.1e} at 10³ steps, {:.1e} at 10⁶, {:.1e} at \
         {total:.0e}; worst over the checkpoints {ud64_worst:.1e}.\n\n\
         **Spread.** In the reference at 10³ steps the eigenvalues run from {:.1e} to {:.1e}; at \
         {total:.0e}, from {:.1e} to {:.1e} (ratio {:.1e}, against 1/ε = {:.1e} for f32). Heading σ: \
         {:.2}° at 10³ steps, {:.2}° at the end; bias σ: {:.1e} °/s at the end.\n\n\
         {h2} The forms\n\n\
         1. **naive f32**: `P ← ΦPΦᵀ + Q`; per scalar update `K = Phᵀ/(hPhᵀ + r)`, `P ← (I − Kh)P`.\n\
         2. **f32 Joseph, symmetrized**: the same predict, then `P ← (P + Pᵀ)/2`; per update \
         `P ← (I − Kh)P(I − Kh)ᵀ + K r Kᵀ`, then `(P + Pᵀ)/2`.\n\
         3. **f32 U-D**: `quatprop::covariance::Ud<f32, 6>` (Thornton predict, Bierman update). Its `P` is \
         formed in f64 from its f32 factors for the metrics (what the factors represent).\n\
         4. **f32 U-D, compensated**: the same factors, predicted with `Ud::predict_compensated` (Thornton's \
         predict with D summed from exact products with TwoSum and its low part carried to the next step), \
         updated with the same `update`. Its `P` is formed from `U` and `D` alone (the carried low part, below \
         D's ulp, is not exposed).\n\n\
         Metrics, at ten checkpoints per decade: max relative error against the reference, element (i, j) \
         relative to sqrt(P_ii P_jj) of the reference; the smallest eigenvalue of the symmetric part \
         (nalgebra, f64) over the reference's; the asymmetry max|P − Pᵀ| / max|P|. *Valid until*: the first \
         step at which, checked after every covariance step, an entry is NaN, a variance negative, the \
         symmetric part has a negative eigenvalue (an LDLᵀ pivot below −64 ε₆₄ of its diagonal entry) or the \
         relative error exceeds 1.\n\n{table}\n{}\n\n{findings}\n\
         {h2} Host cost\n\n\
         Best of 15 rounds of 1000 covariance steps on recorded inputs, this machine (shared, so read the \
         ratios): one predict (Φ, Q given) and one scalar update. The compensated predict costs {:.1}× the \
         plain one; both U-D lines run the same `update`. The diagnostic lines (f64 inputs rounded) are not \
         timed: their arithmetic is that of the line above them.\n\n{timing}",
        o.wall_s,
        ud64_at(1000),
        ud64_at(1_000_000),
        ud64_at(total),
        first.eig[0],
        first.eig[5],
        last.eig[0],
        last.eig[5],
        last.eig[5] / last.eig[0],
        1.0 / f64::from(f32::EPSILON),
        first.heading_sigma.to_degrees(),
        last.heading_sigma.to_degrees(),
        last.bias_sigma.to_degrees(),
        valid.join("; "),
        cp / tp,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The inclination rows see tilt and not heading: h·g = 0 for both rows, and they are orthonormal.
    #[test]
    fn inclination_rows_are_the_tilt() {
        let q = Quat::<f64>::from_rotation_vector(Vec3::new(0.3, -0.7, 1.1));
        let i = inputs(q, q, 0.01, &GyroNoise::from_datasheet(0.3, 10.0).unwrap());
        let g = q.conjugate().rotate(Vec3::new(0.0, 0.0, 1.0));
        for r in &i.h {
            let d = r[0] * g.x + r[1] * g.y + r[2] * g.z;
            assert!(d.abs() < 1e-15, "{d}");
            let n = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
            assert!((n - 1.0).abs() < 1e-15);
            assert_eq!(&r[3..], &[0.0; 3]);
        }
        // Small-angle check against the definition: a body-frame tilt δθ ⟂ g changes g by [g×]δθ.
        let dtheta = Vec3::new(1e-6, 2e-6, -1e-6);
        let truth = (q * Quat::from_rotation_vector(dtheta))
            .conjugate()
            .rotate(Vec3::new(0.0, 0.0, 1.0));
        let dg = truth - g;
        let a = [g.x, g.y, g.z];
        let e = unit3(cross([1.0, 0.0, 0.0], a));
        let t2 = cross(a, e);
        for (t, r) in [e, t2].iter().zip(&i.h) {
            let measured = t[0] * dg.x + t[1] * dg.y + t[2] * dg.z;
            let predicted = r[0] * dtheta.x + r[1] * dtheta.y + r[2] * dtheta.z;
            assert!((measured - predicted).abs() < 1e-11, "{measured} {predicted}");
        }
    }

    /// The dense forms and the core's Ud agree in f64 over a short run.
    #[test]
    fn reference_agrees_with_ud_f64() {
        let o = run(20_000, &indicatif::ProgressBar::hidden());
        for r in &o.refs {
            assert!(r.ud64_error < 1e-9, "{r:?}");
        }
        assert!(o.invalid[2].is_none());
    }

    #[test]
    fn checkpoints_are_multiples_of_ten_with_the_decades() {
        let c = checkpoints(100_000_000);
        assert!(c.iter().all(|k| k % 10 == 0));
        for d in [1_000, 10_000, 1_000_000, 100_000_000] {
            assert!(c.contains(&d), "{d}");
        }
    }
}
