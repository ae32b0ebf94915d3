//! What choosing at run time costs on the host: FIFO bursts of 32 samples through the run-time
//! configuration ([`Configured`]: `push_burst`, which runs the monomorphized loop, and `visit_compact`,
//! which matches the scheme inside each step, as the C API's default build does) against the static
//! propagator the configuration stands for. The firmware's `burst` program measures the same on the
//! Cortex-M4F in instructions (docs/firmware.md); this is the host's time, with the quiet-core gate.

use crate::report::Ctx;
use crate::study::{CsvFile, NoArgs, Study};
use crate::table::{self, Csv, Table};
use quatprop::accumulate::{Accumulator, Kahan};
use quatprop::config::{
    AccumulatorKind, Config, Configured, DeltaModel, InputKind, RateModel, Visit, Visited,
};
use quatprop::frontend::FixedPeriod;
use quatprop::input::{History, InputModel, Linear};
use quatprop::scheme::{ExpMap, Rk4, Scheme, SchemeKind};
use quatprop::stabilize::{FirstOrder, Normalize, Stabilizer, StabilizerKind};
use quatprop::{GyroSample, Propagator, Quat, Vec3};
use serde::{Deserialize, Serialize};
use std::hint::black_box;
use std::time::Instant;

/// The study.
pub struct ConfigCost;

/// Samples per FIFO burst (as the firmware's `burst` program).
const BURST: usize = 32;
/// The sample rate of the stream (Hz).
const HZ: f64 = 1000.0;

/// One configuration: its host time per sample three ways.
#[derive(Serialize, Deserialize, Debug, Clone)]
pub struct Row {
    pub configuration: String,
    pub samples: usize,
    /// The static `Propagator`'s `push_burst` (ns per sample).
    pub static_ns: f64,
    /// `Configured::push_burst` (ns per sample).
    pub configured_ns: f64,
    /// A burst loop through `Configured::visit_compact` (ns per sample).
    pub compact_ns: f64,
    /// Timed runs whose probes on both sides ran at the quiet speed (the least of each variant's is kept).
    pub quiet_runs: usize,
}

impl Csv for Row {
    const FILE: &'static str = "config_cost.csv";
}

// Each table spells out its own line: its columns and their number formats are its own.
impl Table for Row {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&[
            "configuration",
            "static (ns/sample)",
            "`Configured` (ns/sample)",
            "ratio",
            "`visit_compact` (ns/sample)",
            "ratio",
            "quiet runs",
        ]);
        for r in rows {
            t += &format!(
                "| {} | {:.1} | {:.1} | **{:.3}** | {:.1} | {:.3} | {} |\n",
                r.configuration,
                r.static_ns,
                r.configured_ns,
                r.configured_ns / r.static_ns,
                r.compact_ns,
                r.compact_ns / r.static_ns,
                r.quiet_runs
            );
        }
        t
    }
}

/// The bursts through `visit_compact`: one visit per burst, as a C caller's one call per FIFO read.
struct CompactBurst<'a> {
    burst: &'a [GyroSample<f32>],
    period: &'a mut FixedPeriod<f32>,
}

// The method signatures are the `Visit` trait's, which every visitor spells out.
impl Visit<f32> for CompactBurst<'_> {
    type Output = ();
    fn rates<S: Scheme<f32>, I: RateModel<f32>, A: Accumulator<f32>>(
        self,
        p: &mut Visited<f32, S, I, A>,
    ) {
        let _ = black_box(p.push_burst(self.burst, self.period));
    }
    fn deltas<S: Scheme<f32>, I: DeltaModel<f32>, A: Accumulator<f32>>(
        self,
        _: &mut Visited<f32, S, I, A>,
    ) {
        // Both configurations take rates.
    }
}

/// A coning stream at incommensurate frequencies (rad/s).
fn stream(n: usize) -> Vec<GyroSample<f32>> {
    (0..n)
        .map(|k| {
            let t = k as f64 / HZ;
            GyroSample::new(Vec3::new(
                (0.8 * (7.3 * t).sin()) as f32,
                (0.8 * (7.3 * t).cos() + 0.3 * (4.38 * t).sin()) as f32,
                (0.4 + 0.2 * (2.236 * t).cos()) as f32,
            ))
        })
        .collect()
}

/// Times one run over the stream in bursts (ns per sample) and returns the final attitude.
fn timed(
    samples: &[GyroSample<f32>],
    run: impl FnOnce(&[GyroSample<f32>]) -> Quat<f32>,
) -> (f64, Quat<f32>) {
    let t0 = Instant::now();
    let q = run(black_box(samples));
    (
        t0.elapsed().as_nanos() as f64 / samples.len() as f64,
        black_box(q),
    )
}

fn period() -> FixedPeriod<f32> {
    FixedPeriod::new(1.0 / HZ).expect("a positive period")
}

/// The three variants of one configuration, given its static propagator.
fn variants<S, I, Z, A>(
    name: &str,
    config: Config,
    fixed: Propagator<f32, S, I, Z, A>,
) -> (String, Vec<Variant>)
where
    Z: Stabilizer + 'static,
    S: Scheme<f32> + 'static,
    I: InputModel<f32, Sample = GyroSample<f32>> + 'static,
    A: Accumulator<f32> + 'static,
{
    let configured: Configured<f32> = config.build(Quat::IDENTITY).expect("a valid configuration");
    let static_run = in_bursts(fixed, Propagator::attitude, |p, burst, period| {
        let _ = black_box(p.push_burst(burst, period));
    });
    let configured_run = in_bursts(configured, Configured::attitude, |p, burst, period| {
        let _ = black_box(p.push_burst(burst, period));
    });
    let compact_run = in_bursts(configured, Configured::attitude, |p, burst, period| {
        p.visit_compact(CompactBurst { burst, period });
    });
    (
        name.to_string(),
        vec![static_run, configured_run, compact_run],
    )
}

