//! Long horizon in f32: **own error** and **error against physical time**, separately, to 10⁸ steps at
//! 1 kHz (28 h of flight; `--long` 10⁹, `--quick` 10⁶).
//!
//! Every f32 run has an f64 shadow: the same scheme, input model and stabilizer in f64 (with the
//! float-float accumulator, so its own round-off stays far below what is measured), fed **the same f32
//! samples and the same f32 `dt`s** (their f64 values). The f32 run's *own error* is its angle to that
//! shadow: what f32 arithmetic adds, nothing else. For `FloatFloat` the state is `q + l`; its own error is
//! measured on the read-out `q` (what a user reads) and on `q + l` (what the state holds) separately. Its *error against physical time* is its angle to the exact motion at t = k·0.001 s
//! (double-double reference, `crate::dd`), which also holds the samples' rounding, the time base and the
//! scheme's truncation; the shadow's own error against physical time is printed beside it (the floor
//! that no f32 arithmetic can go below).
//!
//! The `dt`s come from `frontend::FixedPeriod::<f32>::new(1e-3)` (exact time base; the error of
//! dt = f32(0.001) is the time-base study's subject). Motions: a constant 1 rad/s about (0.36, −0.48, 0.80)
//! (the reference is the exact rotation of the f32 sample's rate), and coning α = 0.3 rad at Ω = 2π/√2
//! rad/s, a frequency incommensurate with the sample rate (a cone period that divides the sample rate
//! repeats the same roundings every period and locks the error: numerics notes). Input: rates (Hold,
//! Linear, History) or delta angles (the f32 rounding of the exact integral of the rate over each
//! interval, `DeltaAngles` with the `OnePlusPrevious` coning correction).

use crate::configs::scheme_name;
use crate::dd;
use crate::series;
use crate::plot::{plot, Axis, Series};
use crate::table::{self, cell, sci, Csv, Table};
use crate::args::{Horizon, ReportArgs};
use crate::report::Ctx;
use crate::study::{CsvFile, Study};
use quatprop::accumulate::{Accumulator, FloatFloat, Kahan, Plain};
use quatprop::frontend::FixedPeriod;
use quatprop::input::coning::OnePlusPrevious;
use quatprop::input::{DeltaAngles, History, Hold, InputModel, Linear};
use quatprop::scheme::{ExpMap, Scheme, SchemeKind};
use quatprop::stabilize::{FirstOrder, Stabilizer, StabilizerKind};
use quatprop::{DeltaAngle, GyroSample, Propagator, Quat, Real, Vec3};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The long horizon in f32 (sub-command `long-horizon`).
pub struct LongHorizon;

// The `Study` impl each study spells out (its name, files and run: lab/README.md, adding a study).
impl Study for LongHorizon {
    type Args = Horizon;
    const NAME: &'static str = "long-horizon";
    const ABOUT: &'static str = "f32 own error and error against physical time to 1e8 steps (--full; 1e7 by default, 1e9 with --long)";
    const CSV: &'static [CsvFile] = &[CsvFile::data::<PointRow>(), CsvFile::table::<SummaryRow>()];
    fn figures(&self) -> Vec<String> {
        [
            "long_horizon_own_constant",
            "long_horizon_own_coning",
            "long_horizon_physical",
            "long_horizon",
            "long_horizon_norm",
        ]
        .map(String::from)
        .to_vec()
    }
    fn report_args(&self, report: &ReportArgs) -> Horizon {
        report.horizon.clone()
    }
    fn run(&self, ctx: &mut Ctx, horizon: &Horizon) {
        let total = horizon.steps(ctx.scale);
        ctx.section("long horizon", |c| long_horizon(c, total));
    }
}

const AXIS: Vec3<f64> = dd::AXIS;
const ALPHA: f64 = 0.3;

/// The motion of a long run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// 1 rad/s about a skewed axis.
    Constant,
    /// Coning α = 0.3 rad at Ω = 2π/√2 rad/s (0.707 Hz).
    Coning,
}

