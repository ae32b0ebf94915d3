//! The command line (clap): the global options (`--out`, `--quick`, `--full`), `report` (every study in the
//! registry's order) and one sub-command per study, generated from the registry (`studies::ALL`); typed
//! values parsed and checked before anything runs; `quatprop-lab help <command>` for each command's options.
//! Also the argument types several studies share ([`Horizon`], [`Sweep`]) and their value parsers.

use crate::configs::{self, Input, Precision, Stab};
use crate::report::Ctx;
use crate::scenes;
use crate::studies;
use crate::study::Scale;
use clap::{ArgMatches, Args, CommandFactory as _, FromArgMatches, Parser};
use quatprop::scheme::SchemeKind;
use std::ffi::OsString;
use std::path::PathBuf;

/// The global options (every sub-command takes them).
#[derive(Parser, Debug)]
#[command(
    name = "quatprop-lab",
    about = "Host-side lab for quatprop: accuracy against cost, the seed paper's figures, stability, peers",
    version
)]
pub struct Cli {
    /// Output directory (README.md, plots, CSV).
    #[arg(long, global = true, default_value = "report")]
    pub out: PathBuf,
    /// Small grids and horizons: seconds per study (what CI runs).
    #[arg(long, global = true, conflicts_with = "full")]
    pub quick: bool,
    /// The sizes of record (docs/report): the longest grids, horizons and timing runs.
    #[arg(long, global = true)]
    pub full: bool,
}

impl Cli {
    pub fn scale(&self) -> Scale {
        if self.quick {
            Scale::Quick
        } else if self.full {
            Scale::Full
        } else {
            Scale::Default
        }
    }
}

/// The arguments of `report` (handed to the studies that take them: `Study::report_args`).
#[derive(Args, Debug, Clone, Default)]
pub struct ReportArgs {
    #[command(flatten)]
    pub horizon: Horizon,
}

/// The whole command line: the global options, `report`, and every study of the registry.
pub fn command() -> clap::Command {
    let order: Vec<String> = studies::ALL
        .iter()
        .map(|s| format!("  {}: {}", s.name(), s.about()))
        .collect();
    let report = ReportArgs::augment_args(clap::Command::new("report"))
        .about("Every study below: DIR/README.md + plots (SVG, PNG) + CSV.")
        .long_about(format!(
            "Every study, in this order, into DIR/README.md + plots (SVG, PNG) + CSV:\n{}",
            order.join("\n")
        ));
    studies::ALL
        .iter()
        .fold(Cli::command().subcommand(report), |c, s| {
            c.subcommand(s.command())
        })
        .subcommand_required(true)
        .arg_required_else_help(true)
}

/// A parsed command line.
#[derive(Debug)]
pub struct Invocation {
    pub cli: Cli,
    matches: ArgMatches,
}

/// Parses a command line (the program's name first).
pub fn parse_from<I, T>(args: I) -> Result<Invocation, clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let matches = command().try_get_matches_from(args)?;
    let cli = Cli::from_arg_matches(&matches)?;
    Ok(Invocation { cli, matches })
}

impl Invocation {
    /// The sub-command's name and arguments.
    pub fn subcommand(&self) -> (&str, &ArgMatches) {
        self.matches
            .subcommand()
            .expect("clap requires a sub-command")
    }

    /// Runs the sub-command: `report` runs every study in the registry's order.
    pub fn run(&self, ctx: &mut Ctx) -> Result<(), clap::Error> {
        match self.subcommand() {
            ("report", m) => {
                let report = ReportArgs::from_arg_matches(m)?;
                for s in studies::ALL {
                    s.run_in_report(ctx, &report);
                }
                Ok(())
            }
            (name, m) => studies::ALL
                .iter()
                .find(|s| s.name() == name)
                .expect("every sub-command but report is a study of the registry")
                .run_matches(ctx, m),
        }
    }
}

/// Step counts of the long runs.
#[derive(Args, Debug, Clone, Default)]
pub struct Horizon {
    /// To 1e9 steps (instead of 1e7 at the default scale, 1e8 with --full).
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

impl Horizon {
    /// Steps at the default scale: four decades, the last two for the growth exponents.
    pub const DEFAULT_STEPS: u64 = 10_000_000;

