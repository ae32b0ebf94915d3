//! Work–precision: attitude error (final and maximum over the horizon) against cost per gyro sample, for
//! configurations of quatprop and the peers on the same sample streams of a scene.
//!
//! Cost is host time per sample (the least of repeated in-process runs at the core's quiet speed, see
//! `crate::quiet`) and, for quatprop f32
//! configurations the firmware bench measured, Cortex-M4F instructions per simulated second
//! (`firmware/bench-m4f.csv`, written by `python3 firmware/figures.py`). The f32 arithmetic is bit-identical
//! on the M4F and the host (tests/firmware_snapshot.rs), so the host's error is the target's error.

use crate::m4f_bench::{self, BenchRow};
use crate::args::Sweep;
use crate::configs::{
    error_kind, full_grid, scheme_name, scheme_set, Acc, Config, Input, LabReal, Peer, Precision, Stab,
};
use crate::plot::{plot, Axis, Series};
use crate::report::Ctx;
use crate::scene::{attitude_error, stream, Scene};
use crate::scenes;
use crate::scale::Scale;
use crate::study::{CsvFile, Study};
use crate::table::{self, cell, Csv, Table};
use quatprop::scheme::SchemeKind;
use quatprop::{Error, Quat};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::time::{Duration, Instant};

/// Work–precision (sub-command `work-precision`).
pub struct WorkPrecision;

impl Study for WorkPrecision {
    type Args = Sweep;
    const NAME: &'static str = "work-precision";
    const ABOUT: &'static str = "Error against cost per scene and precision, quatprop against the peers";
    // The files it writes, one a line (a list, as every study's).
    const CSV: &'static [CsvFile] = &[
        CsvFile::table::<WpHeadline>(),
        CsvFile::table::<EqualCostRow>(),
        CsvFile::table::<PeerLoopRow>(),
        CsvFile::data::<WpScenes>(),
        CsvFile::table::<SceneSummaryRow>(),
        CsvFile::table::<WpStabilizers>(),
        CsvFile::data::<WpGrid>(),
        CsvFile::table::<M4fRow>().optional(),
    ];
    fn figures(&self) -> Vec<String> {
        let mut v = vec!["work_precision_coning_f32".to_string()];
        for s in scenes::catalogue(0.0) {
            for p in [Precision::F32, Precision::F64] {
                v.push(format!("wp_{}_{}", s.key(), p.name()));
            }
        }
        for p in [Precision::F32, Precision::F64] {
            v.push(format!("wp_stabilizers_coning_{}", p.name()));
        }
        if m4f_bench().is_some() {
            v.push("wp_m4f_coning_f32".into());
        }
        v
    }
    fn run(&self, ctx: &mut Ctx, sweep: &Sweep) {
        let opt = Options::new(sweep, ctx.scale);
        // The rigid bodies' references are tabulated once, long enough for every sweep.
        let catalogue = scenes::catalogue(opt.horizon.unwrap_or(0.0).max(70.0));
        let coning = scenes::Coning;
        if opt.scenes.is_empty() || opt.scenes.iter().any(|s| s == "coning") {
            let mut o = opt.clone();
            o.precisions = vec![Precision::F32];
            ctx.section("work-precision", |c| headline(c, &coning, &o));
        }
        let mut motions = Vec::new();
        ctx.section("wp per scene", |c| per_scene(c, &catalogue, &opt, &mut motions));
        ctx.section("wp equal cost", |c| equal_cost(c, &motions, &opt));
        if opt.scenes.is_empty() {
            ctx.section("wp stabilizers", |c| stabilizers(c, &coning, &opt));
            ctx.section("wp grid + M4F", |c| grid_with_m4f(c, &coning, &opt));
        }
    }
}

/// One measured point: a configuration at one sample rate.
#[derive(Clone, Debug)]
pub struct Point {
    pub config: Config,
    pub hz: u32,
    pub samples: usize,
    pub final_err: f64,
    pub max_err: f64,
    pub ns_per_sample: f64,
    pub refused: u64,
    pub first_error: Option<Error>,
    /// Timed runs at the core's quiet speed (`crate::quiet`); the cost is the least of them, or of every
    /// run when there is none.
    pub quiet_runs: usize,
}

impl Point {
    /// Usable in plots and equal-cost comparisons: no step refused, a finite error.
    pub fn accepted(&self) -> bool {
        self.refused == 0 && self.max_err.is_finite()
    }
}

/// How a sweep times its configurations.
#[derive(Clone, Copy, Debug)]
pub struct Timing {
    /// Quiet runs wanted for each configuration at each rate (its cost is the least of them).
    pub runs: usize,
    /// Least wall time of a sweep's timed rounds.
    pub window: Duration,
    /// How long the quiet-core probe must have been watched in this process before its least time is
    /// trusted as the quiet speed.
    pub calibration: Duration,
    /// A sweep stops timing after this long even if a configuration has too few quiet runs (its point's
    /// `quiet_runs` says so, and the study's text). Zero: `runs` timed rounds whatever the probe says (and
    /// no calibration).
    pub cap: Duration,
}

impl Timing {
    /// `--quick`: one timed round after the warm-up.
    pub const QUICK: Timing = Timing {
        runs: 1,
        window: Duration::ZERO,
        calibration: Duration::ZERO,
        cap: Duration::ZERO,
    };
    /// The default scale: 3 quiet runs each, over at least 1 s, no calibration wait, at most 4 s per sweep
    /// (the report's 21 sweeps in well under a minute; a slow spell of the shared core, up to ~40 s, ends a
    /// sweep's timing at the cap, and the text lists its points).
    pub const DEFAULT: Timing = Timing {
        runs: 3,
        window: Duration::from_secs(1),
        calibration: Duration::ZERO,
        cap: Duration::from_secs(4),
    };
    /// `--full`: 15 quiet runs each, over at least 10 s, the probe watched for 60 s, at most 180 s per sweep.
    pub const FULL: Timing = Timing {
        runs: 15,
        window: Duration::from_secs(10),
        calibration: Duration::from_secs(60),
        cap: Duration::from_secs(180),
    };
}