impl Motion {
    pub fn name(self) -> &'static str {
        match self {
            Motion::Constant => "constant 1 rad/s",
            Motion::Coning => "coning 0.3 rad, Ω = 2π/√2",
        }
    }
    /// The body rate (rad/s) at sample k (physical time t = k·0.001 s).
    fn rate(self, k: u64, phase: &dd::ConePhase) -> Vec3<f64> {
        match self {
            Motion::Constant => AXIS,
            Motion::Coning => {
                let o = 2.0 * core::f64::consts::PI / core::f64::consts::SQRT_2;
                let (s, c) = phase.at(k).sin_cos();
                let s2 = (0.5 * ALPHA).sin();
                Vec3::new(
                    -o * ALPHA.sin() * s,
                    o * ALPHA.sin() * c,
                    -2.0 * o * s2 * s2,
                )
            }
        }
    }
    /// The angle increment ∫ω dt (rad) over the sample interval that ends at sample k ≥ 1, in f64 from
    /// closed forms (no quadrature error; the phase in double-double).
    fn increment(self, k: u64, phase: &dd::ConePhase) -> Vec3<f64> {
        match self {
            Motion::Constant => AXIS * 1e-3,
            Motion::Coning => {
                // ω = Ω·(−A sin φ, A cos φ, −2 sin²(α/2)), A = sin α, φ = Ωt: over [φ₀, φ₁],
                // ∫ωx = A(cos φ₁ − cos φ₀) = −2A sin φ_m sin(δ/2), ∫ωy = 2A cos φ_m sin(δ/2), ∫ωz = −2 sin²(α/2)·δ.
                let delta = phase.per_sample_angle();
                let mid = phase.at(k) - 0.5 * delta;
                let (s, c) = mid.sin_cos();
                let a = ALPHA.sin();
                let sh = (0.5 * delta).sin();
                let s2 = (0.5 * ALPHA).sin();
                Vec3::new(-2.0 * a * s * sh, 2.0 * a * c * sh, -2.0 * s2 * s2 * delta)
            }
        }
    }
    /// The exact attitude at sample k. The constant motion is the exact rotation of the f32 sample the
    /// stream carries: `constant` = (the f32 rate, per second) or (the f32 increment, per sample).
    fn attitude(self, k: u64, phase: &dd::ConePhase, constant: (Vec3<f64>, u32)) -> Quat<f64> {
        match self {
            Motion::Constant => dd::constant_rate_attitude(constant.0, dd::time(k, constant.1)),
            Motion::Coning => {
                let (s, c) = phase.at(k).sin_cos();
                let (sa, ca) = (0.5 * ALPHA).sin_cos();
                Quat::new(ca, sa * c, sa * s, 0.0)
            }
        }
    }
}

/// The lab's accumulators (every one quatprop has: `accumulate::{Plain, Kahan, FloatFloat}`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Acc {
    Plain,
    Kahan,
    FloatFloat,
}

impl Acc {
    pub const ALL: [Acc; 3] = [Acc::Plain, Acc::Kahan, Acc::FloatFloat];
    pub fn name(self) -> &'static str {
        match self {
            Acc::Plain => "Plain",
            Acc::Kahan => "Kahan",
            Acc::FloatFloat => "FloatFloat",
        }
    }
}

/// The input models of the study.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum In {
    Hold,
    Linear,
    History,
    /// Delta angles with the `OnePlusPrevious` coning correction.
    Delta,
}

impl In {
    pub const ALL: [In; 4] = [In::Hold, In::Linear, In::History, In::Delta];
    pub fn name(self) -> &'static str {
        match self {
            In::Hold => "Hold",
            In::Linear => "Linear",
            In::History => "History",
            In::Delta => "DeltaAngles(OnePlusPrevious)",
        }
    }
}

/// One f32 configuration and its f64 shadow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Run {
    pub group: &'static str,
    pub motion: Motion,
    pub scheme: SchemeKind,
    pub stabilizer: StabilizerKind,
    pub input: In,
    pub acc: Acc,
}

/// A stabilizer's name with its parameter (`Every(16)`).
fn stabilizer_name(z: StabilizerKind) -> String {
    match z {
        StabilizerKind::Every(n) => format!("Every({n})"),
        other => other.name().into(),
    }
}

