//! Own error of an f32 attitude: the angle between an f32 propagator and an f64 propagator fed the same
//! f32 samples and the same f32 periods (so the only difference is the f32 arithmetic), at 10⁶, 10⁷ and
//! 10⁸ steps, for each accumulator, on a constant rate and on coning at an incommensurate frequency.
//!
//! The same for the fixed-point propagator (`fixed::Q30Propagator`) beside f32, both fed the motions as a
//! 16-bit gyro's counts.
//!
//! `cargo run --release --example own_error -- [--steps N] [--out DIR]`
use quatprop::accumulate::{Accumulator, FloatFloat, Kahan, Plain};
use quatprop::fixed::Q30Propagator;
use quatprop::frontend::FixedPeriod;
use quatprop::input::{History, Hold, InputModel, Linear};
use quatprop::scheme::ExpMap;
use quatprop::stabilize::FirstOrder;
use quatprop::{GyroSample, Propagator, Quat, Vec3};
use std::fmt::Write as _;

#[derive(Clone, Copy)]
enum Motion {
    Constant,
    Coning,
}

/// The f32 rate at sample k (1 kHz): computed in f64, rounded once to f32.
fn rate(m: Motion, k: u64) -> Vec3<f32> {
    let t = k as f64 * 1e-3;
    let w = match m {
        Motion::Constant => Vec3::new(0.36, -0.48, 0.8),
        Motion::Coning => {
            // Cone half-angle 0.1 rad at Ω = 2π/√2 rad/s: the period is not a whole number of samples.
            let (alpha, om) = (0.1_f64, 2.0 * std::f64::consts::PI / 2f64.sqrt());
            let (s, c) = (om * t).sin_cos();
            Vec3::new(
                -om * alpha.sin() * s,
                om * alpha.sin() * c,
                -2.0 * om * (alpha / 2.0).sin().powi(2),
            )
        }
    };
    Vec3::new(w.x as f32, w.y as f32, w.z as f32)
}

/// Own errors at the checkpoints (rad) and host ns per step.
type Measured = (Vec<f64>, f64);

fn run<I32, I64, A>(motion: Motion, checkpoints: &[u64], i32m: I32, i64m: I64, acc: A) -> Measured
where
    I32: InputModel<f32, Sample = GyroSample<f32>>,
    I64: InputModel<f64, Sample = GyroSample<f64>>,
    A: Accumulator<f32>,
{
    let mut p32 = Propagator::new(Quat::IDENTITY, ExpMap, i32m, FirstOrder)
        .unwrap()
        .with_accumulator(acc);
    let mut p64 = Propagator::new(Quat::IDENTITY, ExpMap, i64m, FirstOrder)
        .unwrap()
        .with_accumulator(Plain);
    let mut period = FixedPeriod::<f32>::new(1e-3).unwrap();
    let mut out = Vec::new();
    let last = *checkpoints.last().unwrap();
    let mut next = 0;
    for k in 0..=last {
        let w = rate(motion, k);
        let dt = period.next_dt();
        p32.push(GyroSample::new(w), dt).unwrap();
        p64.push(GyroSample::new(w.to_f64()), f64::from(dt))
            .unwrap();
        if k == checkpoints[next] {
            out.push(p32.attitude().to_f64().angle_to(p64.attitude()));
            next += 1;
        }
    }
    (out, host_ns(motion, i32m, acc))
}

/// ±2000 °/s on 16 bits (rad/s per count).
const RAD_PER_COUNT: f64 = 2000.0 / 32768.0 * std::f64::consts::PI / 180.0;

/// The motion's rate at sample k as a 16-bit gyro's counts (rounded to nearest).
fn counts(m: Motion, k: u64) -> [i16; 3] {
    let w = rate(m, k).to_f64() * (1.0 / RAD_PER_COUNT);
    [w.x, w.y, w.z].map(|v| v.round() as i16)
}