/// Runs `configs` on `scene` at each rate: accuracy at 64 checkpoints, then timed runs of each
/// configuration at each rate, interleaved (one run of every configuration at every rate per round, after a
/// warm-up round), with the quiet-core probe (`crate::quiet`) timed between runs. Rounds go on until every
/// configuration has `timing.runs` quiet runs, `timing.window` has passed and the probe is calibrated (or
/// `Timing::CAP` has passed); each configuration's cost is its least quiet run.
pub fn sweep<T: LabReal>(
    ctx: &mut Ctx,
    scene: &dyn Scene,
    configs: &[Config],
    rates: &[u32],
    horizon: f64,
    timing: Timing,
) -> Vec<Point> {
    let mut points = Vec::new();
    // Each rate's stream, initial attitude and points, kept for the timed rounds.
    let mut streams = Vec::new();
    for &hz in rates {
        let (samples, dt) = stream::<T>(scene, hz, horizon);
        let n = samples.len() - 1;
        // Checkpoints at even sample indices (the mid input steps over pairs of intervals).
        let mut cps: Vec<usize> = (1..=64).map(|j| 2 * ((j * n) / 128)).collect();
        cps.dedup();
        cps.retain(|&c| c > 0);
        let exact: Vec<Quat<f64>> = cps.iter().map(|&c| scene.attitude(c as f64 * dt)).collect();
        let q0 = Quat::<T>::from_f64(scene.attitude(0.0));
        let first = points.len();
        for &config in configs {
            ctx.tick();
            let Ok(mut run) = config.build::<T>(q0, samples[1].dt) else {
                continue; // a peer without this precision
            };
            let (mut from, mut max_err, mut final_err) = (0usize, 0.0f64, f64::NAN);
            for (&c, &ex) in cps.iter().zip(&exact) {
                run.feed(&samples[from..=c]);
                from = c + 1;
                final_err = attitude_error(run.attitude(), ex);
                max_err = if final_err.is_nan() {
                    f64::NAN
                } else {
                    max_err.max(final_err)
                };
            }
            let (refused, first_error) = run.refused();
            points.push(Point {
                config,
                hz,
                samples: n,
                final_err,
                max_err,
                ns_per_sample: f64::NAN,
                refused,
                first_error,
                quiet_runs: 0,
            });
        }
        streams.push((samples, q0, first..points.len()));
    }
    // Timed rounds; round 0 warms up. Each run: (ns per sample, the slower probe on its two sides).
    let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new(); points.len()];
    let started = Instant::now();
    let mut before = ctx.quiet.probe();
    for round in 0.. {
        let t_round = Instant::now();
        ctx.tick();
        for (samples, q0, range) in &streams {
            for i in range.clone() {
                let Some(ns) = points[i].config.time_run::<T>(*q0, samples) else {
                    continue;
                };
                let after = ctx.quiet.probe();
                if round > 0 {
                    runs[i].push((ns, before.max(after)));
                }
                before = after;
            }
        }
        ctx.quiet.watched(t_round.elapsed());
        if round < timing.runs {
            continue;
        }
        let elapsed = started.elapsed();
        let quiet = &ctx.quiet;
        let enough = runs
            .iter()
            .all(|r| r.iter().filter(|&&(_, p)| quiet.is_quiet(p)).count() >= timing.runs);
        if timing.cap.is_zero()
            || (enough && elapsed >= timing.window && quiet.calibrated(timing.calibration))
            || elapsed >= timing.cap
        {
            break;
        }
    }
    for (p, r) in points.iter_mut().zip(&runs) {
        let least = |quiet_only: bool| {
            r.iter()
                .filter(|&&(_, probe)| !quiet_only || ctx.quiet.is_quiet(probe))
                .map(|&(ns, _)| ns)
                .fold(f64::INFINITY, f64::min)
        };
        p.quiet_runs = r
            .iter()
            .filter(|&&(_, probe)| ctx.quiet.is_quiet(probe))
            .count();
        let ns = if p.quiet_runs > 0 {
            least(true)
        } else {
            least(false)
        };
        p.ns_per_sample = if ns.is_finite() { ns } else { f64::NAN };
    }
    points
}

/// What a study's text says about its timing: the rule, and the points without enough quiet runs.
pub fn timing_note(points: &[Point], timing: Timing) -> String {
    let short: Vec<String> = points
        .iter()
        .filter(|p| p.quiet_runs < timing.runs)
        .map(|p| format!("{} at {} Hz ({})", p.config.label(), p.hz, p.quiet_runs))
        .collect();
    let until = if timing.calibration.is_zero() {
        format!(
            "{} quiet runs and at least {} s had passed, for at most {} s per sweep (the default scale: no wait \
             for the probe's calibration, so a sweep that ran entirely in a slow spell reads slow; `--full` \
             watches the probe for {} s first and wants {} quiet runs)",
            timing.runs,
            timing.window.as_secs(),
            timing.cap.as_secs(),
            Timing::FULL.calibration.as_secs(),
            Timing::FULL.runs,
        )
    } else {
        format!(
            "{} quiet runs, at least {} s had passed and the probe had been watched for {} s in this process",
            timing.runs,
            timing.window.as_secs(),
            timing.calibration.as_secs(),
        )
    };
    let rule = format!(
        "Host time: each configuration's least run among its runs at the core's quiet speed; the runs are \
         interleaved over every configuration and rate, a fixed probe workload is timed between them, and a run \
         counts as quiet when the probes on both sides are within {:.0} % of the probe's least time in this \
         process (this machine is a shared VM on which the same code alternates between two speeds; see \
         `lab/src/quiet.rs`). Rounds continued until every configuration had {until}.",
        100.0 * crate::quiet::Quiet::TOLERANCE,
    );
    if timing.cap.is_zero() {
        "Host time: one timed run after a warm-up (`--quick`: not a measurement of record)."
            .to_string()
    } else if short.is_empty() {
        rule
    } else if short.len() <= 12 {
        format!(
            "{rule} **Fewer quiet runs** (after {} s; the cost is then the least of all runs): {}.",
            timing.cap.as_secs(),
            short.join(", ")
        )
    } else {
        format!(
            "{rule} **Fewer quiet runs** (after {} s; the cost is then the least of all runs): {} of the {} \
             points, among them {}.",
            timing.cap.as_secs(),
            short.len(),
            points.len(),
            short[..3].join(", ")
        )
    }
}

/// One measured point as a CSV row (every work-precision CSV has these columns).
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct WpRow {
    pub scene: String,
    pub precision: String,
    pub configuration: String,
    pub is_peer: bool,
    pub rate_hz: u32,
    pub samples: u64,
    pub final_error_rad: f64,
    pub max_error_rad: f64,
    pub host_ns_per_sample: f64,
    pub refused_steps: u64,
    /// The first refusal's error (empty: none).
    pub first_error: String,
    /// Its variant name (empty: none).
    pub error_kind: String,
}

impl WpRow {
    fn accepted(&self) -> bool {
        self.refused_steps == 0 && self.max_error_rad.is_finite()
    }
    /// "final / max" or the refusal.
    fn errors(&self) -> String {
        if self.refused_steps > 0 {
            format!("refused {} steps ({})", self.refused_steps, self.error_kind)
        } else {
            format!("{:.2e} / {:.2e}", self.final_error_rad, self.max_error_rad)
        }
    }
}

/// Typed rows of one scene and precision.
pub fn wp_rows(scene: &str, prec: Precision, points: &[Point]) -> Vec<WpRow> {
    points
        .iter()
        .map(|p| WpRow {
            scene: scene.into(),
            precision: prec.name().into(),
            configuration: p.config.label(),
            is_peer: p.config.is_peer(),
            rate_hz: p.hz,
            samples: p.samples as u64,
            final_error_rad: p.final_err,
            max_error_rad: p.max_err,
            host_ns_per_sample: p.ns_per_sample,
            refused_steps: p.refused,
            first_error: p.first_error.map_or(String::new(), |e| format!("{e:?}")),
            error_kind: if p.first_error.is_some() {
                error_kind(p.first_error)
            } else {
                String::new()
            },
        })
        .collect()
}

