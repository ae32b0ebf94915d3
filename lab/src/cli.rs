//! The command line (clap derive): one sub-command per study, `report` for all of them; typed values
//! parsed and checked before anything runs; `quatprop-lab help <command>` for each command's options.

use crate::configs::{self, Input, Stab};
use crate::work_precision::{Options, Precision};
use crate::{
    atlas, baumgarte_sweep, bias, coning_drift, geiger, long_horizon, scene_table, scenes, sensor,
    time_base, work_precision, Ctx,
};
use clap::{Args, Parser, Subcommand};
use quatprop::scheme::SchemeKind;
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "quatprop-lab",
    about = "Host-side lab for quatprop: accuracy against cost, the seed paper's figures, stability, peers",
    version
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
    /// Output directory (README.md, plots, CSV).
    #[arg(long, global = true, default_value = "report")]
    pub out: PathBuf,
    /// Small grids and horizons (what CI runs).
    #[arg(long, global = true)]
    pub quick: bool,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Every study below: DIR/README.md + plots (SVG, PNG) + CSV.
    Report(Horizon),
    /// The seed paper's Fig. 1 and Fig. 2, and Baumgarte k swept to divergence in propagation.
    Geiger,
    /// Per-step norm factor and error against the step angle, measured stability bounds.
    Atlas,
    /// Error against cost per scene and precision, quatprop against the peers.
    WorkPrecision(Sweep),
    /// Every scene × the comparison set at 1 kHz, f32.
    Scenes,
    /// Sensor realism: noise, bias, 16-bit counts, saturation, dropped samples, dt jitter.
    Sensor(Sweep),
    /// Coning drift coefficient of every rate scheme and input model.
    ConingDrift,
    /// Bias estimation: quatprop's BiasEstimator against Fusion's FusionOffset (and its C code with
    /// `--features fusion-c`).
    Bias,
    /// An f64 state fed f32 samples with dt = f32(0.001) or from FixedPeriod, against physical time.
    TimeBase(Horizon),
    /// f32 own error and error against physical time to 1e8 steps (1e9 with --long).
    LongHorizon(Horizon),
}

/// Step counts of the long runs.
#[derive(Args, Debug, Clone, Default)]
pub struct Horizon {
    /// To 1e9 steps instead of 1e8.
    #[arg(long)]
    pub long: bool,
    /// Steps (at least 1e3; `1e7` and `10000000` both work); overrides --long and --quick.
    #[arg(long, value_parser = parse_steps)]
    pub steps: Option<u64>,
}

/// Parameters of a work-precision or sensor sweep (empty lists: the defaults).
#[derive(Args, Debug, Clone, Default)]
pub struct Sweep {
    /// Scenes by key (comma-separated).
    #[arg(long = "scene", value_delimiter = ',', value_parser = parse_scene)]
    pub scenes: Vec<String>,
    /// Schemes (comma-separated): Euler, Rk2, Rk3, Rk4, Rk5, ExpMap, Magnus4, Cf4.
    #[arg(long, value_delimiter = ',', value_parser = parse_scheme)]
    pub schemes: Vec<SchemeKind>,
    /// Stabilizers (comma-separated): Off, Normalize, FirstOrder, EveryN (e.g. Every16), Baumgarte (k = 0.5)
    /// or Baumgarte=K (Runge–Kutta schemes only).
    #[arg(long, value_delimiter = ',', value_parser = parse_stab)]
    pub stabilizers: Vec<Stab>,
    /// Input models (comma-separated): hold, linear, history, mid.
    #[arg(long, value_delimiter = ',', value_parser = parse_input)]
    pub inputs: Vec<Input>,
    /// Precisions (comma-separated): f32, f64.
    #[arg(long, value_delimiter = ',', value_parser = parse_precision)]
    pub precision: Vec<Precision>,
    /// Gyro sample rates in Hz (comma-separated).
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..))]
    pub rates: Vec<u32>,
    /// Seconds per run.
    #[arg(long, value_parser = parse_positive)]
    pub horizon: Option<f64>,
}

fn parse_steps(s: &str) -> Result<u64, String> {
    let n: f64 = s.parse().map_err(|e| format!("{e}"))?;
    if (1e3..=1e12).contains(&n) {
        Ok(n.round() as u64)
    } else {
        Err("a step count from 1e3 to 1e12".into())
    }
}

