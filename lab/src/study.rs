//! What a study is: one file under `studies/` implementing [`Study`], and one line in the registry
//! (`studies/mod.rs`). The registry is the only list: the command line's sub-commands, `report`'s order,
//! the CSV files the tests read strictly and the tables they check all come from it.
//!
//! A study declares its sub-command (name, one-line description, clap arguments), the files it writes (its
//! CSV files with their row types, its figures) and runs through a [`Ctx`]: `ctx.section(name, ...)` times one
//! part and adds its Markdown to the report, `ctx.table` / `ctx.rows` write CSV, `ctx.plot` writes a figure,
//! and `ctx.scale` says how big to make it (`Scale`).

use crate::args::ReportArgs;
use crate::report::Ctx;
use crate::table::{self, Csv, Table};
use clap::{ArgMatches, Args, FromArgMatches};
use std::path::Path;

/// The arguments of a study that has none.
#[derive(Args, Debug, Clone, Default)]
pub struct NoArgs {}

/// A CSV file a study writes, with its row type: how to read it strictly and, for a table, how the report
/// renders it.
#[derive(Clone, Copy)]
pub struct CsvFile {
    /// The file name in the report's directory (the row type's [`Csv::FILE`]).
    pub file: &'static str,
    read: fn(&Path) -> Result<usize, String>,
    render: Option<Render>,
    /// Written only when what it shows exists (the Cortex-M4F table needs `firmware/bench-m4f.csv`).
    pub optional: bool,
}

/// Renders a table from its CSV file in a directory.
type Render = fn(&Path) -> Result<String, String>;

fn read_rows<R: Csv>(dir: &Path) -> Result<usize, String> {
    table::read::<R>(&dir.join(R::FILE)).map(|r| r.len())
}

impl CsvFile {
    /// A data file (not shown as a table).
    pub const fn data<R: Csv>() -> Self {
        Self {
            file: R::FILE,
            read: read_rows::<R>,
            render: None,
            optional: false,
        }
    }

    /// A file the report also shows as a table.
    pub const fn table<R: Table>() -> Self {
        Self {
            file: R::FILE,
            read: read_rows::<R>,
            render: Some(table::rendered::<R>),
            optional: false,
        }
    }

    /// Written only when its input exists.
    pub const fn optional(self) -> Self {
        Self {
            optional: true,
            ..self
        }
    }

    /// Reads the file in `dir` strictly as its row type; the number of rows.
    pub fn read_strict(&self, dir: &Path) -> Result<usize, String> {
        (self.read)(dir)
    }

    /// The table as the report shows it (markers included), from the file in `dir`; `None` for a data file.
    pub fn render(&self, dir: &Path) -> Option<Result<String, String>> {
        self.render.map(|r| r(dir))
    }
}

/// A study of the lab: one sub-command, one or more sections of the report.
pub trait Study: Sync + 'static {
    /// Its sub-command's arguments (clap derive; [`NoArgs`] for none).
    type Args: Args + FromArgMatches;
    /// The sub-command (kebab-case).
    const NAME: &'static str;
    /// One line: the sub-command's help and the study's line in `quatprop-lab help` and lab/README.md.
    const ABOUT: &'static str;
    /// Every CSV file it writes, with its row type.
    const CSV: &'static [CsvFile];
    /// The figures it writes in a report (file stems; each as `.svg` and `.png`; default: none).
    fn figures(&self) -> Vec<String> {
        Vec::new()
    }
    /// The arguments it runs with in `report` (default: its sub-command's defaults, as with no argument).
    fn report_args(&self, _report: &ReportArgs) -> Self::Args {
        defaults()
    }
    /// Runs the study: its files through `ctx`, its report sections through `ctx.section`.
    fn run(&self, ctx: &mut Ctx, args: &Self::Args);
}

/// Arguments as an empty command line gives them (clap's defaults).
pub fn defaults<A: Args + FromArgMatches>() -> A {
    let matches = A::augment_args(clap::Command::new("defaults"))
        .no_binary_name(true)
        .try_get_matches_from(Vec::<String>::new())
        .expect("a study's arguments all have defaults");
    A::from_arg_matches(&matches).expect("a study's arguments all have defaults")
}

/// A [`Study`] behind a reference, for the registry (its arguments parsed from the command line).
pub trait AnyStudy: Sync {
    fn name(&self) -> &'static str;
    fn about(&self) -> &'static str;
    /// Its sub-command with its arguments.
    fn command(&self) -> clap::Command;
    /// Runs it with the arguments of its sub-command.
    fn run_matches(&self, ctx: &mut Ctx, matches: &ArgMatches) -> Result<(), clap::Error>;
    /// Runs it as part of `report`.
    fn run_in_report(&self, ctx: &mut Ctx, report: &ReportArgs);
    fn csv(&self) -> &'static [CsvFile];
    fn figures(&self) -> Vec<String>;
}

impl<S: Study> AnyStudy for S {
    fn name(&self) -> &'static str {
        S::NAME
    }
    fn about(&self) -> &'static str {
        S::ABOUT
    }
    fn command(&self) -> clap::Command {
        // After the arguments: their struct's doc comment would otherwise be the about.
        S::Args::augment_args(clap::Command::new(S::NAME))
            .about(S::ABOUT)
            .long_about(None)
    }
    fn run_matches(&self, ctx: &mut Ctx, matches: &ArgMatches) -> Result<(), clap::Error> {
        let args = S::Args::from_arg_matches(matches)?;
        self.run(ctx, &args);
        Ok(())
    }
    fn run_in_report(&self, ctx: &mut Ctx, report: &ReportArgs) {
        let args = self.report_args(report);
        self.run(ctx, &args);
    }
    fn csv(&self) -> &'static [CsvFile] {
        S::CSV
    }
    fn figures(&self) -> Vec<String> {
        Study::figures(self)
    }
}