/// A work-precision CSV file: [`WpRow`]s under their own file name.
macro_rules! wp_file {
    ($(#[$m:meta])* $name:ident, $file:literal) => {
        $(#[$m])*
        #[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
        #[serde(transparent)]
        pub struct $name(pub WpRow);
        impl Csv for $name {
            const FILE: &'static str = $file;
        }
    };
}
wp_file!(
    /// The per-scene sweeps.
    WpScenes,
    "work_precision_scenes.csv"
);
wp_file!(
    /// The stabilizers side by side (also a table: configurations down, rates across).
    WpStabilizers,
    "work_precision_stabilizers.csv"
);
wp_file!(
    /// The full grid.
    WpGrid,
    "work_precision_grid.csv"
);
wp_file!(
    /// The headline sweep (also a table at the reference rate).
    WpHeadline,
    "work_precision_coning_f32.csv"
);

/// The reference rate of a table from the rates in its rows.
fn rows_rate(rows: &[WpRow]) -> u32 {
    let mut rates: Vec<u32> = rows.iter().map(|r| r.rate_hz).collect();
    rates.sort_unstable();
    rates.dedup();
    if rates.is_empty() {
        0
    } else {
        table_rate(&rates)
    }
}

impl Table for WpStabilizers {
    fn render(rows: &[Self]) -> String {
        by_rate(
            rows,
            ["configuration", "precision"],
            |hz| format!("{hz} Hz: max error / ns"),
            |r| (r.0.configuration.as_str(), r.0.precision.as_str(), r.0.rate_hz),
            |r| {
                if r.0.accepted() {
                    format!("{:.2e} / {:.1}", r.0.max_error_rad, r.0.host_ns_per_sample)
                } else {
                    r.0.errors()
                }
            },
        )
    }
}

/// A table of one line per pair of keys (in the order of the rows) and one column per rate (ascending):
/// `key` gives a row's two keys and rate, `rate_title` a rate column's title, `text` a cell's text (`–`
/// where no row has that line's keys at that rate). The first key is escaped for the table.
fn by_rate<'a, R>(
    rows: &'a [R],
    key_titles: [&str; 2],
    rate_title: impl Fn(u32) -> String,
    key: impl Fn(&'a R) -> (&'a str, &'a str, u32),
    text: impl Fn(&R) -> String,
) -> String {
    let mut rates: Vec<u32> = rows.iter().map(|r| key(r).2).collect();
    rates.sort_unstable();
    rates.dedup();
    let mut cols: Vec<String> = key_titles.iter().map(|k| k.to_string()).collect();
    cols.extend(rates.iter().map(|&hz| rate_title(hz)));
    let mut t = table::header(&cols.iter().map(String::as_str).collect::<Vec<_>>());
    let lines = table::distinct(rows, |r| {
        let (a, b, _) = key(r);
        (a, b)
    });
    for (a, b) in lines {
        t += &format!("| {} | {b} |", cell(a));
        for &hz in &rates {
            match rows.iter().find(|r| key(r) == (a, b, hz)) {
                Some(r) => t += &format!(" {} |", text(r)),
                None => t += " – |",
            }
        }
        t += "\n";
    }
    t
}

impl Table for WpHeadline {
    fn render(rows: &[Self]) -> String {
        let rows: Vec<WpRow> = rows.iter().map(|r| r.0.clone()).collect();
        let r = rows_rate(&rows);
        let mut t = table::header(&[
            "configuration",
            &format!("final / max error at {r} Hz (rad)"),
            "host ns/sample",
        ]);
        for p in rows.iter().filter(|p| p.rate_hz == r) {
            t += &format!(
                "| {} | {} | {:.1} |\n",
                cell(&p.configuration),
                p.errors(),
                p.host_ns_per_sample
            );
        }
        t
    }
}

/// The per-scene summary: best quatprop configuration and best peer at the reference rate.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SceneSummaryRow {
    pub scene: String,
    pub precision: String,
    pub rate_hz: u32,
    /// Empty: none accepted.
    pub best_quatprop: String,
    pub best_quatprop_final_error_rad: f64,
    pub best_quatprop_max_error_rad: f64,
    pub best_peer: String,
    pub best_peer_final_error_rad: f64,
    pub best_peer_max_error_rad: f64,
    /// Configurations refused at this rate, with their refusals ("; "-separated; empty: none).
    pub refused: String,
}
impl Csv for SceneSummaryRow {
    const FILE: &'static str = "work_precision_summary.csv";
}
impl Table for SceneSummaryRow {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&[
            "scene",
            "precision",
            "rate (Hz)",
            "best quatprop: final / max error (rad)",
            "best peer: final / max error (rad)",
            "ratio (max error)",
        ]);
        let best = |c: &str, f: f64, m: f64| {
            if c.is_empty() {
                "–".to_string()
            } else {
                format!("{}: {f:.2e} / {m:.2e}", cell(c))
            }
        };
        for r in rows {
            let ratio = if r.best_quatprop.is_empty() || r.best_peer.is_empty() {
                "–".to_string()
            } else {
                format!(
                    "{:.0}×",
                    r.best_peer_max_error_rad / r.best_quatprop_max_error_rad
                )
            };
            t += &format!(
                "| {} | {} | {} | {} | {} | {ratio} |\n",
                r.scene,
                r.precision,
                r.rate_hz,
                best(
                    &r.best_quatprop,
                    r.best_quatprop_final_error_rad,
                    r.best_quatprop_max_error_rad
                ),
                best(
                    &r.best_peer,
                    r.best_peer_final_error_rad,
                    r.best_peer_max_error_rad
                ),
            );
            if !r.refused.is_empty() {
                t += &format!(
                    "| | | | refused at {} Hz: {} | | |\n",
                    r.rate_hz,
                    cell(&r.refused)
                );
            }
        }
        t
    }
}

/// The Pareto front on the Cortex-M4F.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct M4fRow {
    pub configuration: String,
    pub rate_hz: u32,
    pub m4f_instructions_per_step: f64,
    pub m4f_instructions_per_second: f64,
    pub max_error_rad: f64,
}
impl Csv for M4fRow {
    const FILE: &'static str = "work_precision_m4f_pareto.csv";
}
impl Table for M4fRow {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&[
            "Pareto configuration (M4F)",
            "rate (Hz)",
            "M4F instructions per step",
            "M4F instructions per second",
            "max error (rad)",
        ]);
        for r in rows {
            t += &format!(
                "| {} | {} | {:.1} | {:.3e} | {:.2e} |\n",
                cell(&r.configuration),
                r.rate_hz,
                r.m4f_instructions_per_step,
                r.m4f_instructions_per_second,
                r.max_error_rad
            );
        }
        t
    }
}

/// The motions of the equal-cost comparison (scene keys): a closed-form cone, a random smooth motion, a
/// recorded one, and the recorded one low-passed (the motion without the gyro's noise).
pub const EQUAL_COST_MOTIONS: [&str; 4] = ["coning", "random", "broad07", "broad07-lp"];

/// The ratio equal cost is to reach against every peer.
pub const EQUAL_COST_GOAL: f64 = 100.0;

/// One peer at one rate against quatprop at the same host time per simulated second, interpolated along each
/// quatprop configuration's error–cost curve.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct EqualCostRow {
    pub motion: String,
    pub peer: String,
    pub rate_hz: u32,
    pub peer_max_error_rad: f64,
    /// Host ns per simulated second: ns per sample × rate.
    pub peer_ns_per_second: f64,
    /// The configuration with the least error at that cost (empty: none reaches that cost).
    pub quatprop: String,
    /// Where on its curve: "between A and B Hz" (interpolated) or "at A Hz" (a measured point costing less).
    pub quatprop_where: String,
    pub quatprop_max_error_rad: Option<f64>,
    /// Under the goal: what bounds the ratio (empty: the goal is reached).
    pub bounded_by: String,
}
impl Csv for EqualCostRow {
    const FILE: &'static str = "work_precision_equal_cost.csv";
}
impl EqualCostRow {
    pub fn ratio(&self) -> Option<f64> {
        self.quatprop_max_error_rad
            .map(|e| self.peer_max_error_rad / e)
    }
}
impl Table for EqualCostRow {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&[
            "motion",
            "peer",
            "rate (Hz)",
            "peer: max error (rad)",
            "peer: host µs per simulated s",
            "quatprop at that cost (log-log interpolated)",
            "its max error (rad)",
            "error ratio",
        ]);
        for r in rows {
            let (q, e, ratio) = match (r.quatprop_max_error_rad, r.ratio()) {
                (Some(e), Some(x)) => (
                    format!("{} {}", cell(&r.quatprop), r.quatprop_where),
                    format!("{e:.2e}"),
                    if r.bounded_by.is_empty() {
                        format!("**{}**", fmt_ratio(x))
                    } else {
                        format!("{} ({})", fmt_ratio(x), cell(&r.bounded_by))
                    },
                ),
                _ => (
                    "none reaches that cost".to_string(),
                    String::new(),
                    cell(&r.bounded_by),
                ),
            };
            t += &format!(
                "| {} | {} | {} | {:.2e} | {:.1} | {q} | {e} | {ratio} |\n",
                cell(&r.motion),
                cell(&r.peer),
                r.rate_hz,
                r.peer_max_error_rad,
                r.peer_ns_per_second * 1e-3,
            );
        }
        t
    }
}

