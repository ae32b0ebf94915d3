//! The command line (clap): the global options (`--out`, `--quick`, `--full`), `report` (every study in the
//! registry's order) and one sub-command per study, generated from the registry (`studies::ALL`); typed
//! values parsed and checked before anything runs (the shared argument types: `args.rs`); `quatprop-lab help
//! <command>` for each command's options. After the run, [`Invocation::finish`] writes the report and, after
//! `report`, checks its files against the registry.

use crate::args::ReportArgs;
use crate::report::{self, Ctx};
use crate::scale::Scale;
use crate::{outputs, studies};
use clap::{ArgMatches, Args, CommandFactory as _, FromArgMatches, Parser};
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

    /// After [`Invocation::run`]: writes the Markdown and checks every figure it links
    /// ([`report::finish`]) and, after `report` (the lab report's README.md, not a study's page of its
    /// own), the files against the registry ([`outputs::check`]); the failures.
    pub fn finish(&self, ctx: &mut Ctx, command: &str) -> Vec<String> {
        let mut failures = report::finish(ctx, command);
        if self.subcommand().0 == "report" && !ctx.writes_page() {
            failures.extend(outputs::check(ctx.out(), ctx.files(), studies::ALL));
        }
        failures
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::args::{Horizon, Sweep};
    use crate::configs::Stab;
    use quatprop::scheme::SchemeKind;
    use std::collections::BTreeSet;

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

    /// The quick report, run in-process as `main` runs it: it passes its own [`check`], and the directory
    /// holds exactly the files the registry declares (README.md and the optional files aside), every CSV
    /// with rows.
    #[test]
    fn quick_report_writes_exactly_the_declared_files() {
        let dir = crate::table::scratch_dir("quatprop-lab-quick");
        let out = dir.to_str().unwrap();
        let inv = parse_from(["quatprop-lab", "report", "--quick", "--out", out]).unwrap();
        let mut ctx = Ctx::new(dir.clone(), inv.cli.scale());
        inv.run(&mut ctx).unwrap();
        let failures = inv.finish(&mut ctx, "report --quick");
        assert!(failures.is_empty(), "{failures:?}");
        let written: BTreeSet<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        let declared = outputs::declared(studies::ALL);
        let mut expected: BTreeSet<String> = declared
            .iter()
            .filter(|(_, optional)| !optional)
            .map(|(f, _)| f.clone())
            .collect();
        // The report's own files: its README and CSV files (run times, the summary).
        expected.insert("README.md".to_string());
        expected.extend(outputs::REPORT_CSV.iter().map(|c| c.file.to_string()));
        let optional: BTreeSet<String> = declared
            .iter()
            .filter(|(_, optional)| *optional)
            .map(|(f, _)| f.clone())
            .collect();
        let extra: Vec<&String> = written
            .difference(&expected)
            .filter(|f| !optional.contains(*f))
            .collect();
        let missing: Vec<&String> = expected.difference(&written).collect();
        assert!(extra.is_empty(), "written, not declared: {extra:?}");
        assert!(missing.is_empty(), "declared, not written: {missing:?}");
        for f in written.iter().filter(|f| f.ends_with(".csv")) {
            let rows = outputs::csv_file(studies::ALL, f)
                .unwrap()
                .read_strict(&dir)
                .unwrap();
            assert!(rows > 0, "{f}: no rows");
        }
        let tables = outputs::check_tables(&dir, studies::ALL).unwrap_or_else(|e| panic!("{e}"));
        assert!(tables >= 15, "{tables} tables");
        // The check catches a missing file.
        std::fs::remove_file(dir.join("time_base.png")).unwrap();
        assert!(outputs::check(&dir, &[], studies::ALL)
            .iter()
            .any(|f| f.contains("time_base.png")));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