/// Own errors (rad) at the checkpoints of the fixed-point propagator and of the f32 recommended one, each
/// against the f64 recommended propagator fed the same counts (times the scale) at 1 ms.
fn run_counts(motion: Motion, checkpoints: &[u64]) -> (Vec<f64>, Vec<f64>) {
    let mut fixed = Q30Propagator::new(Quat::<f64>::IDENTITY, RAD_PER_COUNT, 1e-3).unwrap();
    let mut p32 = Propagator::recommended(Quat::<f32>::IDENTITY).unwrap();
    let mut p64 = Propagator::recommended(Quat::<f64>::IDENTITY).unwrap();
    let mut period = FixedPeriod::<f32>::new(1e-3).unwrap();
    let (mut e_fixed, mut e_f32) = (Vec::new(), Vec::new());
    let last = *checkpoints.last().unwrap();
    let mut next = 0;
    for k in 0..=last {
        let c = counts(motion, k);
        fixed.push(c).unwrap();
        let w = Vec3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2])) * RAD_PER_COUNT;
        p64.push(GyroSample::new(w), 1e-3).unwrap();
        let scale = RAD_PER_COUNT as f32;
        let w32 = Vec3::new(f32::from(c[0]), f32::from(c[1]), f32::from(c[2])) * scale;
        p32.push(GyroSample::new(w32), period.next_dt()).unwrap();
        if k == checkpoints[next] {
            e_fixed.push(fixed.attitude_f64().angle_to(p64.attitude()));
            e_f32.push(p32.attitude().to_f64().angle_to(p64.attitude()));
            next += 1;
        }
    }
    (e_fixed, e_f32)
}