/// An error ratio: whole above 10, two significant digits under.
fn fmt_ratio(x: f64) -> String {
    if x >= 10.0 {
        format!("{x:.0}×")
    } else {
        format!("{x:.2}×")
    }
}

/// quatprop's least maximum error at host cost `budget` (ns per simulated second) among the configurations
/// in `points` (peers left out): along each configuration's curve over its rates, log(error) linear in
/// log(cost) between neighbouring rates whose costs bracket the budget, or a measured point that costs no
/// more. (Configuration, where on its curve, error.)
pub fn at_equal_cost(points: &[Point], budget: f64) -> Option<(Config, String, f64)> {
    let mut configs: Vec<Config> = Vec::new();
    for p in points.iter().filter(|p| !p.config.is_peer()) {
        if !configs.contains(&p.config) {
            configs.push(p.config);
        }
    }
    let mut best: Option<(Config, String, f64)> = None;
    let mut consider = |c: Config, at: String, e: f64| {
        if e.is_finite() && best.as_ref().is_none_or(|b| e < b.2) {
            best = Some((c, at, e));
        }
    };
    let cost = |p: &Point| p.ns_per_sample * p.hz as f64;
    for c in configs {
        let mut curve: Vec<&Point> = points.iter().filter(|p| p.config == c).collect();
        curve.sort_by_key(|p| p.hz);
        for p in curve.iter().filter(|p| p.accepted() && cost(p) <= budget) {
            consider(c, format!("at {} Hz", p.hz), p.max_err);
        }
        for w in curve.windows(2) {
            let (a, b) = (w[0], w[1]);
            let (ca, cb) = (cost(a), cost(b));
            if !(a.accepted() && b.accepted()) || ca.min(cb) > budget || ca.max(cb) < budget || ca == cb {
                continue;
            }
            let u = (budget.ln() - ca.ln()) / (cb.ln() - ca.ln());
            let e = (a.max_err.ln() + u * (b.max_err.ln() - a.max_err.ln())).exp();
            consider(c, format!("between {} and {} Hz", a.hz, b.hz), e);
        }
    }
    best
}

/// Each peer at each rate of each motion against quatprop at equal cost.
pub fn equal_cost(ctx: &mut Ctx, motions: &[(String, Vec<Point>)], opt: &Options) -> String {
    let mut rows = Vec::new();
    let mut floors = String::new();
    let mut least = String::new();
    let mut orders = String::new();
    for (motion, points) in motions {
        // The least error any f32 quatprop configuration reaches on this motion, at any rate and cost.
        let floor = points
            .iter()
            .filter(|p| !p.config.is_peer() && p.accepted())
            .map(|p| p.max_err)
            .fold(f64::INFINITY, f64::min);
        let _ = write!(floors, "{motion}: {floor:.2e} rad; ");
        let _ = write!(
            orders,
            "{motion}: {}; ",
            observed_orders(points, ORDER_PROBE, floor)
        );
        for peer in Peer::ALL {
            let mut worst: Option<(f64, u32)> = None;
            for bp in points
                .iter()
                .filter(|p| p.config == Config::Peer(peer) && p.accepted())
            {
                let budget = bp.ns_per_sample * bp.hz as f64;
                let q = at_equal_cost(points, budget);
                let mut row = EqualCostRow {
                    motion: motion.clone(),
                    peer: peer.name().trim_start_matches("peer: ").to_string(),
                    rate_hz: bp.hz,
                    peer_max_error_rad: bp.max_err,
                    peer_ns_per_second: budget,
                    quatprop: q.as_ref().map_or(String::new(), |q| q.0.label()),
                    quatprop_where: q.as_ref().map_or(String::new(), |q| q.1.clone()),
                    quatprop_max_error_rad: q.as_ref().map(|q| q.2),
                    bounded_by: String::new(),
                };
                match row.ratio() {
                    Some(x) => {
                        if worst.is_none_or(|w| x < w.0) {
                            worst = Some((x, bp.hz));
                        }
                        if x < EQUAL_COST_GOAL {
                            let e = row.quatprop_max_error_rad.unwrap_or(f64::NAN);
                            // The least error of the chosen configuration over its rates.
                            let own = q.as_ref().map_or(f64::NAN, |q| {
                                points
                                    .iter()
                                    .filter(|p| p.config == q.0 && p.accepted())
                                    .map(|p| p.max_err)
                                    .fold(f64::INFINITY, f64::min)
                            });
                            row.bounded_by = if bp.max_err < EQUAL_COST_GOAL * floor {
                                "f32 floor: the peer is within 100× of it".into()
                            } else if e <= 3.0 * floor {
                                "f32 floor: quatprop is at it".into()
                            } else if e <= 3.0 * own {
                                format!(
                                    "the budget: that configuration is within 3× of its own least \
                                     error, {own:.1e}"
                                )
                            } else {
                                format!(
                                    "the budget: that configuration reaches {own:.1e} only at a \
                                     higher cost"
                                )
                            };
                        }
                    }
                    None => {
                        row.bounded_by = "the budget: no quatprop configuration is that cheap".into();
                        worst = Some((0.0, bp.hz));
                    }
                }
                rows.push(row);
            }
            if let Some((x, hz)) = worst {
                let peer = peer.name().trim_start_matches("peer: ");
                let _ = if x > 0.0 {
                    write!(least, "{motion}, {peer}: {} (at {hz} Hz); ", fmt_ratio(x))
                } else {
                    write!(
                        least,
                        "{motion}, {peer}: no quatprop configuration as cheap (at {hz} Hz); "
                    )
                };
            }
        }
    }
    let table = ctx.table(&rows);
    format!(
        "### Each peer against quatprop at equal cost, on four motions\n\nMotions: coning (closed form), a \
         random smooth motion (closed form: `q = exp(φ(t))`, each component of φ a sum of four random sinusoids, \
         |ω| ≤ 2.6 rad/s) and the rate profile of a recorded trial (BROAD trial 07, fast rotation, up to {:.0} \
         rad/s: its gyro samples at 285.7 Hz through a natural cubic spline define ω(t) at any rate; reference: \
         that ω(t) integrated in f64 by Magnus-4 with {} substeps per recorded interval, which moves by \
         {:.1e} rad when the substep is halved; data: D. Laidig, M. Caruso, A. Cereatti, T. Seel, BROAD — A \
         Benchmark for Robust Inertial Orientation Estimation, Data 6(7):72, 2021, doi:10.3390/data6070072, CC BY \
         4.0; excerpt and attribution in `lab/data/broad/`), and the same profile low-passed by a zero-phase \
         Gaussian of σ = {:.0} ms (−3 dB at {:.1} Hz: the body's motion without the gyro's noise; its reference \
         moves by {:.1e} rad when the substep is halved). f32, the comparison set of the previous section at \
         every rate; these are its points (horizon {}). Cost: host ns per simulated second (ns per sample × \
         rate). For each peer at each rate, quatprop's least maximum error at the peer's cost: along each \
         configuration's curve over the rates, log(error) interpolated linearly in log(cost) between the two \
         rates whose costs bracket the peer's, or a measured point that costs no more (no extrapolation: a \
         configuration none of whose points is that cheap is left out). Goal: {EQUAL_COST_GOAL:.0}× against \
         every peer. The least error any f32 quatprop configuration reaches on each motion (the f32 floor for \
         these streams): {}. Under the goal the table says what bounds the ratio: the peer's own error \
         within 100× of that floor (no f32 integrator can be 100× better); quatprop already at the floor; or \
         the budget: quatprop's best configuration at that cost is within 3× of its own least error over the \
         rates (its own floor: in f32 with a plain accumulator, its rounding over the horizon's steps; the \
         Kahan and float-float accumulators, which go lower, cost more per sample), or it reaches a lower \
         error only at a higher cost (still truncation-bound at that cost; the next paragraph). The observed order of \
         `{}` between neighbouring rates (log of the error ratio over log of the rate ratio; 4 is its order \
         on a smooth rate; \"floor\": an error within 30× of the motion's f32 floor): {}. The recorded motion is \
         not smooth on the scale of these rates: the spline through 285.7 Hz samples of a real gyro (its \
         noise included) carries content up to 143 Hz, its Nyquist frequency, which gyro rates of a few \
         hundred Hz do not resolve (100 Hz samples it below its own rate). Where the observed order there is \
         far under 4, the ratio is bounded by the motion's bandwidth against the rate, not by quatprop's order.\n\nLeast ratio per motion and peer over the rates: {}\n\n{table}",
        crate::recorded::RecordedMotion::broad().peak_rate(),
        crate::recorded::RecordedMotion::SUBSTEPS,
        crate::recorded::RecordedMotion::broad().reference_check(),
        crate::recorded::RecordedMotion::LOW_PASS_SIGMA * 1e3,
        crate::recorded::RecordedMotion::low_pass_cutoff(),
        crate::recorded::RecordedMotion::broad_low_passed().reference_check(),
        opt.scale.pick(
            "2.37 s, the two lowest rates",
            "5.37 s",
            "20.37 s"
        ),
        floors.trim_end_matches("; "),
        ORDER_PROBE.label(),
        orders.trim_end_matches("; "),
        least.trim_end_matches("; "),
    )
}