type Variant = Box<dyn Fn(&[GyroSample<f32>]) -> Quat<f32>>;

/// A variant that runs the stream through a fresh copy of `p` in bursts of [`BURST`], `push` taking one
/// burst, and returns the copy's final attitude.
fn in_bursts<P: Copy + 'static>(
    p: P,
    attitude: fn(&P) -> Quat<f32>,
    push: impl Fn(&mut P, &[GyroSample<f32>], &mut FixedPeriod<f32>) + 'static,
) -> Variant {
    Box::new(move |s: &[GyroSample<f32>]| {
        let mut p = p;
        let mut period = period();
        for burst in s.chunks(BURST) {
            push(&mut p, burst, &mut period);
        }
        attitude(&p)
    })
}

// The `Study` impl each study spells out (its name, files and run: lab/README.md, adding a study).
impl Study for ConfigCost {
    type Args = NoArgs;
    const NAME: &'static str = "config-cost";
    const ABOUT: &'static str =
        "Host cost of choosing at run time: bursts of 32 through Configured against the static propagator";
    const CSV: &'static [CsvFile] = &[CsvFile::table::<Row>()];
    fn run(&self, ctx: &mut Ctx, _: &NoArgs) {
        let (n, rounds) = ctx.scale.pick((20_000, 3), (200_000, 15), (1_000_000, 40));
        ctx.section("config cost", |ctx| {
            let samples = stream(n);
            let recommended = Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder)
                .expect("a unit attitude");
            let rk4 = Propagator::new(Quat::IDENTITY, Rk4, Linear::new(), Normalize)
                .expect("a unit attitude")
                .with_accumulator(Kahan::default());
            let cases = [
                variants("`Config::RECOMMENDED` (ExpMap + History + FirstOrder)", Config::RECOMMENDED, recommended),
                variants(
                    "Rk4 + Linear + Normalize + Kahan",
                    Config {
                        scheme: SchemeKind::Rk4,
                        input: InputKind::Linear,
                        stabilizer: StabilizerKind::Normalize,
                        accumulator: AccumulatorKind::Kahan,
                        ..Config::RECOMMENDED
                    },
                    rk4,
                ),
            ];
            // best[case][variant]: (least quiet ns, least ns); the variants alternate within each round.
            let mut best = vec![[(f64::INFINITY, f64::INFINITY); 3]; cases.len()];
            let mut quiet_runs = vec![usize::MAX; cases.len()];
            let mut counts = vec![[0usize; 3]; cases.len()];
            let mut before = ctx.quiet.probe();
            for round in 0..=rounds {
                ctx.tick();
                let t_round = Instant::now();
                for (c, (name, runs)) in cases.iter().enumerate() {
                    let mut finals = Vec::new();
                    for (v, run) in runs.iter().enumerate() {
                        let (ns, q) = timed(&samples, run);
                        let after = ctx.quiet.probe();
                        finals.push(q);
                        // Round 0 warms up.
                        if round > 0 {
                            let b = &mut best[c][v];
                            b.1 = b.1.min(ns);
                            if ctx.quiet.is_quiet(before.max(after)) {
                                b.0 = b.0.min(ns);
                                counts[c][v] += 1;
                            }
                        }
                        before = after;
                    }
                    if finals.windows(2).any(|w| w[0] != w[1]) {
                        ctx.fail(format!(
                            "config-cost: {name}: the three ways end on different attitudes {finals:?}"
                        ));
                    }
                }
                ctx.quiet.watched(t_round.elapsed());
            }
            let mut rows = Vec::new();
            for (c, (name, _)) in cases.iter().enumerate() {
                let pick = |v: usize| {
                    let (quiet, any) = best[c][v];
                    if quiet.is_finite() {
                        quiet
                    } else {
                        any
                    }
                };
                quiet_runs[c] = counts[c].iter().copied().min().unwrap_or(0);
                rows.push(Row {
                    configuration: name.clone(),
                    samples: n,
                    static_ns: pick(0),
                    configured_ns: pick(1),
                    compact_ns: pick(2),
                    quiet_runs: quiet_runs[c],
                });
            }
            let table = ctx.table(&rows);
            format!(
                "### The cost of choosing at run time (host)\n\n\
                 A stream of {n} f32 samples at 1 kHz in FIFO bursts of {BURST}: the static propagator's \
                 `push_burst`, `Configured::push_burst` (one `match` per burst, then the monomorphized loop) \
                 and a burst loop through `Configured::visit_compact` (the scheme matched in every step: the C \
                 API's default build). The three alternate in each of {rounds} rounds and end on the same \
                 bits (checked); each figure is the least time of its quiet runs (the probe's rule, \
                 `quiet.rs`; \"quiet runs\" is the fewest any of the three had; with none, the least of all \
                 runs). The Cortex-M4F's instruction counts of the same comparison are in \
                 docs/firmware.md.\n\n{table}"
            )
        });
    }
}