impl Run {
    pub fn label(&self) -> String {
        format!(
            "{} + {} + {} + {}",
            scheme_name(self.scheme),
            self.input.name(),
            stabilizer_name(self.stabilizer),
            self.acc.name()
        )
    }
}

/// One checkpoint of one run.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PointRow {
    pub motion: String,
    pub configuration: String,
    pub steps: u64,
    /// Angle between the f32 attitude (the read-out `q`) and its f64 shadow (same f32 samples, same
    /// f32 dts) (rad).
    pub own_error_rad: f64,
    /// Angle between the f32 state and the shadow (rad): `q + l` (exact in f64) for FloatFloat, `q` for
    /// the others.
    pub state_own_error_rad: f64,
    /// Angle between the f32 state and the exact motion at t = steps·0.001 s (rad).
    pub physical_error_rad: f64,
    /// Angle between the f64 shadow and the exact motion (rad): the floor of the samples and scheme.
    pub f64_physical_error_rad: f64,
    /// |N| = ||q|² − 1| of the f32 state.
    pub abs_n: f64,
}
impl Csv for PointRow {
    const FILE: &'static str = "long_horizon.csv";
}

/// The summary of one run: the last three decades and the growth exponents.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SummaryRow {
    pub group: String,
    pub motion: String,
    pub configuration: String,
    pub steps_end: u64,
    pub own_error_at_end_over_100: f64,
    pub own_error_at_end_over_10: f64,
    pub own_error_at_end: f64,
    /// Least-squares slope of log(own error) against log(steps) over the last two decades.
    pub own_growth: f64,
    /// The state's own error (`q + l` for FloatFloat) at the end.
    pub state_own_error_at_end: f64,
    pub physical_error_at_end_over_100: f64,
    pub physical_error_at_end_over_10: f64,
    pub physical_error_at_end: f64,
    pub physical_growth: f64,
    pub f64_physical_error_at_end: f64,
    pub max_abs_n: f64,
}
// A row type names its file and renders its table through the `Csv` and `Table` impls (alike in each).
impl Csv for SummaryRow {
    const FILE: &'static str = "long_horizon_summary.csv";
}
impl Table for SummaryRow {
    fn render(rows: &[Self]) -> String {
        let n = rows.first().map_or(0, |r| r.steps_end) as f64;
        let (a, b, c) = (
            format!("{:.0e}", n / 100.0),
            format!("{:.0e}", n / 10.0),
            format!("{n:.0e}"),
        );
        let mut t = table::header(&[
            "group",
            "motion",
            "f32 configuration",
            &format!("own error {a}"),
            &format!("own {b}"),
            &format!("own {c}"),
            "own growth",
            &format!("state (q + l) own {c}"),
            &format!("physical-time error {a}"),
            &format!("physical {b}"),
            &format!("physical {c}"),
            "physical growth",
            &format!("f64 shadow, physical {c}"),
            "max \\|N\\|",
        ]);
        for r in rows {
            t += &format!(
                "| {} | {} | {} | {} | {} | {} | {:.2} | {} | {} | {} | {} | {:.2} | {} | {} |\n",
                r.group,
                cell(&r.motion),
                cell(&r.configuration),
                sci(r.own_error_at_end_over_100, 2),
                sci(r.own_error_at_end_over_10, 2),
                sci(r.own_error_at_end, 2),
                r.own_growth,
                sci(r.state_own_error_at_end, 2),
                sci(r.physical_error_at_end_over_100, 2),
                sci(r.physical_error_at_end_over_10, 2),
                sci(r.physical_error_at_end, 2),
                r.physical_growth,
                sci(r.f64_physical_error_at_end, 2),
                sci(r.max_abs_n, 1),
            );
        }
        t
    }
}

/// Checkpoints every half decade from 10³ to `total`.
fn checkpoints(total: u64) -> Vec<u64> {
    series::half_decades(1e3, total)
}

fn angle(a: Quat<f64>, b: Quat<f64>) -> f64 {
    match (a.normalized(), b.normalized()) {
        (Some(a), Some(b)) => a.angle_to(b),
        _ => f64::NAN,
    }
}