/// The fourth-order configuration whose observed order the equal-cost text reports.
const ORDER_PROBE: Config = Config::qp(SchemeKind::ExpMap, Stab::FirstOrder, Input::History).with(Acc::Kahan);

/// A configuration's observed order between neighbouring rates: "100→200 Hz: 3.9, …" (log of the error
/// ratio over log of the rate ratio; "–" where a point was refused, "floor" where an error is within 30× of
/// `floor`, the rounding floor, where the order says nothing).
pub fn observed_orders(points: &[Point], config: Config, floor: f64) -> String {
    let mut curve: Vec<&Point> = points.iter().filter(|p| p.config == config).collect();
    curve.sort_by_key(|p| p.hz);
    curve
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let order = (a.max_err / b.max_err).ln() / (b.hz as f64 / a.hz as f64).ln();
            if !(a.accepted() && b.accepted()) {
                format!("{}→{} Hz: –", a.hz, b.hz)
            } else if a.max_err.min(b.max_err) < 30.0 * floor {
                format!("{}→{} Hz: floor", a.hz, b.hz)
            } else {
                format!("{}→{} Hz: {order:.1}", a.hz, b.hz)
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// A peer's wrapper (as the studies run it) against its plain loop (`crate::peer_loops`), timed in the same
/// sweep at one rate.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PeerLoopRow {
    pub peer: String,
    pub precision: String,
    pub rate_hz: u32,
    pub wrapper_ns_per_sample: f64,
    pub loop_ns_per_sample: f64,
    /// Wrapper and loop ended on the same maximum and final error (the unit tests check the bits).
    pub same_errors: bool,
}
impl Csv for PeerLoopRow {
    const FILE: &'static str = "work_precision_peer_loops.csv";
}
impl Table for PeerLoopRow {
    fn render(rows: &[Self]) -> String {
        by_rate(
            rows,
            ["peer", "precision"],
            |hz| format!("{hz} Hz: wrapper / loop ns (ratio)"),
            |r| (r.peer.as_str(), r.precision.as_str(), r.rate_hz),
            |r| {
                format!(
                    "{:.1} / {:.1} ({:.2}){}",
                    r.wrapper_ns_per_sample,
                    r.loop_ns_per_sample,
                    r.wrapper_ns_per_sample / r.loop_ns_per_sample,
                    if r.same_errors { "" } else { ", **errors differ**" }
                )
            },
        )
    }
}

/// Each peer's wrapper against its plain loop, from a sweep that ran both.
pub fn peer_loop_rows(prec: Precision, points: &[Point]) -> Vec<PeerLoopRow> {
    let mut rows = Vec::new();
    for w in points {
        let Config::Peer(p) = w.config else { continue };
        let Some(l) = points
            .iter()
            .find(|l| l.config == Config::PeerLoop(p) && l.hz == w.hz)
        else {
            continue;
        };
        rows.push(PeerLoopRow {
            peer: p.name().trim_start_matches("peer: ").to_string(),
            precision: prec.name().into(),
            rate_hz: w.hz,
            wrapper_ns_per_sample: w.ns_per_sample,
            loop_ns_per_sample: l.ns_per_sample,
            same_errors: w.max_err.to_bits() == l.max_err.to_bits()
                && w.final_err.to_bits() == l.final_err.to_bits(),
        });
    }
    rows
}

/// Pareto front (cost, error) over accepted points.
fn pareto(points: &[&Point], cost: impl Fn(&Point) -> Option<f64>) -> Vec<(f64, f64)> {
    let mut pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.accepted())
        .filter_map(|p| Some((cost(p)?, p.max_err)))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for (c, e) in pts {
        if e < best {
            best = e;
            front.push((c, e));
        }
    }
    front
}

/// Error against host time per sample, one series per configuration, Pareto front dashed.
/// Plots the points' error against host time (`<name>.svg`, `.png`) and returns the figure's Markdown link.
pub fn plot_points(ctx: &mut Ctx, name: &str, title: &str, points: &[Point]) -> String {
    let mut configs: Vec<Config> = Vec::new();
    for p in points {
        if !configs.contains(&p.config) {
            configs.push(p.config);
        }
    }
    let mut series: Vec<Series> = configs
        .iter()
        .filter(|c| !matches!(c, Config::PeerLoop(_)))
        .map(|c| {
            let s = Series::both(
                c.label(),
                points
                    .iter()
                    .filter(|p| p.config == *c && p.accepted())
                    .map(|p| (p.ns_per_sample, p.max_err.max(1e-17)))
                    .collect(),
            );
            if c.is_peer() {
                s.dashed()
            } else {
                s
            }
        })
        .collect();
    let refs: Vec<&Point> = points.iter().collect();
    series.push(Series::line("Pareto front", pareto(&refs, |p| Some(p.ns_per_sample))).dashed());
    let (name, title) = (name.to_string(), title.to_string());
    ctx.plot(|dir| {
        plot(
            dir,
            &name,
            &title,
            Axis {
                label: "host time per gyro sample (ns, least of the runs)",
                log: true,
            },
            Axis {
                label: "max attitude error over the horizon (rad)",
                log: true,
            },
            &series,
        )
    });
    format!("![{name}]({name}.png)\n\n")
}