fn parse_positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v > 0.0 && v.is_finite() => Ok(v),
        _ => Err("a positive number of seconds".into()),
    }
}

fn parse_scene(s: &str) -> Result<String, String> {
    let keys: Vec<&str> = scenes::catalogue(0.0).iter().map(|c| c.key()).collect();
    if keys.contains(&s) {
        Ok(s.to_string())
    } else {
        Err(format!("unknown scene; one of {}", keys.join(", ")))
    }
}

fn parse_scheme(s: &str) -> Result<SchemeKind, String> {
    SchemeKind::ALL
        .into_iter()
        .find(|&m| configs::scheme_name(m).eq_ignore_ascii_case(s))
        .ok_or_else(|| {
            let names: Vec<&str> = SchemeKind::ALL
                .iter()
                .map(|&m| configs::scheme_name(m))
                .collect();
            format!("unknown scheme; one of {}", names.join(", "))
        })
}

fn parse_stab(s: &str) -> Result<Stab, String> {
    let bad = || "one of Off, Normalize, FirstOrder, EveryN, Baumgarte, Baumgarte=K".to_string();
    Ok(match s {
        "Off" => Stab::Off,
        "Normalize" => Stab::Normalize,
        "FirstOrder" => Stab::FirstOrder,
        "Baumgarte" => Stab::Baumgarte(0.5),
        _ => {
            if let Some(n) = s.strip_prefix("Every") {
                let n: u32 = n
                    .trim_matches(|c| c == '(' || c == ')')
                    .parse()
                    .map_err(|_| bad())?;
                if n == 0 {
                    return Err("Every(0) is not a stabilizer".into());
                }
                Stab::Every(n)
            } else {
                let k: f64 = s
                    .strip_prefix("Baumgarte=")
                    .ok_or_else(bad)?
                    .parse()
                    .map_err(|_| bad())?;
                Stab::Baumgarte(k)
            }
        }
    })
}

fn parse_input(s: &str) -> Result<Input, String> {
    Input::ALL
        .into_iter()
        .find(|i| i.name() == s)
        .ok_or_else(|| "one of hold, linear, history, mid".into())
}

fn parse_precision(s: &str) -> Result<Precision, String> {
    match s {
        "f32" => Ok(Precision::F32),
        "f64" => Ok(Precision::F64),
        _ => Err("f32 or f64".into()),
    }
}

impl Sweep {
    fn options(&self, quick: bool) -> Options {
        Options {
            scenes: self.scenes.clone(),
            precisions: self.precision.clone(),
            methods: self.schemes.clone(),
            stabs: self.stabilizers.clone(),
            inputs: self.inputs.clone(),
            rates: self.rates.clone(),
            horizon: self.horizon,
            quick,
        }
    }
}

impl Horizon {
    fn steps(&self, quick: bool) -> u64 {
        self.steps.unwrap_or(if quick {
            1_000_000
        } else if self.long {
            1_000_000_000
        } else {
            100_000_000
        })
    }
}