/// The input models as the library's types.
trait LongInput<T: Real>: InputModel<T> {
    /// Samples are angle increments (rad), not rates (rad/s).
    const DELTA: bool = false;
    fn fresh() -> Self;
    fn sample(v: Vec3<T>) -> Self::Sample;
}
impl<T: Real> LongInput<T> for Hold {
    fn fresh() -> Self {
        Hold
    }
    fn sample(v: Vec3<T>) -> GyroSample<T> {
        GyroSample::new(v)
    }
}
impl<T: Real> LongInput<T> for Linear<T> {
    fn fresh() -> Self {
        Linear::new()
    }
    fn sample(v: Vec3<T>) -> GyroSample<T> {
        GyroSample::new(v)
    }
}
impl<T: Real> LongInput<T> for History<T> {
    fn fresh() -> Self {
        History::new()
    }
    fn sample(v: Vec3<T>) -> GyroSample<T> {
        GyroSample::new(v)
    }
}
impl<T: Real> LongInput<T> for DeltaAngles<T, OnePlusPrevious> {
    const DELTA: bool = true;
    fn fresh() -> Self {
        DeltaAngles::new(OnePlusPrevious)
    }
    fn sample(v: Vec3<T>) -> DeltaAngle<T> {
        DeltaAngle::new(v)
    }
}

/// What an accumulator's state holds, in f64 (exact): `q + l` for FloatFloat, `q` for the others.
trait State: Accumulator<f32> {
    fn state(&self, q: Quat<f32>) -> Quat<f64> {
        q.to_f64()
    }
}
impl State for Plain {}
impl State for Kahan<f32> {}
impl State for FloatFloat<f32> {
    fn state(&self, q: Quat<f32>) -> Quat<f64> {
        let l = self.low().to_f64();
        let q = q.to_f64();
        Quat::new(q.w + l.w, q.x + l.x, q.y + l.y, q.z + l.z)
    }
}

/// The f32 run and its shadow in lock step; one point per checkpoint.
fn pair<S, Z, I32, I64, A>(
    r: &Run,
    s: S,
    z: Z,
    acc: A,
    total: u64,
    bar: &indicatif::ProgressBar,
) -> Vec<PointRow>
where
    S: Scheme<f32> + Scheme<f64>,
    Z: Stabilizer,
    I32: LongInput<f32>,
    I64: LongInput<f64>,
    A: State,
{
    let motion = r.motion;
    let phase = dd::ConePhase::over_sqrt2(1000);
    let q0 = motion.attitude(0, &phase, (AXIS, 1));
    let mut p32 = Propagator::new(Quat::<f32>::from_f64(q0), s, I32::fresh(), z)
        .expect("valid configuration")
        .with_accumulator(acc);
    let q0_32 = p32.attitude().to_f64();
    // The shadow starts where the f32 state starts (its rounded q0), so only the steps differ.
    let mut p64 = Propagator::new(q0_32, s, I64::fresh(), z)
        .expect("valid configuration")
        .with_accumulator(FloatFloat::new());
    let mut period = FixedPeriod::<f32>::new(1e-3).expect("valid period");
    // Sample k: the rate at t_k, or the increment over (t_{k−1}, t_k].
    let w_of = |k: u64| {
        Vec3::<f32>::from_f64(if I32::DELTA {
            motion.increment(k, &phase)
        } else {
            motion.rate(k, &phase)
        })
    };
    // A rate stream starts with the sample at t = 0 (no interval before it; Hold keeps nothing of it).
    // An increment stream has nothing at t = 0.
    if !I32::DELTA {
        let w = w_of(0);
        p32.start(I32::sample(w)).expect("finite sample");
        p64.start(I64::sample(w.to_f64())).expect("finite sample");
    }
    let constant = if I32::DELTA {
        (w_of(1).to_f64(), 1)
    } else {
        (w_of(0).to_f64(), 1000)
    };
    let mut out = Vec::new();
    let mut k = 0u64;
    let label = r.label();
    for c in checkpoints(total) {
        while k < c {
            k += 1;
            let w = w_of(k);
            let dt = period.next_dt();
            let _ = p32.push(I32::sample(w), dt);
            let _ = p64.push(I64::sample(w.to_f64()), dt as f64);
            if k.is_multiple_of(1_000_000) {
                bar.inc(1);
            }
        }
        let exact = motion.attitude(k, &phase, constant);
        let (q32, q64) = (p32.attitude().to_f64(), p64.attitude());
        let state = p32.accumulator().state(p32.attitude());
        out.push(PointRow {
            motion: motion.name().into(),
            configuration: label.clone(),
            steps: k,
            own_error_rad: angle(q32, q64),
            state_own_error_rad: angle(state, q64),
            physical_error_rad: angle(q32, exact),
            f64_physical_error_rad: angle(q64, exact),
            abs_n: p32.norm_error().abs() as f64,
        });
    }
    out
}