fn fmt_err(p: &Point) -> String {
    if p.refused > 0 {
        format!(
            "refused {} steps ({})",
            p.refused,
            error_kind(p.first_error)
        )
    } else {
        format!("{:.2e} / {:.2e}", p.final_err, p.max_err)
    }
}

/// Runs `configs` on `scene` in `prec`. (Its parameters are [`sweep`]'s, which it forwards in each
/// precision.)
pub fn sweep_in(
    ctx: &mut Ctx,
    prec: Precision,
    scene: &dyn Scene,
    configs: &[Config],
    rates: &[u32],
    horizon: f64,
    timing: Timing,
) -> Vec<Point> {
    match prec {
        Precision::F32 => sweep::<f32>(ctx, scene, configs, rates, horizon, timing),
        Precision::F64 => sweep::<f64>(ctx, scene, configs, rates, horizon, timing),
    }
}

/// What a work-precision run covers (command-line parameters; empty lists mean the defaults).
#[derive(Clone, Debug, Default)]
pub struct Options {
    pub scenes: Vec<String>,
    pub precisions: Vec<Precision>,
    pub methods: Vec<SchemeKind>,
    pub stabs: Vec<Stab>,
    pub inputs: Vec<Input>,
    pub rates: Vec<u32>,
    pub horizon: Option<f64>,
    pub scale: Scale,
}

impl Options {
    /// The command line's sweep at `scale`.
    pub fn new(s: &Sweep, scale: Scale) -> Self {
        Options {
            scenes: s.scenes.clone(),
            precisions: s.precision.clone(),
            methods: s.schemes.clone(),
            stabs: s.stabilizers.clone(),
            inputs: s.inputs.clone(),
            rates: s.rates.clone(),
            horizon: s.horizon,
            scale,
        }
    }
    /// The configurations: the filters applied to the scheme set (or to the full grid when any of schemes,
    /// stabilizers or inputs is given).
    fn configs(&self) -> Vec<Config> {
        let filtered =
            !(self.methods.is_empty() && self.stabs.is_empty() && self.inputs.is_empty());
        let base = if filtered { full_grid() } else { scheme_set() };
        base.into_iter()
            .filter(|c| match *c {
                Config::Quatprop {
                    method,
                    stab,
                    input,
                    ..
                } => {
                    (self.methods.is_empty() || self.methods.contains(&method))
                        && (self.stabs.is_empty() || self.stabs.contains(&stab))
                        && (self.inputs.is_empty() || self.inputs.contains(&input))
                }
                Config::Peer(_) | Config::PeerLoop(_) => !filtered,
            })
            .collect()
    }
    fn precisions(&self) -> Vec<Precision> {
        if self.precisions.is_empty() {
            vec![Precision::F32, Precision::F64]
        } else {
            self.precisions.clone()
        }
    }
    fn timing(&self) -> Timing {
        self.scale
            .pick(Timing::QUICK, Timing::DEFAULT, Timing::FULL)
    }
    /// The rates and the horizon of a scene's sweep: every rate the scene lists (`--quick`: its two lowest);
    /// its horizon at `--full`, a quarter of it by default (the error curves keep their order and slope, the
    /// timed rounds cost a quarter), an eighth with `--quick`.
    fn rates_horizon(&self, scene: &dyn Scene) -> (Vec<u32>, f64) {
        let sw = scene.sweep();
        let mut rates = if self.rates.is_empty() {
            sw.rates.to_vec()
        } else {
            self.rates.clone()
        };
        let mut horizon = self.horizon.unwrap_or(sw.horizon);
        match self.scale {
            Scale::Quick => {
                rates.truncate(2);
                horizon = horizon.min(2.37 * sw.horizon / 20.37);
            }
            Scale::Default => {
                horizon = self.horizon.unwrap_or(5.37 * sw.horizon / 20.37);
            }
            Scale::Full => {}
        }
        (rates, horizon)
    }
}

/// One precision's points on `scene`: its CSV rows (each wrapped by `row`) added to `csv`, and its figure,
/// `figure = (stem, what)`: the file `{stem}{scene}_{precision}` titled "{scene}, {precision}: {what}".
/// Returns the figure's Markdown.
fn rows_and_figure<R>(
    ctx: &mut Ctx,
    scene: &dyn Scene,
    prec: Precision,
    points: &[Point],
    csv: &mut Vec<R>,
    row: fn(WpRow) -> R,
    (stem, what): (&str, &str),
) -> String {
    csv.extend(wp_rows(scene.key(), prec, points).into_iter().map(row));
    let name = format!("{stem}{}_{}", scene.key(), prec.name());
    let title = format!("{}, {}: {what}", scene.name(), prec.name());
    plot_points(ctx, &name, &title, points)
}

/// The reference rate of a table: 1 kHz if swept, else the middle rate.
fn table_rate(rates: &[u32]) -> u32 {
    if rates.contains(&1000) {
        1000
    } else {
        rates[rates.len() / 2]
    }
}

/// Work–precision per scene and precision (the comparison set, or the filtered grid): one plot each, a
/// summary table of the best quatprop configuration and the best peer at the reference rate.
/// Its f32 points on the motions of the equal-cost comparison ([`EQUAL_COST_MOTIONS`]) go to `motions`
/// (scene name, points).
pub fn per_scene(
    ctx: &mut Ctx,
    scenes: &[Box<dyn Scene>],
    opt: &Options,
    motions: &mut Vec<(String, Vec<Point>)>,
) -> String {
    let configs = opt.configs();
    let mut csv: Vec<WpScenes> = Vec::new();
    let mut summary = Vec::new();
    let mut figures = String::new();
    let mut timed = Vec::new();
    for scene in scenes {
        if !opt.scenes.is_empty() && !opt.scenes.iter().any(|s| s == scene.key()) {
            continue;
        }
        let (rates, horizon) = opt.rates_horizon(scene.as_ref());
        for prec in opt.precisions() {
            let points = sweep_in(
                ctx,
                prec,
                scene.as_ref(),
                &configs,
                &rates,
                horizon,
                opt.timing(),
            );
            timed.extend(points.iter().cloned());
            if prec == Precision::F32 && EQUAL_COST_MOTIONS.contains(&scene.key()) {
                motions.push((scene.name().to_string(), points.clone()));
            }
            let figure = ("wp_", "error against host time");
            figures += &rows_and_figure(ctx, scene.as_ref(), prec, &points, &mut csv, WpScenes, figure);
            let r = table_rate(&rates);
            let best = |peer: bool| {
                points
                    .iter()
                    .filter(|p| p.hz == r && p.config.is_peer() == peer && p.accepted())
                    .min_by(|a, b| a.max_err.total_cmp(&b.max_err))
            };
            let refused: Vec<String> = points
                .iter()
                .filter(|p| p.hz == r && p.refused > 0)
                .map(|p| format!("{} {}", p.config.label(), fmt_err(p)))
                .collect();
            let (bq, bp) = (best(false), best(true));
            let name_of = |p: Option<&Point>| p.map_or(String::new(), |p| p.config.label());
            summary.push(SceneSummaryRow {
                scene: scene.name().into(),
                precision: prec.name().into(),
                rate_hz: r,
                best_quatprop: name_of(bq),
                best_quatprop_final_error_rad: bq.map_or(f64::NAN, |p| p.final_err),
                best_quatprop_max_error_rad: bq.map_or(f64::NAN, |p| p.max_err),
                best_peer: name_of(bp),
                best_peer_final_error_rad: bp.map_or(f64::NAN, |p| p.final_err),
                best_peer_max_error_rad: bp.map_or(f64::NAN, |p| p.max_err),
                refused: refused.join("; "),
            });
        }
    }
    ctx.rows(&csv);
    let table = ctx.table(&summary);
    format!(
        "### Work–precision per scene, f32 and f64\n\nEvery scheme with linear input, the sample-history and mid \
         inputs, all with FirstOrder, and every peer, on the same samples of each scene (ω(t_k), t_k = k·dt with dt \
         in the run's precision). Error: final and maximum over 64 checkpoints of the horizon (the plots show the \
         maximum); cost: host ns per gyro sample. {} Refused steps (a step angle beyond a scheme's stability \
         bound) are reported, never dropped: such a point is left out of the plots and the Pareto front. CSV: \
         `work_precision_scenes.csv`.\n\n{table}\n{figures}",
        timing_note(&timed, opt.timing())
    )
}