    /// The step count: `--steps`, else by scale (`--long`: 1e9 unless `--quick`).
    pub fn steps(&self, scale: Scale) -> u64 {
        self.steps.unwrap_or(match scale {
            Scale::Quick => 1_000_000,
            _ if self.long => 1_000_000_000,
            Scale::Default => Self::DEFAULT_STEPS,
            Scale::Full => 100_000_000,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sweep_of(args: &[&str]) -> (Scale, Sweep) {
        let inv = parse_from(args).unwrap();
        let (name, m) = inv.subcommand();
        assert_eq!(name, args[1]);
        (inv.cli.scale(), Sweep::from_arg_matches(m).unwrap())
    }

    #[test]
    fn command_line_is_consistent_and_typed() {
        command().debug_assert();
        let (scale, s) = sweep_of(&[
            "quatprop-lab",
            "work-precision",
            "--schemes",
            "rk4,ExpMap",
            "--stabilizers",
            "Every16,Baumgarte=0.25",
            "--rates",
            "100,1000",
            "--quick",
        ]);
        assert_eq!(s.schemes, vec![SchemeKind::Rk4, SchemeKind::ExpMap]);
        assert_eq!(s.stabilizers, vec![Stab::Every(16), Stab::Baumgarte(0.25)]);
        assert_eq!(s.rates, vec![100, 1000]);
        assert_eq!(scale, Scale::Quick);
        for bad in [
            &["quatprop-lab", "work-precision", "--schemes", "Rk9"][..],
            &["quatprop-lab", "work-precision", "--rates", "0"],
            &["quatprop-lab", "work-precision", "--stabilizers", "Every0"],
            &["quatprop-lab", "sensor", "--scene", "nowhere"],
            &["quatprop-lab", "long-horizon", "--steps", "12"],
            &["quatprop-lab", "geiger", "--steps", "1e6"],
            &["quatprop-lab", "report", "--quick", "--full"],
            &["quatprop-lab", "no-such-study"],
            &["quatprop-lab"],
        ] {
            assert!(parse_from(bad).is_err(), "{bad:?}");
        }
        let inv = parse_from(["quatprop-lab", "long-horizon", "--steps", "1e7"]).unwrap();
        let h = Horizon::from_arg_matches(inv.subcommand().1).unwrap();
        assert_eq!(h.steps(Scale::Full), 10_000_000);
        // The global options work before and after the sub-command.
        let inv = parse_from(["quatprop-lab", "--full", "report", "--out", "x", "--long"]).unwrap();
        assert_eq!(inv.cli.scale(), Scale::Full);
        assert_eq!(inv.cli.out, PathBuf::from("x"));
        let r = ReportArgs::from_arg_matches(inv.subcommand().1).unwrap();
        assert_eq!(r.horizon.steps(Scale::Full), 1_000_000_000);
        assert_eq!(r.horizon.steps(Scale::Quick), 1_000_000);
        let inv = parse_from(["quatprop-lab", "report"]).unwrap();
        assert_eq!(inv.cli.scale(), Scale::Default);
        assert_eq!(inv.cli.out, PathBuf::from("report"));
    }

    /// Every study of the registry is a sub-command, with its one-line description as its help, beside
    /// `report`; nothing else is.
    #[test]
    fn sub_commands_are_the_registry() {
        let names: Vec<String> = command()
            .get_subcommands()
            .map(|c| c.get_name().to_string())
            .collect();
        let mut expected = vec!["report".to_string()];
        expected.extend(studies::ALL.iter().map(|s| s.name().to_string()));
        assert_eq!(names, expected);
        let c = command();
        let report = c.find_subcommand("report").unwrap();
        assert_eq!(
            report.get_about().map(|a| a.to_string()).as_deref(),
            Some("Every study below: DIR/README.md + plots (SVG, PNG) + CSV.")
        );
        for s in studies::ALL {
            let sub = c.find_subcommand(s.name()).unwrap();
            assert_eq!(
                sub.get_about().map(|a| a.to_string()),
                Some(s.about().to_string())
            );
            assert!(
                parse_from(["quatprop-lab", s.name()]).is_ok(),
                "{}",
                s.name()
            );
        }
    }
}