/// Dispatches a run to its monomorphized types.
fn run_one(r: &Run, total: u64, bar: &indicatif::ProgressBar) -> Vec<PointRow> {
    macro_rules! with_input {
        ($s:expr, $z:expr, $a:expr) => {
            match r.input {
                In::Hold => pair::<_, _, Hold, Hold, _>(r, $s, $z, $a, total, bar),
                In::Linear => pair::<_, _, Linear<f32>, Linear<f64>, _>(r, $s, $z, $a, total, bar),
                In::History => {
                    pair::<_, _, History<f32>, History<f64>, _>(r, $s, $z, $a, total, bar)
                }
                In::Delta => pair::<
                    _,
                    _,
                    DeltaAngles<f32, OnePlusPrevious>,
                    DeltaAngles<f64, OnePlusPrevious>,
                    _,
                >(r, $s, $z, $a, total, bar),
            }
        };
    }
    macro_rules! with_acc {
        ($s:expr, $z:expr) => {
            match r.acc {
                Acc::Plain => with_input!($s, $z, Plain),
                Acc::Kahan => with_input!($s, $z, Kahan::new()),
                Acc::FloatFloat => with_input!($s, $z, FloatFloat::new()),
            }
        };
    }
    // The exponential map with FirstOrder (the matrix) monomorphized; other rows through the runtime enums.
    if r.scheme == SchemeKind::ExpMap && r.stabilizer == StabilizerKind::FirstOrder {
        with_acc!(ExpMap, FirstOrder)
    } else {
        with_acc!(r.scheme, r.stabilizer)
    }
}

/// The runs: the accumulator × input matrix (ExpMap + FirstOrder) on both motions, every scheme on the
/// constant rate, every other post-step stabilizer on both motions.
pub fn runs() -> Vec<Run> {
    let mut v = Vec::new();
    for motion in [Motion::Constant, Motion::Coning] {
        for acc in Acc::ALL {
            for input in In::ALL {
                v.push(Run {
                    group: "accumulator × input",
                    motion,
                    scheme: SchemeKind::ExpMap,
                    stabilizer: StabilizerKind::FirstOrder,
                    input,
                    acc,
                });
            }
        }
    }
    // Every other scheme, plain and float-float (the Runge–Kutta schemes and Cf4 hand FloatFloat their step
    // as a rounded right factor with no low part; Magnus4 keeps its rotation vector's rounding like ExpMap).
    for acc in [Acc::Plain, Acc::FloatFloat] {
        for scheme in SchemeKind::ALL {
            if scheme != SchemeKind::ExpMap {
                v.push(Run {
                    group: "scheme",
                    motion: Motion::Constant,
                    scheme,
                    stabilizer: StabilizerKind::FirstOrder,
                    input: In::Hold,
                    acc,
                });
            }
        }
    }
    for motion in [Motion::Constant, Motion::Coning] {
        for stabilizer in [
            StabilizerKind::Off,
            StabilizerKind::Normalize,
            StabilizerKind::Every(16),
        ] {
            v.push(Run {
                group: "stabilizer",
                motion,
                scheme: SchemeKind::ExpMap,
                stabilizer,
                input: if motion == Motion::Coning {
                    In::History
                } else {
                    In::Hold
                },
                acc: Acc::Plain,
            });
        }
    }
    v
}