/// Stabilizers side by side on coning: Rk4 linear and ExpMap history with each stabilizer, f32 and f64.
pub fn stabilizers(ctx: &mut Ctx, scene: &dyn Scene, opt: &Options) -> String {
    let mut configs = Vec::new();
    for (m, i) in [
        (SchemeKind::Rk4, Input::Linear),
        (SchemeKind::ExpMap, Input::History),
    ] {
        for s in Stab::ALL {
            let c = Config::qp(m, s, i);
            if c.exists() {
                configs.push(c);
            }
        }
    }
    let (rates, horizon) = opt.rates_horizon(scene);
    let mut csv: Vec<WpStabilizers> = Vec::new();
    let mut figures = String::new();
    let mut timed = Vec::new();
    for prec in opt.precisions() {
        let points = sweep_in(ctx, prec, scene, &configs, &rates, horizon, opt.timing());
        timed.extend(points.iter().cloned());
        let figure = ("wp_stabilizers_", "stabilizers");
        figures += &rows_and_figure(ctx, scene, prec, &points, &mut csv, WpStabilizers, figure);
    }
    let table = ctx.table(&csv);
    format!(
        "### Work–precision per stabilizer: {}\n\nRk4 with linear input and the exponential map with the sample \
         history, each with every stabilizer (Every(16); Baumgarte k = 0.5 /s, for Rk4 only: since quatprop 0.2 \
         Baumgarte is a right-hand-side option of the Runge–Kutta schemes, so the exponential map has no Baumgarte \
         row). {} CSV: `work_precision_stabilizers.csv`.\n\n{table}\n{figures}",
        scene.name(),
        timing_note(&timed, opt.timing())
    )
}

/// M4F instructions per step from `firmware/bench-m4f.csv`, if the firmware figures were generated.
pub fn m4f_bench() -> Option<Vec<BenchRow>> {
    m4f_bench::read(&m4f_bench::path()).ok()
}

/// The full grid on one scene in f32 and f64 (CSV), and in f32 the error against Cortex-M4F instructions per
/// simulated second for every configuration the firmware bench measured.
pub fn grid_with_m4f(ctx: &mut Ctx, scene: &dyn Scene, opt: &Options) -> String {
    let configs = full_grid();
    let (rates, horizon) = opt.rates_horizon(scene);
    let mut csv: Vec<WpGrid> = Vec::new();
    let mut f32_points = Vec::new();
    let mut counts = 0;
    let mut timed = Vec::new();
    for prec in opt.precisions() {
        let points = sweep_in(ctx, prec, scene, &configs, &rates, horizon, opt.timing());
        timed.extend(points.iter().cloned());
        counts += points.len();
        csv.extend(wp_rows(scene.key(), prec, &points).into_iter().map(WpGrid));
        if prec == Precision::F32 {
            f32_points = points;
        }
    }
    ctx.rows(&csv);
    let Some(bench) = m4f_bench() else {
        return format!(
            "### Full grid and Cortex-M4F cost\n\n{counts} points (every scheme × stabilizer × input × rate × \
             precision; Baumgarte with the Runge–Kutta schemes only) in `work_precision_grid.csv`. {} No `firmware/bench-m4f.csv`: run `python3 firmware/figures.py` \
             for the instruction-count overlay.\n",
            timing_note(&timed, opt.timing())
        );
    };
    let instr = |c: &Config| -> Option<f64> {
        let Config::Quatprop {
            method,
            stab,
            input,
            accumulator: Acc::Plain,
        } = *c
        else {
            return None;
        };
        let sname = match stab {
            Stab::Every(_) => "Every(16)".to_string(),
            Stab::Baumgarte(_) => "Baumgarte".to_string(),
            s => s.name(),
        };
        bench
            .iter()
            .find(|b| {
                b.0 == "f32" && b.1 == scheme_name(method) && b.2 == sname && b.3 == input.name()
            })
            .map(|b| b.4)
    };
    // Instructions per simulated second = per step × steps per second.
    let cost = |p: &Point| instr(&p.config).map(|i| i * p.hz as f64 * p.config.steps_per_sample());
    let mut series = Vec::new();
    let mut shown = Vec::new();
    for m in SchemeKind::ALL {
        for i in Input::ALL {
            let c = Config::qp(m, Stab::FirstOrder, i);
            let pts: Vec<(f64, f64)> = f32_points
                .iter()
                .filter(|p| p.config == c && p.accepted())
                .filter_map(|p| Some((cost(p)?, p.max_err.max(1e-17))))
                .collect();
            if !pts.is_empty()
                && matches!(
                    m,
                    SchemeKind::Euler
                        | SchemeKind::Rk2
                        | SchemeKind::Rk4
                        | SchemeKind::ExpMap
                        | SchemeKind::Magnus4
                )
            {
                series.push(Series::both(c.label(), pts));
                shown.push(c);
            }
        }
    }
    let refs: Vec<&Point> = f32_points.iter().collect();
    let front = pareto(&refs, cost);
    series
        .push(Series::line("Pareto front (every measured configuration)", front.clone()).dashed());
    ctx.plot(|dir| {
        plot(
            dir,
            "wp_m4f_coning_f32",
            "Coning, f32: error against Cortex-M4F instructions per simulated second",
            Axis {
                label: "M4F instructions per second of flight (bench, -icount)",
                log: true,
            },
            Axis {
                label: "max attitude error over the horizon (rad)",
                log: true,
            },
            &series,
        )
    });
    let mut pareto_rows = Vec::new();
    for (c, e) in &front {
        if let Some(p) = f32_points
            .iter()
            .find(|p| p.accepted() && cost(p) == Some(*c) && p.max_err == *e)
        {
            pareto_rows.push(M4fRow {
                configuration: p.config.label(),
                rate_hz: p.hz,
                m4f_instructions_per_step: instr(&p.config).unwrap_or(f64::NAN),
                m4f_instructions_per_second: *c,
                max_error_rad: *e,
            });
        }
    }
    let table = ctx.table(&pareto_rows);
    format!(
        "### Full grid and Cortex-M4F cost: {}\n\n{counts} points (every scheme × stabilizer × input model × rate × \
         precision; Baumgarte with the Runge–Kutta schemes only) in `work_precision_grid.csv`. {} The plot puts the f32 errors (bit-identical on the M4F) against \
         the instructions the firmware bench counted on the Cortex-M4F (`firmware/bench-m4f.csv`, from \
         `python3 firmware/figures.py`) times the steps per second; the bench measures ExpMap, Magnus4, Cf4 and \
         Rk4 with FirstOrder and Normalize on every input model (a configuration it does not measure has no \
         point here). Shown: the schemes among Euler, Rk2, Rk4, ExpMap and Magnus4 with FirstOrder that it \
         measured; the front is over every measured configuration.\n\n\
         ![m4f](wp_m4f_coning_f32.png)\n\n{table}",
        scene.name(),
        timing_note(&timed, opt.timing())
    )
}