/// Host nanoseconds per push of the f32 propagator alone (samples and dts precomputed): the least of
/// five runs of 10⁶ pushes.
fn host_ns<I, A>(motion: Motion, input: I, acc: A) -> f64
where
    I: InputModel<f32, Sample = GyroSample<f32>>,
    A: Accumulator<f32>,
{
    const N: usize = 1_000_000;
    let mut period = FixedPeriod::<f32>::new(1e-3).unwrap();
    let stream: Vec<(GyroSample<f32>, f32)> = (0..N as u64)
        .map(|k| (GyroSample::new(rate(motion, k)), period.next_dt()))
        .collect();
    (0..5)
        .map(|_| {
            let mut p = Propagator::new(Quat::IDENTITY, ExpMap, input, FirstOrder)
                .unwrap()
                .with_accumulator(acc);
            let t0 = std::time::Instant::now();
            for &(sample, dt) in std::hint::black_box(&stream) {
                let _ = std::hint::black_box(p.push(sample, dt));
            }
            std::hint::black_box(p.attitude());
            t0.elapsed().as_secs_f64() * 1e9 / N as f64
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let steps: u64 = args
        .iter()
        .position(|a| a == "--steps")
        .and_then(|i| args.get(i + 1))
        .map(|s| s.parse().unwrap())
        .unwrap_or(10_000_000);
    let out_dir = args
        .iter()
        .position(|a| a == "--out")
        .and_then(|i| args.get(i + 1));
    let mut checkpoints = vec![];
    let mut c = 1_000_000u64.min(steps);
    while c <= steps {
        checkpoints.push(c);
        c *= 10;
    }
    let start = std::time::Instant::now();
    let mut md = String::new();
    writeln!(
        md,
        "Generated by `cargo run --release --example own_error -- --steps {steps} --out docs`.\n"
    )
    .unwrap();
    write!(md, "| motion | input | accumulator |").unwrap();
    for c in &checkpoints {
        write!(md, " own error at {c:.0e} (rad) |").unwrap();
    }
    writeln!(
        md,
        " growth exponent | Cortex-M4F instructions per step (ExpMap + FirstOrder) | host ns per step |"
    )
    .unwrap();
    writeln!(md, "|{}", "---|".repeat(6 + checkpoints.len())).unwrap();
    let m4f = m4f_instructions();
    // Constant-rate own error at the last checkpoint and its maximum over the checkpoints, per accumulator
    // (Hold): what the horizon table below is computed from.
    let mut constant_rate: Vec<(&str, f64, f64)> = Vec::new();
    for (mname, m) in [
        ("constant 1 rad/s", Motion::Constant),
        ("coning, Ω = 2π/√2", Motion::Coning),
    ] {
        let rows: Vec<(&str, &str, Measured)> = vec![
            ("Hold", "Plain", run(m, &checkpoints, Hold, Hold, Plain)),
            (
                "Hold",
                "Kahan",
                run(m, &checkpoints, Hold, Hold, Kahan::new()),
            ),
            (
                "Linear",
                "Plain",
                run(m, &checkpoints, Linear::new(), Linear::new(), Plain),
            ),
            (
                "History",
                "Plain",
                run(m, &checkpoints, History::new(), History::new(), Plain),
            ),
            (
                "History",
                "Kahan",
                run(
                    m,
                    &checkpoints,
                    History::new(),
                    History::new(),
                    Kahan::new(),
                ),
            ),
            (
                "Hold",
                "FloatFloat",
                run(m, &checkpoints, Hold, Hold, FloatFloat::new()),
            ),
            (
                "Linear",
                "FloatFloat",
                run(
                    m,
                    &checkpoints,
                    Linear::new(),
                    Linear::new(),
                    FloatFloat::new(),
                ),
            ),
            (
                "History",
                "FloatFloat",
                run(
                    m,
                    &checkpoints,
                    History::new(),
                    History::new(),
                    FloatFloat::new(),
                ),
            ),
        ];
        for (input, acc, (errs, ns)) in rows {
            if matches!(m, Motion::Constant) && input == "Hold" {
                let max = errs.iter().copied().fold(0.0, f64::max);
                constant_rate.push((acc, *errs.last().unwrap(), max));
            }
            write!(md, "| {mname} | {input} | {acc} |{}", error_cells(&errs)).unwrap();
            let slope = growth(&errs);
            let cost = m4f
                .iter()
                .find(|(a, i, _)| a == acc && i.eq_ignore_ascii_case(input))
                .map_or("not measured".to_string(), |(_, _, n)| format!("{n:.1}"));
            writeln!(md, " {slope:.2} | {cost} | {ns:.1} |").unwrap();
        }
    }
    writeln!(
        md,
        "\nOwn error: the angle between the f32 attitude and an f64 propagator (plain accumulation) fed the same f32 \
         samples and the same f32 periods (`FixedPeriod`), so the only difference is the f32 arithmetic; \
         10⁸ steps and the error against physical time are in the lab's long-horizon study \
         ([report](report/README.md#long-horizon-in-f32-own-error-and-error-against-physical-time)). \
         Instructions: `firmware/bench-m4f.csv` (`python3 firmware/figures.py`, QEMU `-icount`; docs/firmware.md). \
         Host: the f32 propagator alone over 10⁶ precomputed samples, the least of five runs, on the machine \
         that ran this command.\n\n\
         ## Which accumulator, for which horizon\n\n\
         Pick the cheapest accumulator whose own error stays below what the gyro itself contributes over the run. \
         The gyro's share is at least its angle random walk, `ARW·√t`; the f32 arithmetic's share is the own \
         error above, which for `Plain` and `Kahan` grows linearly (a drift `r` rad/s, here from the constant \
         1 rad/s rows at {last:.0e} steps, and roughly proportional to the mean rotation rate), so it stays below \
         the noise until `t* = (ARW / r)²`. `FloatFloat`'s own error does not grow: it stays at the f32 output's \
         rounding (its largest value over the checkpoints, `L`), below the noise from `t₀ = (L / ARW)²` on. \
         ARW values are typical of each grade (assumed, not measured here; the consumer MEMS figure is the \
         ICM-42688-P datasheet's 2.8 m°/s/√Hz).\n\n\
         | accumulator | own error at 1 rad/s | consumer MEMS, 0.17 °/√h | industrial MEMS, 0.05 °/√h | tactical, 0.01 °/√h | navigation, 0.001 °/√h |\n\
         |---|---|---|---|---|---|",
        last = checkpoints.last().copied().unwrap_or(0) as f64,
    )
    .unwrap();
    let grades_deg_per_root_hour: [f64; 4] = [0.17, 0.05, 0.01, 0.001];
    let last_s = checkpoints.last().copied().unwrap_or(1) as f64 * 1e-3;
    for (acc, end, max) in &constant_rate {
        let growing = *acc != "FloatFloat";
        if growing {
            write!(md, "| {acc} | drift {:.2e} rad/s |", end / last_s).unwrap();
        } else {
            write!(md, "| {acc} | level {max:.2e} rad |").unwrap();
        }
        for g in grades_deg_per_root_hour {
            // °/√h → rad/√s.
            let arw = g.to_radians() / 60.0;
            if growing {
                let t = (arw / (end / last_s)).powi(2);
                write!(md, " below the noise for {} |", duration(t)).unwrap();
            } else {
                let t = (max / arw).powi(2);
                write!(md, " below the noise after {} |", duration(t)).unwrap();
            }
        }
        writeln!(md).unwrap();
    }
    let drift = |a: &str| {
        constant_rate
            .iter()
            .find(|r| r.0 == a)
            .map_or(f64::NAN, |r| r.1)
    };
    let ratio = drift("Plain") / drift("Kahan");
    writeln!(
        md,
        "\nSo: `Plain` (the quick start's) while the run is shorter than its `t*` for your gyro (for consumer \
         MEMS, longer than an attitude is flown on gyro alone); `Kahan` cuts the drift by {kahan:.1}× (`t*` \
         {kahan2:.0}× longer) for a few instructions; `FloatFloat` beyond those horizons (tactical and \
         navigation-grade gyros, hours-long runs), at its instruction cost above. The drift also scales with the \
         rate: `t*` at 2 rad/s is a quarter of the table's.",
        kahan = ratio,
        kahan2 = ratio * ratio,
    )
    .unwrap();
    writeln!(
        md,
        "\n## Fixed point (`fixed::Q30Propagator`)\n\n\
         The recommended step in integers for cores without an FPU, fed a 16-bit gyro's counts (±2000 °/s, \
         the motions above rounded to counts), against the f64 recommended propagator fed the same counts \
         times the scale at exactly 1 ms; beside it the f32 recommended propagator on the same counts (its \
         periods from `FixedPeriod`, as above). The f32 column differs from the table above because the \
         samples differ (counts, not f32 rates).\n"
    )
    .unwrap();
    write!(md, "| motion | propagator |").unwrap();
    for c in &checkpoints {
        write!(md, " own error at {c:.0e} (rad) |").unwrap();
    }
    writeln!(md, " growth exponent |").unwrap();
    writeln!(md, "|{}", "---|".repeat(3 + checkpoints.len())).unwrap();
    for (mname, m) in [
        ("constant 1 rad/s", Motion::Constant),
        ("coning, Ω = 2π/√2", Motion::Coning),
    ] {
        let (fixed, f32) = run_counts(m, &checkpoints);
        for (label, errs) in [("`Q30Propagator` (Q30)", fixed), ("recommended, f32", f32)] {
            let slope = growth(&errs);
            writeln!(
                md,
                "| {mname} | {label} |{} {slope:.2} |",
                error_cells(&errs)
            )
            .unwrap();
        }
    }
    writeln!(
        md,
        "\nInstructions per step on cores without an FPU, the fixed-point step against soft-float f32: \
         docs/firmware.md."
    )
    .unwrap();
    writeln!(md, "\nRun time {:.0} s.", start.elapsed().as_secs_f64()).unwrap();
    print!("{md}");
    if let Some(dir) = out_dir {
        std::fs::write(format!("{dir}/own_error.md"), md).unwrap();
    }
}

/// The checkpoints' errors as table cells.
fn error_cells(errs: &[f64]) -> String {
    errs.iter().map(|e| format!(" {e:.2e} |")).collect()
}

/// The growth exponent of the errors over the decades of the checkpoints (NaN for one checkpoint).
fn growth(errs: &[f64]) -> f64 {
    match errs {
        [first, .., last] => (last / first).log10() / (errs.len() - 1) as f64,
        _ => f64::NAN,
    }
}

/// A duration (s) in the unit a reader would say it in.
fn duration(t: f64) -> String {
    if t < 1e-3 {
        format!("{:.0} µs", t * 1e6)
    } else if t < 1.0 {
        format!("{:.0} ms", t * 1e3)
    } else if t < 120.0 {
        format!("{t:.1} s")
    } else if t < 7200.0 {
        format!("{:.0} min", t / 60.0)
    } else if t < 3.0 * 86400.0 {
        format!("{:.1} h", t / 3600.0)
    } else {
        format!("{:.0} days", t / 86400.0)
    }
}

/// (accumulator, input, instructions per step) for ExpMap + FirstOrder from `firmware/bench-m4f.csv`.
fn m4f_instructions() -> Vec<(String, String, f64)> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/firmware/bench-m4f.csv");
    let Ok(text) = std::fs::read_to_string(path) else {
        return Vec::new();
    };
    text.lines()
        .skip(1)
        .filter_map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let acc = match *f.first()? {
                "f32" => "Plain",
                "f32-kahan" => "Kahan",
                "f32-floatfloat" => "FloatFloat",
                _ => return None,
            };
            (f.get(1)? == &"ExpMap" && f.get(2)? == &"FirstOrder").then(|| {
                Some((
                    acc.to_string(),
                    f.get(3)?.to_string(),
                    f.get(4)?.parse().ok()?,
                ))
            })?
        })
        .collect()
}