/// Least-squares slope of log(err) against log(steps) over the last two decades.
fn slope(points: &[(u64, f64)]) -> f64 {
    let last = points.last().map_or(1, |p| p.0) as f64;
    let sel: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| (p.0 as f64) >= last / 100.0 * 0.999)
        .map(|p| (p.0 as f64, p.1))
        .collect();
    series::log_slope(&sel)
}

fn summary(r: &Run, pts: &[PointRow]) -> SummaryRow {
    let end = pts.last().map_or(0, |p| p.steps);
    let at =
        |k: u64, f: fn(&PointRow) -> f64| pts.iter().find(|p| p.steps == k).map_or(f64::NAN, f);
    let own: Vec<(u64, f64)> = pts.iter().map(|p| (p.steps, p.own_error_rad)).collect();
    let phys: Vec<(u64, f64)> = pts
        .iter()
        .map(|p| (p.steps, p.physical_error_rad))
        .collect();
    SummaryRow {
        group: r.group.into(),
        motion: r.motion.name().into(),
        configuration: r.label(),
        steps_end: end,
        own_error_at_end_over_100: at(end / 100, |p| p.own_error_rad),
        own_error_at_end_over_10: at(end / 10, |p| p.own_error_rad),
        own_error_at_end: at(end, |p| p.own_error_rad),
        own_growth: slope(&own),
        state_own_error_at_end: at(end, |p| p.state_own_error_rad),
        physical_error_at_end_over_100: at(end / 100, |p| p.physical_error_rad),
        physical_error_at_end_over_10: at(end / 10, |p| p.physical_error_rad),
        physical_error_at_end: at(end, |p| p.physical_error_rad),
        physical_growth: slope(&phys),
        f64_physical_error_at_end: at(end, |p| p.f64_physical_error_rad),
        max_abs_n: pts.iter().map(|p| p.abs_n).fold(0.0, f64::max),
    }
}