/// The headline: coning in f32, quatprop's best against every peer at equal host time.
pub fn headline(ctx: &mut Ctx, scene: &dyn Scene, opt: &Options) -> String {
    let mut configs = vec![
        Config::qp(SchemeKind::ExpMap, Stab::FirstOrder, Input::Linear),
        Config::qp(SchemeKind::Rk4, Stab::FirstOrder, Input::Linear),
        Config::qp(SchemeKind::ExpMap, Stab::FirstOrder, Input::History),
        Config::qp(SchemeKind::ExpMap, Stab::FirstOrder, Input::History).with(Acc::Kahan),
        Config::qp(SchemeKind::ExpMap, Stab::FirstOrder, Input::History).with(Acc::FloatFloat),
        Config::qp(SchemeKind::Rk4, Stab::FirstOrder, Input::History),
        Config::qp(SchemeKind::Magnus4, Stab::FirstOrder, Input::History),
    ];
    configs.extend(Peer::ALL.iter().map(|&p| Config::Peer(p)));
    configs.extend(Peer::ALL.iter().map(|&p| Config::PeerLoop(p)));
    let (rates, horizon) = opt.rates_horizon(scene);
    let points = sweep::<f32>(ctx, scene, &configs, &rates, horizon, opt.timing());
    let loops = ctx.table(&peer_loop_rows(Precision::F32, &points));
    let csv: Vec<WpHeadline> = wp_rows(scene.key(), Precision::F32, &points)
        .into_iter()
        .map(WpHeadline)
        .collect();
    let table = ctx.table(&csv);
    plot_points(
        ctx,
        "work_precision_coning_f32",
        "Coning, f32, one sample per step: error against host time per sample",
        &points,
    );
    format!(
        "### Work–precision: coning in f32, one gyro sample per step\n\n![work-precision](work_precision_coning_f32.png)\n\n\
         {}, horizon {horizon} s, gyro rates {rates:?} Hz, every configuration fed the same f32 samples. {}, this machine. Peers as crates: `ahrs` 0.8 \
         (`Madgwick::update_gyro`, on its own nalgebra 0.34, which it builds with `libm-force`: a copy apart \
         from the nalgebra peers', so that feature leaves their sin/cos/exp alone), `nalgebra` 0.35 \
         (`UnitQuaternion`), `glam` 0.34 (`Quat::from_scaled_axis`), all converted through `mint`; Fusion (C): its gyroscope update from its published source \
         (`lab/src/peers.rs`). Bias estimation beside Fusion's and VQF's: docs/bias.md.\n\n{table}\n\
         Each peer's wrapper, as the studies run it (a state kept in a struct between `feed` calls, one call \
         per stream), against the same peer call in a plain hand-written loop with its state in locals \
         (`lab/src/peer_loops.rs`; the peer in the form its users write it), timed in the same sweep by the \
         same rule: host ns per sample, the wrapper's over the loop's in brackets (the unit tests check that \
         both end on the same attitude bit for bit).\n\n{loops}\n\
         Each peer against quatprop at equal cost, on coning and three more motions: section \"Each peer \
         against quatprop at equal cost, on four motions\" below.\n",
        scene.name(),
        timing_note(&points, opt.timing()).trim_end_matches('.')
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(config: Config, hz: u32, ns_per_sample: f64, max_err: f64) -> Point {
        Point {
            config,
            hz,
            samples: 1,
            final_err: max_err,
            max_err,
            ns_per_sample,
            refused: 0,
            first_error: None,
            quiet_runs: 1,
        }
    }

    /// Equal cost interpolates log(error) linearly in log(cost) along each configuration's curve, takes a
    /// cheaper measured point when it is better, never extrapolates, skips refused points and peers.
    #[test]
    fn equal_cost_interpolates_each_curve_in_log_log() {
        let a = Config::qp(SchemeKind::ExpMap, Stab::FirstOrder, Input::History);
        let b = Config::qp(SchemeKind::Rk4, Stab::FirstOrder, Input::Linear);
        // a: 10 ns/sample; cost 1e3 at 100 Hz (error 1e-4), 1e4 at 1000 Hz (error 1e-8).
        let mut pts = vec![
            point(a, 100, 10.0, 1e-4),
            point(a, 1000, 10.0, 1e-8),
            point(b, 100, 1.0, 1e-3),
            point(Config::Peer(Peer::Fusion), 100, 0.1, 1e-12),
        ];
        // Halfway in log cost: halfway in log error.
        let (c, at, e) = at_equal_cost(&pts, 1e3 * 10f64.sqrt()).unwrap();
        assert_eq!((c, at.as_str()), (a, "between 100 and 1000 Hz"));
        assert!((e / 1e-6 - 1.0).abs() < 1e-12, "{e:e}");
        // Below a's cheapest point only b's measured point counts; below every point, nothing.
        assert_eq!(at_equal_cost(&pts, 500.0).map(|q| (q.0, q.2)), Some((b, 1e-3)));
        assert!(at_equal_cost(&pts, 50.0).is_none());
        // Beyond a's dearest point: its last point, not an extrapolation.
        assert_eq!(at_equal_cost(&pts, 1e6).map(|q| q.2), Some(1e-8));
        // A refused point breaks its curve.
        pts[1].refused = 1;
        assert_eq!(at_equal_cost(&pts, 1e3 * 10f64.sqrt()).map(|q| (q.0, q.2)), Some((a, 1e-4)));
    }

    /// The observed order of a fourth-order curve reads 4.
    #[test]
    fn observed_order_of_a_fourth_order_curve() {
        let a = ORDER_PROBE;
        let pts = [point(a, 100, 1.0, 1.6e-3), point(a, 200, 1.0, 1e-4)];
        assert_eq!(observed_orders(&pts, a, 1e-9), "100→200 Hz: 4.0");
        assert_eq!(observed_orders(&pts, a, 1e-5), "100→200 Hz: floor");
    }

    /// `--full` times as the report of record did: its rule is, word for word, the one in docs/report; the
    /// default scale says that it does not wait for the calibration, and `--quick` that it is no
    /// measurement of record.
    #[test]
    fn timing_notes_per_scale() {
        let docs = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/report/README.md"),
        )
        .unwrap();
        let full = timing_note(&[], Timing::FULL);
        assert!(docs.contains(&full), "{full}");
        let default = timing_note(&[], Timing::DEFAULT);
        assert!(default.contains("3 quiet runs and at least 1 s had passed, for at most 4 s per sweep"));
        assert!(default.contains("no wait for the probe's calibration"));
        assert!(timing_note(&[], Timing::QUICK).contains("not a measurement of record"));
        for t in [Timing::DEFAULT, Timing::FULL] {
            assert!(t.cap >= t.window && t.runs >= 1, "{t:?}");
        }
    }
}