/// Runs the command's studies; their report sections in order.
pub fn run(cli: &Cli, ctx: &mut Ctx) -> Vec<String> {
    let quick = cli.quick;
    let (all, sweep, horizon) = match &cli.command {
        Command::Report(h) => (true, Sweep::default(), h.clone()),
        Command::WorkPrecision(s) | Command::Sensor(s) => (false, s.clone(), Horizon::default()),
        Command::TimeBase(h) | Command::LongHorizon(h) => (false, Sweep::default(), h.clone()),
        _ => (false, Sweep::default(), Horizon::default()),
    };
    let is = |f: fn(&Command) -> bool| all || f(&cli.command);
    let opt = sweep.options(quick);
    let total = horizon.steps(quick);
    let mut sections = Vec::new();
    let mut run = |ctx: &mut Ctx, name: &'static str, f: &mut dyn FnMut(&mut Ctx) -> String| {
        ctx.bar.set_message(name);
        let clock = crate::timing::Clock::start();
        let s = f(ctx);
        let row = clock.row(name);
        ctx.bar.suspend(|| {
            eprintln!(
                "{name}: done in {:.1} s (CPU {:.1} s)",
                row.wall_s, row.cpu_s
            )
        });
        ctx.times.push(row);
        sections.push(s);
    };
    // The rigid bodies' references are tabulated once, long enough for every study.
    let catalogue = scenes::catalogue(opt.horizon.unwrap_or(0.0).max(70.0));
    let coning = scenes::Coning;
    if is(|c| matches!(c, Command::Geiger)) {
        run(ctx, "geiger fig 1", &mut geiger::figure1);
        run(ctx, "geiger fig 2", &mut |c| geiger::figure2(c, quick));
        run(ctx, "baumgarte sweep", &mut |c| {
            baumgarte_sweep::baumgarte_sweep(c, quick)
        });
    }
    if is(|c| matches!(c, Command::Atlas)) {
        run(ctx, "stability atlas", &mut |c| atlas::atlas(c, quick));
    }
    if is(|c| matches!(c, Command::WorkPrecision(_))) {
        if opt.scenes.is_empty() || opt.scenes.iter().any(|s| s == "coning") {
            let mut o = opt.clone();
            o.precisions = vec![Precision::F32];
            run(ctx, "work-precision", &mut |c| {
                work_precision::headline(c, &coning, &o)
            });
        }
        run(ctx, "wp per scene", &mut |c| {
            work_precision::per_scene(c, &catalogue, &opt)
        });
        if opt.scenes.is_empty() {
            run(ctx, "wp stabilizers", &mut |c| {
                work_precision::stabilizers(c, &coning, &opt)
            });
            run(ctx, "wp grid + M4F", &mut |c| {
                work_precision::grid_with_m4f(c, &coning, &opt)
            });
        }
    }
    if is(|c| matches!(c, Command::Scenes)) {
        run(ctx, "scenes", &mut |c| {
            scene_table::scene_table(c, &catalogue, quick)
        });
    }
    if is(|c| matches!(c, Command::Sensor(_))) {
        run(ctx, "sensor realism", &mut |c| {
            sensor::sensor_study(c, &catalogue, &opt)
        });
    }
    if is(|c| matches!(c, Command::ConingDrift)) {
        run(ctx, "coning drift", &mut |c| {
            coning_drift::coning_drift(c, quick)
        });
    }
    if is(|c| matches!(c, Command::Bias)) {
        run(ctx, "bias estimation", &mut |c| bias::bias_study(c, quick));
    }
    if is(|c| matches!(c, Command::TimeBase(_))) {
        run(ctx, "time base", &mut |c| time_base::time_base(c, total));
    }
    if is(|c| matches!(c, Command::LongHorizon(_))) {
        run(ctx, "long horizon", &mut |c| {
            long_horizon::long_horizon(c, total)
        });
    }
    sections
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory as _;

    #[test]
    fn command_line_is_consistent_and_typed() {
        Cli::command().debug_assert();
        let c = Cli::try_parse_from([
            "quatprop-lab",
            "work-precision",
            "--schemes",
            "rk4,ExpMap",
            "--stabilizers",
            "Every16,Baumgarte=0.25",
            "--rates",
            "100,1000",
            "--quick",
        ])
        .unwrap();
        let Command::WorkPrecision(s) = c.command else {
            panic!("{c:?}")
        };
        assert_eq!(s.schemes, vec![SchemeKind::Rk4, SchemeKind::ExpMap]);
        assert_eq!(s.stabilizers, vec![Stab::Every(16), Stab::Baumgarte(0.25)]);
        assert_eq!(s.rates, vec![100, 1000]);
        assert!(c.quick);
        for bad in [
            &["quatprop-lab", "work-precision", "--schemes", "Rk9"][..],
            &["quatprop-lab", "work-precision", "--rates", "0"],
            &["quatprop-lab", "work-precision", "--stabilizers", "Every0"],
            &["quatprop-lab", "sensor", "--scene", "nowhere"],
            &["quatprop-lab", "long-horizon", "--steps", "12"],
            &["quatprop-lab", "geiger", "--steps", "1e6"],
        ] {
            assert!(Cli::try_parse_from(bad).is_err(), "{bad:?}");
        }
        let c = Cli::try_parse_from(["quatprop-lab", "long-horizon", "--steps", "1e7"]).unwrap();
        let Command::LongHorizon(h) = c.command else {
            panic!()
        };
        assert_eq!(h.steps(false), 10_000_000);
    }
}