fn long_horizon(ctx: &mut Ctx, total: u64) -> String {
    let runs = runs();
    let bar = ctx.progress();
    // Accuracy runs: independent, in parallel (rayon); nothing here is timed.
    let curves: Vec<Vec<PointRow>> = runs.par_iter().map(|r| run_one(r, total, &bar)).collect();
    let points: Vec<PointRow> = curves.iter().flatten().cloned().collect();
    ctx.rows(&points);
    let summaries: Vec<SummaryRow> = runs
        .iter()
        .zip(&curves)
        .map(|(r, c)| summary(r, c))
        .collect();
    let table = ctx.table(&summaries);
    let series =
        |sel: &dyn Fn(&Run) -> bool, f: fn(&PointRow) -> f64, name: &dyn Fn(&Run) -> String| {
            runs.iter()
                .zip(&curves)
                .filter(|(r, _)| sel(r))
                .map(|(r, c)| {
                    Series::both(
                        name(r),
                        c.iter()
                            .map(|p| (p.steps as f64, f(p).max(1e-16)))
                            .collect(),
                    )
                })
                .collect::<Vec<_>>()
        };
    let matrix = |m: Motion| move |r: &Run| r.group == "accumulator × input" && r.motion == m;
    let io_name = |r: &Run| format!("{} + {}", r.input.name(), r.acc.name());
    let steps_axis = Axis {
        label: "steps (1 kHz)",
        log: true,
    };
    let err_axis = |label| Axis { label, log: true };
    let mut physical = series(
        &|r| {
            r.group == "accumulator × input" && r.motion == Motion::Coning && r.input == In::History
        },
        |p| p.physical_error_rad,
        &|r| format!("f32 {}: against physical time", r.acc.name()),
    );
    physical.extend(series(
        &|r| {
            r.group == "accumulator × input" && r.motion == Motion::Coning && r.input == In::History
        },
        |p| p.own_error_rad,
        &|r| format!("f32 {}: own error", r.acc.name()),
    ));
    physical.extend(
        series(
            &|r| {
                r.group == "accumulator × input"
                    && r.motion == Motion::Coning
                    && r.input == In::History
                    && r.acc == Acc::Plain
            },
            |p| p.f64_physical_error_rad,
            &|_| "f64 shadow (same f32 samples): against physical time".into(),
        )
        .into_iter()
        .map(Series::dashed),
    );
    let scheme_acc = |r: &Run| format!("{} + {}", scheme_name(r.scheme), r.acc.name());
    let mut schemes = series(&|r| r.group == "scheme", |p| p.own_error_rad, &scheme_acc);
    schemes.extend(series(
        &|r| {
            r.group == "accumulator × input"
                && r.motion == Motion::Constant
                && r.input == In::Hold
                && r.acc != Acc::Kahan
        },
        |p| p.own_error_rad,
        &scheme_acc,
    ));
    let norm = series(
        &|r| {
            r.motion == Motion::Coning
                && (r.group == "stabilizer"
                    || (r.group == "accumulator × input"
                        && r.input == In::History
                        && r.acc == Acc::Plain))
        },
        |p| p.abs_n.max(1e-18),
        &|r| stabilizer_name(r.stabilizer),
    );
    let plots: [(&str, &str, Axis, Vec<Series>); 5] = [
        (
            "long_horizon_own_constant",
            "Constant 1 rad/s, f32 ExpMap + FirstOrder: own error per input and accumulator",
            err_axis("own error: angle to the f64 shadow (rad)"),
            series(&matrix(Motion::Constant), |p| p.own_error_rad, &io_name),
        ),
        (
            "long_horizon_own_coning",
            "Coning at Ω = 2π/√2, f32 ExpMap + FirstOrder: own error per input and accumulator",
            err_axis("own error: angle to the f64 shadow (rad)"),
            series(&matrix(Motion::Coning), |p| p.own_error_rad, &io_name),
        ),
        (
            "long_horizon_physical",
            "Coning, History: own error and error against physical time are different numbers",
            err_axis("attitude error (rad)"),
            physical,
        ),
        (
            "long_horizon",
            "Constant 1 rad/s, f32, Hold + FirstOrder: own error of every scheme, Plain and FloatFloat",
            err_axis("own error: angle to the f64 shadow (rad)"),
            schemes,
        ),
        (
            "long_horizon_norm",
            "Coning, f32 ExpMap: |N| = ||q|² − 1| per post-step stabilizer",
            err_axis("|N| (dimensionless)"),
            norm,
        ),
    ];
    for (name, title, y, s) in plots {
        ctx.plot(|dir| plot(dir, name, title, steps_axis, y, &s));
    }
    let find = |m: Motion, i: In, a: Acc| {
        summaries
            .iter()
            .zip(&runs)
            .find(|(_, r)| {
                r.group == "accumulator × input" && r.motion == m && r.input == i && r.acc == a
            })
            .map(|(s, _)| s.clone())
    };
    let mut headline = String::new();
    if let (Some(p), Some(k), Some(f), Some(c)) = (
        find(Motion::Coning, In::History, Acc::Plain),
        find(Motion::Coning, In::History, Acc::Kahan),
        find(Motion::Coning, In::History, Acc::FloatFloat),
        find(Motion::Constant, In::Hold, Acc::FloatFloat),
    ) {
        headline = format!(
            "On incommensurate coning with the sample history after {total:.0e} steps, plain f32 is {:.2e} rad from its \
             f64 shadow (growth exponent {:.2}) and {:.2e} rad from the physical motion; Kahan's own error is \
             {:.2e} rad (exponent {:.2}) and its physical-time error {:.2e} rad. The shadow itself is {:.2e} rad \
             from the physical motion: that is the f32 samples' rounding (the cone's constant axial rate \
             −2Ω sin²(α/2) rounds the same way every sample, a biased floor that grows linearly), and an f32 run can \
             land closer to the physical motion than its own shadow only by its arithmetic error cancelling part \
             of that floor, which is why the own error is the measure of the arithmetic. FloatFloat's own error \
             on the same stream is {:.2e} rad (exponent {:.2}), and {:.2e} rad on the constant rate: below the \
             rounding of an f32 attitude itself (half an ulp of each component, up to {:.1e} rad) at every \
             checkpoint; its physical-time error is {:.2e} rad, the shadow's. The Runge–Kutta schemes and Cf4 \
             hand FloatFloat a rounded right factor (no low part), so their own error still grows linearly \
             (the \"scheme\" rows). ",
            p.own_error_at_end,
            p.own_growth,
            p.physical_error_at_end,
            k.own_error_at_end,
            k.own_growth,
            k.physical_error_at_end,
            k.f64_physical_error_at_end,
            f.own_error_at_end,
            f.own_growth,
            c.own_error_at_end,
            f64::from(f32::EPSILON),
            f.physical_error_at_end,
        );
    }
    format!(
        "### Long horizon in f32: own error and error against physical time\n\n\
         ![own error, constant rate](long_horizon_own_constant.png)\n\n\
         ![own error, coning](long_horizon_own_coning.png)\n\n\
         ![own and physical-time error](long_horizon_physical.png)\n\n\
         ![every scheme](long_horizon.png)\n\n![norm](long_horizon_norm.png)\n\n\
         At 1 kHz, {total:.0e} steps. Every f32 run has an **f64 shadow**: the same scheme, input model and \
         stabilizer in f64 (Kahan-compensated), fed the same f32 samples and the same f32 dts. **Own error** = \
         the f32 state's angle to its shadow: what f32 arithmetic adds. **Error against physical time** = its \
         angle to the exact motion at t = k·0.001 s (double-double reference): that also holds the samples' \
         rounding, the time base and the scheme's truncation, and it can pass through zero by cancellation, \
         which is why it is not the measure of the arithmetic. The shadow's own physical-time error is the \
         floor no f32 arithmetic can go below. dts from `FixedPeriod::<f32>::new(1e-3)` (exact time base; \
         dt = f32(0.001) costs 4.75e-3 rad at 10⁸ whatever the arithmetic: see the time-base study). Constant \
         rate: 1 rad/s about (0.36, −0.48, 0.80) from the identity, reference the exact rotation of the f32 \
         sample's rate. Coning: α = 0.3 rad at Ω = 2π/√2 rad/s, incommensurate with 1 kHz (a commensurate \
         cone repeats its roundings every period and locks the error), f32 samples of the exact rate, \
         reference the exact motion. Delta angles: the f32 rounding of the exact increment over each interval, \
         `DeltaAngles` with `OnePlusPrevious` (the constant rate's reference is then the exact rotation of the \
         f32 increment, so its floor is the shadow's arithmetic alone). For FloatFloat the state is `q + l`: \
         \"state own error\" is the angle of `q + l` (exact in f64) to the shadow, the read-out `q` adds its \
         own rounding (the other accumulators' state is `q`). Growth exponent: slope of log error against log steps over the last two \
         decades (1 a biased drift, ½ a random walk). No Baumgarte row: since quatprop 0.2 it is a right-hand-side \
         option of the Runge–Kutta schemes, not a post-step stabilizer.\n\n{headline}\n\n{table}"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shadow is what it claims: with the same f32 samples and dts, an f64 run of the same
    /// configuration; its own physical-time error on the constant rate is tiny (Hold is exact there), so
    /// the f32 run's own and physical-time errors agree.
    #[test]
    fn shadow_tracks_physical_time_on_a_constant_rate() {
        let r = Run {
            group: "test",
            motion: Motion::Constant,
            scheme: SchemeKind::ExpMap,
            stabilizer: StabilizerKind::FirstOrder,
            input: In::Hold,
            acc: Acc::Plain,
        };
        let pts = run_one(&r, 100_000, &indicatif::ProgressBar::hidden());
        let last = pts.last().unwrap();
        assert_eq!(last.steps, 100_000);
        assert!(last.f64_physical_error_rad < 1e-12, "{last:?}");
        assert!(
            (last.own_error_rad - last.physical_error_rad).abs() < 1e-11,
            "{last:?}"
        );
        assert!(last.own_error_rad > 0.0);
    }

    #[test]
    fn checkpoints_include_the_decades() {
        let c = checkpoints(100_000_000);
        for d in [1_000_000, 10_000_000, 100_000_000] {
            assert!(c.contains(&d));
        }
    }
}
